// Ground truth from YOLO files (one per image, named as the image: a line "class cx cy w h" per
// box, normalised to the image's size, read from the image beside it; class names in classes.txt).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "truth_formats.hpp"

namespace apex_nodes {
namespace truth_formats {
namespace fs = std::filesystem;
namespace {

/** Where the image of a labels file may be: beside it, or in the images/ folder of a labels/ one
 *  (Ultralytics' dataset/labels/train/x.txt for dataset/images/train/x.jpg). */
std::vector<fs::path> imageFolders(const fs::path& labels) {
  const fs::path dir = labels.parent_path();
  std::vector<fs::path> parts(dir.begin(), dir.end());
  const auto last = std::find(parts.rbegin(), parts.rend(), fs::path("labels"));
  if (last == parts.rend()) return {dir};
  *last = "images";
  fs::path images;
  for (const auto& p : parts) images /= p;
  return {dir, images};
}

cv::Size imageSize(const std::string& file) {
  static const char* const kExtensions[] = {".png", ".jpg", ".jpeg", ".bmp",  ".tif", ".tiff", ".webp", ".pgm",
                                            ".ppm", ".PNG", ".JPG",  ".JPEG", ".BMP", ".TIF",  ".TIFF"};
  const std::string stem = fs::path(file).stem().string();
  std::string looked;
  for (const auto& dir : imageFolders(file)) {
    for (const char* ext : kExtensions) {
      const fs::path image = dir / (stem + ext);
      if (!fs::is_regular_file(image)) continue;
      const cv::Mat m = cv::imread(image.string(), cv::IMREAD_UNCHANGED);
      if (m.empty()) fail(file, "its image '" + image.string() + "' does not decode");
      return m.size();
    }
    looked += (looked.empty() ? "" : " or ") + dir.string();
  }
  fail(file, "no image " + stem + ".png (.jpg, ...) in " + looked + " to give the size its boxes are fractions of");
}

}  // namespace

std::vector<std::string> yoloClasses(const std::string& file) {
  const fs::path dir = fs::path(file).parent_path();
  for (const auto& candidate : {dir / "classes.txt", dir.parent_path() / "classes.txt"}) {
    std::ifstream in(candidate);
    if (!in) continue;
    std::vector<std::string> names;
    for (std::string name; std::getline(in, name);) {
      name.erase(name.find_last_not_of(" \t\r") + 1);
      if (!name.empty()) names.push_back(name);
    }
    return names;
  }
  return {};
}

void readYolo(const std::string& file, const std::vector<std::string>& classes, Truth& t) {
  std::ifstream in(file);
  if (!in) fail(file, "cannot be read");
  auto& signs = newFrame(t, stampOfImage(fs::path(file).filename().string(), file, "its name"), file, "its name");
  cv::Size size;
  int n = 0;
  for (std::string text; std::getline(in, text);) {
    const std::string at = "line " + std::to_string(++n);
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream fields(text);
    long cls = -1;
    double cx, cy, w, h;
    std::string more;
    if (!(fields >> cls >> cx >> cy >> w >> h) || (fields >> more) || cls < 0)
      fail(file, at + ": '" + text + "' is not 'class cx cy width height'");
    if (!classes.empty() && cls >= static_cast<long>(classes.size()))
      fail(file, at + ": class " + std::to_string(cls) + ", but classes.txt names " + std::to_string(classes.size()));
    if (std::min({cx, cy, w, h}) < 0 || std::max({cx, cy, w, h}) > 1)
      fail(file, at + ": '" + text + "': the centre and size are fractions of the image's, 0 to 1");
    if (size.empty()) size = imageSize(file);
    const std::string label = classes.empty() ? std::to_string(cls) : classes[cls];
    signs.push_back(signOf((cx - w / 2) * size.width, (cy - h / 2) * size.height, (cx + w / 2) * size.width,
                           (cy + h / 2) * size.height, label));
  }
}

}  // namespace truth_formats
}  // namespace apex_nodes
