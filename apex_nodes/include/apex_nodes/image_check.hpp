// Checks image nodes make on their input: a clear error instead of an OpenCV
// assertion deep inside a call.
#pragma once

#include <stdexcept>
#include <string>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief The channel counts in `channels` ("134") in words: "1, 3 or 4 channels". */
inline std::string channelWords(const std::string& channels) {
  if (channels == "1") return "a single-channel image";
  std::string out;
  for (std::size_t i = 0; i < channels.size(); ++i)
    out += (i == 0 ? "" : i + 1 == channels.size() ? " or " : ", ") + std::string(1, channels[i]);
  return out + " channels";
}

/** @brief Throws std::invalid_argument naming the problem if the image is empty or has
 *  a channel count not in `channels` (e.g. "1" or "13" for one or three). */
inline void requireImage(const Image& image, const std::string& channels = "134") {
  if (image.mat.empty()) throw std::invalid_argument("received an empty image");
  const char c = static_cast<char>('0' + image.mat.channels());
  if (channels.find(c) == std::string::npos)
    throw std::invalid_argument("cannot handle " + std::to_string(image.mat.channels()) + "-channel images (encoding '" +
                                image.encoding + "'); needs " + channelWords(channels));
}

/** @brief The encoding of a result with `channels` channels, following the input's. */
inline std::string encodingFor(const Image& in, int channels, int depth = CV_8U) {
  if (channels == in.mat.channels() && depth == in.mat.depth()) return in.encoding;
  if (channels == 1) return depth == CV_8U ? "mono8" : depth == CV_16U ? "mono16" : "32FC1";
  if (channels == 3) return "bgr8";
  return "bgra8";
}

/** @brief A new image with the input's header. */
inline std::shared_ptr<Image> resultOf(const Image& in, cv::Mat mat, std::string encoding) {
  auto out = std::make_shared<Image>();
  out->header = in.header;
  out->encoding = std::move(encoding);
  out->mat = std::move(mat);
  return out;
}

}  // namespace apex_nodes
