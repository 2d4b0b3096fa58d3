// apex_make_bag's inputs (make_bag_sources.hpp): frames, encodings, stamps.
#include "make_bag_sources.hpp"

#include <glob.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <opencv2/videoio/registry.hpp>
#include <regex>
#include <stdexcept>
#include <utility>

namespace apex_tools {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& message) { throw std::runtime_error(message); }

const char* kImageNames = "bmp dib jpeg jpg jpe jp2 png webp pbm pgm ppm pxm pnm pfm sr ras tiff tif exr hdr pic";

/** A file named as one of the images cv::imread reads (by its extension, in any case). */
bool isImageName(const fs::path& path) {
  std::string ext = path.extension().string();
  if (ext.size() < 2) return false;
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return (" " + std::string(kImageNames) + " ").find(" " + ext.substr(1) + " ") != std::string::npos;
}

std::vector<std::string> folderImages(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && isImageName(entry.path()) && entry.path().filename().string()[0] != '.')
      files.push_back(entry.path().string());
  if (files.empty()) fail("the folder '" + folder + "' holds no images (" + kImageNames + ")");
  return files;
}

/** The files (not folders) `pattern` matches, as the shell would (~ too). */
std::vector<std::string> globFiles(const std::string& pattern) {
  glob_t found{};
  const int r = ::glob(pattern.c_str(), GLOB_TILDE, nullptr, &found);
  std::vector<std::string> files;
  for (std::size_t i = 0; r == 0 && i < found.gl_pathc; ++i)
    if (fs::is_regular_file(found.gl_pathv[i])) files.emplace_back(found.gl_pathv[i]);
  globfree(&found);
  if (files.empty()) fail("no files match '" + pattern + "'");
  return files;
}

class ImageFiles : public FrameSource {
 public:
  ImageFiles(std::string name, std::vector<std::string> files, int flags)
      : FrameSource(std::move(name)), files_(std::move(files)), flags_(flags) {}
  bool next(cv::Mat& frame) override {
    if (next_ == files_.size()) return false;
    const std::string& file = files_[next_++];
    frame = cv::imread(file, flags_);
    if (frame.empty()) fail(std::ifstream(file) ? "'" + file + "' does not decode as an image" : "cannot read '" + file + "'");
    return true;
  }
  long long total() const override { return static_cast<long long>(files_.size()); }
  std::size_t rest() override { return files_.size() - std::exchange(next_, files_.size()); }
  std::string where() const override { return "'" + files_[next_ ? next_ - 1 : 0] + "'"; }

 private:
  std::vector<std::string> files_;
  int flags_;
  std::size_t next_ = 0;
};

class VideoFile : public FrameSource {
 public:
  explicit VideoFile(const std::string& path) : FrameSource(path) {
    namespace logging = cv::utils::logging;  // quiet: each backend that cannot open it says so at length
    const logging::LogLevel level = logging::setLogLevel(logging::LOG_LEVEL_SILENT);
    // Each file backend in turn, but gphoto2's: it is for cameras on USB, and it leaks libusb's
    // device list (5,000 allocations under LeakSanitizer) when asked to open a file it cannot.
    for (const auto backend : cv::videoio_registry::getStreamBackends())
      if (backend != cv::CAP_GPHOTO2 && video_.open(path, backend)) break;
    logging::setLogLevel(level);
    if (!video_.isOpened()) fail("OpenCV cannot open '" + path + "' as a video (nor is it named as an image)");
    const double n = video_.get(cv::CAP_PROP_FRAME_COUNT), fps = video_.get(cv::CAP_PROP_FPS);
    estimate_ = n >= 1 ? std::llround(n) : -1;
    fps_ = std::isfinite(fps) && fps > 0 ? fps : 0;
  }
  bool next(cv::Mat& frame) override {
    if (!video_.read(frame)) return false;  // the end, or a frame that does not decode: OpenCV does not tell them apart
    ++read_;
    return true;
  }
  long long total() const override { return -1; }
  long long estimate() const override { return estimate_; }
  double fps() const override { return fps_; }
  std::size_t rest() override {
    std::size_t n = 0;
    while (video_.grab()) ++n;
    return n;
  }
  std::string where() const override { return "'" + name() + "' frame " + std::to_string(read_ ? read_ - 1 : 0); }

