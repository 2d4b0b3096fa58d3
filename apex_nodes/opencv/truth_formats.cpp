// loadTruth: which reader a file or folder goes to, and what the readers of labelling tools' files
// share (a frame's stamp from its image's name, a label's digit, errors naming the file).
#include "truth_formats.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

namespace apex_nodes {
namespace truth_formats {
namespace fs = std::filesystem;

void fail(const std::string& file, const std::string& what) {
  throw std::invalid_argument("the ground truth '" + file + "': " + what);
}

namespace {

bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)); }

/** `name` without its folders ('/' or a Windows tool's '\') and without an extension: what
 *  follows the last point if that is not all digits (a point before digits is the stamp's). */
std::string stem(const std::string& name) {
  std::string s = name.substr(name.find_last_of("/\\") + 1);
  const auto dot = s.rfind('.');
  if (dot != std::string::npos && !std::all_of(s.begin() + dot + 1, s.end(), isDigit)) s.erase(dot);
  return s;
}

/** The digits that end `s` before `end`, as [begin, end). */
std::size_t digitsBefore(const std::string& s, std::size_t end) {
  while (end > 0 && isDigit(s[end - 1])) --end;
  return end;
}

/** Seconds and up to nine decimals (the stamp as ROS prints it) as ns; -1 past ROS's 32-bit seconds. */
long long fromSeconds(const std::string& sec, std::string frac) {
  if (sec.size() > 10 || frac.size() > 9 || std::stoull(sec) > 0xffffffffULL) return -1;
  frac.resize(9, '0');
  return static_cast<long long>(std::stoull(sec) * 1000000000ULL + std::stoull(frac));
}

}  // namespace

std::uint64_t stampOfImage(const std::string& image, const std::string& file, const std::string& where) {
  const std::string s = stem(image);
  const std::size_t frac = digitsBefore(s, s.size());  // the digits that end the name
  const bool point = frac > 0 && frac < s.size() && s[frac - 1] == '.';
  const std::size_t sec = point ? digitsBefore(s, frac - 1) : frac;  // the digits before the point
  long long ns = -1;
  if (point && sec < frac - 1) ns = fromSeconds(s.substr(sec, frac - 1 - sec), s.substr(frac));
  else if (s.size() - frac >= 10 && s.size() - frac <= 19)
    ns = static_cast<long long>(std::stoull(s.substr(frac)));  // past 2^63: < 0
  if (ns <= 0)
    fail(file, where + ": the image name '" + image + "' holds no stamp: name each image after its frame's stamp, " +
                   "frame_<sec>.<nsec>.png or <nanoseconds>.png (a frame number is not a stamp)");
  return static_cast<std::uint64_t>(ns);
}

TruthSign signOf(double x0, double y0, double x1, double y1, const std::string& label) {
  const int left = cvRound(std::min(x0, x1)), top = cvRound(std::min(y0, y1));
  const cv::Rect box(left, top, cvRound(std::max(x0, x1)) - left, cvRound(std::max(y0, y1)) - top);
  std::string l = label;
  l.erase(0, l.find_first_not_of(" \t"));
  l.erase(l.find_last_not_of(" \t") + 1);
  return {box, l.size() == 1 && isDigit(l[0]) ? l[0] - '0' : -1};
}

std::vector<TruthSign>& newFrame(Truth& t, std::uint64_t stamp, const std::string& file, const std::string& where) {
  auto [it, added] = t.frames.emplace(stamp, std::vector<TruthSign>{});
  if (!added) fail(file, where + ": a second image of the frame at " + std::to_string(stamp) + " ns (two images, one stamp)");
  return it->second;
}

void finishLabelled(Truth& t, const std::string& source) {
  if (t.frames.empty()) fail(source, "lists no frames");
  t.has_digits = std::all_of(t.frames.begin(), t.frames.end(), [](const auto& f) {
    return std::all_of(f.second.begin(), f.second.end(), [](const TruthSign& s) { return s.digit >= 0; });
  });
}

YAML::Node loadJson(const std::string& file) {
  try {
    return YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    fail(file, "cannot be read");
  } catch (const YAML::Exception& e) {
    fail(file, e.what());
  }
}

YAML::Node need(const YAML::Node& node, const char* key, const std::string& file, const std::string& where) {
  if (!node.IsMap() || !node[key]) fail(file, where + ": no '" + key + "'");
  return node[key];
}

double number(const YAML::Node& node, const std::string& file, const std::string& where) {
  double v = NAN;  // (decode leaves 0 in v when the text is not a number)
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, v) || !std::isfinite(v))
    fail(file, where + ": '" + (node.IsScalar() ? node.Scalar() : "(not a value)") + "' is not a number");
  return v;
}

std::string text(const YAML::Node& node, const std::string& file, const std::string& where) {
  if (!node.IsScalar()) fail(file, where + ": not a text");
  return node.Scalar();
}

namespace {

std::string extension(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

/** One labelme file (the folder's kind of .json); a COCO file has folders of its own. */
void readLabelmeFile(const std::string& file, Truth& t) {
  const YAML::Node root = loadJson(file);
  if (root.IsMap() && root["shapes"]) return readLabelme(root, file, t);
  if (root.IsMap() && root["images"]) fail(file, "a COCO file: give the file itself as the ground truth, not its folder");
  fail(file, "not a labelme file: no 'shapes'");
}

/** A folder of one tool's per-image files: .xml (VOC), .json (labelme) or .txt (YOLO). */
Truth readFolder(const std::string& dir) {
  std::map<std::string, std::vector<std::string>> kinds;  // extension: files, in name order
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string(), ext = extension(e.path());
    if (e.is_regular_file() && name[0] != '.' && name != "classes.txt" && (ext == ".xml" || ext == ".json" || ext == ".txt"))
      kinds[ext].push_back(e.path().string());
  }
  if (kinds.empty()) fail(dir, "a folder without labels (.xml of Pascal VOC, .json of labelme, .txt of YOLO)");
  if (kinds.size() > 1)
    fail(dir,
         "a folder with " + kinds.begin()->first + " and " + kinds.rbegin()->first + " files: keep one tool's labels per folder");
  auto& [ext, files] = *kinds.begin();
  std::sort(files.begin(), files.end());
  Truth t;
  for (const auto& f : files) {
    if (ext == ".xml") readVoc(f, t);
    if (ext == ".json") readLabelmeFile(f, t);
    if (ext == ".txt") readYolo(f, yoloClasses(f), t);
  }
  finishLabelled(t, dir);
  return t;
}

/** A .json: COCO (images and annotations) or one labelme file (shapes), by its keys. */
Truth readJson(const std::string& file) {
  const YAML::Node root = loadJson(file);
  if (root.IsMap() && root["images"]) return readCoco(root, file);
  Truth t;
  if (!root.IsMap() || !root["shapes"]) fail(file, "neither COCO ('images', 'annotations') nor labelme ('shapes')");
  readLabelme(root, file, t);
  finishLabelled(t, file);
  return t;
}

}  // namespace
}  // namespace truth_formats

Truth loadTruth(const std::string& path) {
  using namespace truth_formats;
  std::error_code ec;
  if (fs::is_directory(path, ec)) return readFolder(path);
  const std::string ext = extension(path);
  if (ext == ".json") return readJson(path);
  Truth t;
  if (ext == ".xml") readVoc(path, t);
  else if (ext == ".txt") readYolo(path, yoloClasses(path), t);
  else return readDemoYaml(path);  // .yaml, .yml, and any other name as before
  finishLabelled(t, path);
  return t;
}

}  // namespace apex_nodes
