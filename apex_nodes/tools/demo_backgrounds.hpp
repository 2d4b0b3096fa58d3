// Real backgrounds for apex_make_demo_bag (--backgrounds real): frame-sized crops of a few of
// opencv-doc's photographs of the world (a building, a street, a desk, a city from the air, ...),
// in place of the generated texture.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace apex_tools {

/** @brief The photographs' file names, in opencv-doc's example data, in the order crops pick them. */
const std::vector<std::string>& backgroundPhotoNames();

/** @brief The folder they are read from: $APEX_OPENCV_DATA when set and not empty, else
 *  opencv-doc's /usr/share/doc/opencv-doc/examples/data. */
std::string opencvDataDir();

/** One photograph, read as bgr8 and scaled (aspect kept) to cover 1.3 times the frame, so that
 *  crops of it vary. */
struct BackgroundPhoto {
  std::string name;  // as in backgroundPhotoNames()
  cv::Mat image;  // CV_8UC3
};

/** @brief Every photo of backgroundPhotoNames() read from `dir` and scaled to cover `frame`
 *  1.3 times over. Throws std::runtime_error naming the first file that cannot be read and
 *  saying that opencv-doc provides it. */
std::vector<BackgroundPhoto> loadBackgroundPhotos(const std::string& dir, const cv::Size& frame);

/** Where a frame's background was cut: photos[photo].image(rect). */
struct BackgroundCrop {
  std::size_t photo;
  cv::Rect rect;  // frame-sized, in the scaled photo
};

/** @brief A photo and a frame-sized place in it, drawn from `rng` (three draws: photo, x, y).
 *  `photos` must not be empty. */
BackgroundCrop pickCrop(const std::vector<BackgroundPhoto>& photos, const cv::Size& frame, cv::RNG& rng);

}  // namespace apex_tools