 private:
  cv::VideoCapture video_;
  long long estimate_;
  double fps_;
  std::size_t read_ = 0;
};

std::string joined(const std::vector<std::string>& specs) {
  std::string all;
  for (const auto& s : specs) all += (all.empty() ? "" : " ") + s;
  return all;
}

/** Where `frame`'s pixels stand among gray, BGR and BGRA: 0, 1, 2. */
int channelIndex(const cv::Mat& frame, const std::string& where) {
  switch (frame.channels()) {
    case 1:
      return 0;
    case 3:
      return 1;
    case 4:
      return 2;
    default:
      fail(where + " has " + std::to_string(frame.channels()) + " channels: not gray, colour or colour with alpha");
  }
}

}  // namespace

std::unique_ptr<FrameSource> openFrameSource(const std::vector<std::string>& specs, int flags) {
  if (specs.empty()) fail("no input");
  std::vector<std::string> files;
  for (const auto& spec : specs) {
    std::error_code ec;
    const fs::file_status status = fs::status(spec, ec);
    std::vector<std::string> more;
    if (!fs::exists(status) && spec.find_first_of("*?[") != std::string::npos) more = globFiles(spec);
    else if (!fs::exists(status)) fail("'" + spec + "' does not exist");
    else if (fs::is_directory(status)) more = folderImages(spec);
    else if (isImageName(spec)) more = {spec};
    else if (specs.size() == 1) return std::make_unique<VideoFile>(spec);
    else fail("'" + spec + "' is not named as an image (" + kImageNames + "): a video is given on its own");
    files.insert(files.end(), more.begin(), more.end());
  }
  std::sort(files.begin(), files.end(), naturalLess);
  return std::make_unique<ImageFiles>(joined(specs), std::move(files), flags);
}

bool naturalLess(const std::string& a, const std::string& b) {
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (!digit(a[i]) || !digit(b[j])) {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i, ++j;
      continue;
    }
    std::size_t ie = i, je = j;  // the runs of digits; then their numbers, leading zeros aside
    while (ie < a.size() && digit(a[ie])) ++ie;
    while (je < b.size() && digit(b[je])) ++je;
    while (i + 1 < ie && a[i] == '0') ++i;
    while (j + 1 < je && b[j] == '0') ++j;
    if (ie - i != je - j) return ie - i < je - j;  // fewer digits: a smaller number
    if (const int c = a.compare(i, ie - i, b, j, je - j)) return c < 0;
    i = ie, j = je;
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return a < b;  // the same but for leading zeros: some fixed order all the same
}

const std::vector<std::string>& frameEncodings() {
  static const std::vector<std::string> all = {"bgr8", "rgb8", "bgra8", "rgba8", "mono8", "mono16", "16UC1"};
  return all;
}

int readFlags(const std::string& encoding) {
  if (encoding == "mono8") return cv::IMREAD_GRAYSCALE;
  if (encoding == "mono16" || encoding == "16UC1") return cv::IMREAD_ANYDEPTH;
  if (encoding == "bgra8" || encoding == "rgba8") return cv::IMREAD_UNCHANGED;
  return cv::IMREAD_COLOR;
}

