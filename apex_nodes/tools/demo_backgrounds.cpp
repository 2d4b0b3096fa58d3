// Real backgrounds for apex_make_demo_bag: opencv-doc's photographs, scaled once, cropped per frame.
#include "demo_backgrounds.hpp"

#include <algorithm>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace apex_tools {

namespace {

// Room beyond the frame: even a photo of the frame's size gives crops at many places.
constexpr double kCover = 1.3;

}  // namespace

const std::vector<std::string>& backgroundPhotoNames() {
  // Photographs of places and things, none a test pattern, a chessboard or digits (Debian ships
  // these uncompressed; checked on bookworm's opencv-doc 4.6).
  static const std::vector<std::string> kNames = {"building.jpg", "home.jpg",   "stuff.jpg", "aero3.jpg",
                                                  "leuvenA.jpg",  "fruits.jpg", "graf1.png"};
  return kNames;
}

std::string opencvDataDir() {
  const char* dir = std::getenv("APEX_OPENCV_DATA");
  return dir && *dir ? dir : "/usr/share/doc/opencv-doc/examples/data";
}

std::vector<BackgroundPhoto> loadBackgroundPhotos(const std::string& dir, const cv::Size& frame) {
  std::vector<BackgroundPhoto> photos;
  for (const auto& name : backgroundPhotoNames()) {
    const std::string path = dir + "/" + name;
    const cv::Mat read = cv::imread(path, cv::IMREAD_COLOR);
    if (read.empty())
      throw std::runtime_error("cannot read the background photograph '" + path +
                               "': opencv-doc provides it (apt-get install opencv-doc; APEX_OPENCV_DATA names another folder)");
    const double scale =
        kCover * std::max(static_cast<double>(frame.width) / read.cols, static_cast<double>(frame.height) / read.rows);
    const cv::Size size(cvCeil(read.cols * scale), cvCeil(read.rows * scale));
    BackgroundPhoto p{name, cv::Mat()};
    cv::resize(read, p.image, size, 0, 0, scale < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
    photos.push_back(std::move(p));
  }
  return photos;
}

BackgroundCrop pickCrop(const std::vector<BackgroundPhoto>& photos, const cv::Size& frame, cv::RNG& rng) {
  BackgroundCrop c;
  c.photo = static_cast<std::size_t>(rng.uniform(0, static_cast<int>(photos.size())));
  const cv::Size size = photos[c.photo].image.size();
  const int x = rng.uniform(0, size.width - frame.width + 1), y = rng.uniform(0, size.height - frame.height + 1);
  c.rect = cv::Rect(cv::Point(x, y), frame);
  return c;
}

}  // namespace apex_tools