cv::Mat toEncoding(const cv::Mat& frame, const std::string& encoding, const std::string& where) {
  if (encoding == "mono16" || encoding == "16UC1") {
    if (frame.type() != CV_16UC1) fail(where + " is not a 16-bit gray image, which --encoding " + encoding + " needs");
    return frame;
  }
  if (frame.depth() != CV_8U) fail(where + " has more than 8 bits a pixel: --encoding mono16 keeps them (gray)");
  using Codes = std::array<int, 3>;  // the conversion from gray, BGR, BGRA; -1: none
  static const std::map<std::string, Codes> codes = {{"mono8", {-1, cv::COLOR_BGR2GRAY, cv::COLOR_BGRA2GRAY}},
                                                     {"bgr8", {cv::COLOR_GRAY2BGR, -1, cv::COLOR_BGRA2BGR}},
                                                     {"rgb8", {cv::COLOR_GRAY2RGB, cv::COLOR_BGR2RGB, cv::COLOR_BGRA2RGB}},
                                                     {"bgra8", {cv::COLOR_GRAY2BGRA, cv::COLOR_BGR2BGRA, -1}},
                                                     {"rgba8", {cv::COLOR_GRAY2RGBA, cv::COLOR_BGR2RGBA, cv::COLOR_BGRA2RGBA}}};
  const int code = codes.at(encoding)[channelIndex(frame, where)];
  if (code < 0) return frame;
  cv::Mat out;
  cv::cvtColor(frame, out, code);
  return out;
}

std::int64_t nanoseconds(const std::string& seconds) {
  constexpr std::int64_t kBillion = 1000000000, kEnd = 4294967296;  // ROS stamps: 32-bit seconds
  static const std::regex decimal(R"((\d{1,10})(?:\.(\d*))?)");
  std::smatch m;
  if (std::regex_match(seconds, m, decimal)) {
    const std::int64_t whole = std::stoll(m[1].str());
    std::string fraction = m[2].str().substr(0, 9);
    fraction.resize(9, '0');
    return whole < kEnd ? whole * kBillion + std::stoll(fraction) : -1;
  }
  char* end = nullptr;
  const double s = std::strtod(seconds.c_str(), &end);
  if (seconds.empty() || *end || !std::isfinite(s) || s < 0 || s >= static_cast<double>(kEnd)) return -1;
  return std::llround(s * 1e9);
}

std::vector<std::int64_t> readTimestamps(const std::string& file) {
  std::ifstream in(file);
  if (!in) fail("cannot read the timestamps file '" + file + "'");
  std::vector<std::int64_t> stamps;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::size_t from = line.find_first_not_of(" \t\r");
    if (from == std::string::npos || line[from] == '#') continue;
    const std::string text = line.substr(from, line.find_first_of(" \t\r,", from) - from);
    const std::int64_t ns = nanoseconds(text);
    const std::string at = "'" + file + "' line " + std::to_string(n) + ": ";
    if (ns < 0) fail(at + "'" + text + "' is not a time in seconds (from 0 to 4294967295)");
    if (!stamps.empty() && ns <= stamps.back()) fail(at + text + " is not later than the stamp before it");
    stamps.push_back(ns);
  }
  if (stamps.empty()) fail("the timestamps file '" + file + "' holds no timestamps");
  return stamps;
}

FrameClock::FrameClock(const std::string& file, std::int64_t start, double rate) : file_(file), start_(start), rate_(rate) {
  if (file_.empty()) return;
  stamps_ = readTimestamps(file_);
  const std::int64_t shift = start >= 0 ? start - stamps_.front() : 0;
  for (auto& s : stamps_) s += shift;
  if (stamps_.front() <= 0) fail("'" + file_ + "': the first stamp is 0, which ROS reads as none: give --start to shift them");
}

std::int64_t FrameClock::at(std::size_t i, const std::string& source) const {
  if (file_.empty()) return start_ + std::llround(static_cast<double>(i) * 1e9 / rate_);
  if (i >= stamps_.size()) mismatch(source, "more");
  return stamps_[i];
}

void FrameClock::requireLength(std::size_t frames, bool all, const std::string& source) const {
  if (!file_.empty() && (all ? stamps_.size() != frames : stamps_.size() < frames)) mismatch(source, std::to_string(frames));
}

void FrameClock::mismatch(const std::string& source, const std::string& frames) const {
  fail("'" + file_ + "' has " + std::to_string(stamps_.size()) + " timestamps but '" + source + "' has " + frames +
       " frames: give one per frame");
}

}  // namespace apex_tools
