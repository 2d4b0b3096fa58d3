// ColorConvert: cv::cvtColor between the common colour spaces, and from cameras' YUV 4:2:2.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {

class ColorConvert : public ImageFilter {
 public:
  struct Conversion {
    int code;
    int in_channels;
    const char* out_encoding;
  };
  // The options in name order, as they were listed when they came from a std::map: the panel's
  // list and docs/nodes.md stay as they were. UYVY, YUYV: YUV 4:2:2 as cameras send it (2
  // channels): ROS's "yuv422" is UYVY; YUYV for drivers that send it (Debian 12's sensor_msgs has
  // no name for it, so it comes as a 2-channel image from a node, not through fromRos).
  static inline const apex::ChoiceDecl<Conversion> kConversion =
      apex::param::choice<Conversion>("conversion", {{"BGR2BGRA", {cv::COLOR_BGR2BGRA, 3, "bgra8"}},
                                                     {"BGR2GRAY", {cv::COLOR_BGR2GRAY, 3, "mono8"}},
                                                     {"BGR2HSV", {cv::COLOR_BGR2HSV, 3, "8UC3"}},
                                                     {"BGR2RGB", {cv::COLOR_BGR2RGB, 3, "rgb8"}},
                                                     {"BGR2YUV", {cv::COLOR_BGR2YUV, 3, "8UC3"}},
                                                     {"BGRA2BGR", {cv::COLOR_BGRA2BGR, 4, "bgr8"}},
                                                     {"GRAY2BGR", {cv::COLOR_GRAY2BGR, 1, "bgr8"}},
                                                     {"HSV2BGR", {cv::COLOR_HSV2BGR, 3, "bgr8"}},
                                                     {"RGB2BGR", {cv::COLOR_RGB2BGR, 3, "bgr8"}},
                                                     {"RGB2GRAY", {cv::COLOR_RGB2GRAY, 3, "mono8"}},
                                                     {"RGB2HSV", {cv::COLOR_RGB2HSV, 3, "8UC3"}},
                                                     {"UYVY2BGR", {cv::COLOR_YUV2BGR_UYVY, 2, "bgr8"}},
                                                     {"UYVY2GRAY", {cv::COLOR_YUV2GRAY_UYVY, 2, "mono8"}},
                                                     {"YUV2BGR", {cv::COLOR_YUV2BGR, 3, "bgr8"}},
                                                     {"YUYV2BGR", {cv::COLOR_YUV2BGR_YUYV, 2, "bgr8"}},
                                                     {"YUYV2GRAY", {cv::COLOR_YUV2GRAY_YUYV, 2, "mono8"}}})
          .init("BGR2GRAY")
          .describe("source and target colour space");
  static apex::Manifest manifest() {
    return filterManifest("Converts between colour spaces (cv::cvtColor)").inCategory("colour").param(kConversion);
  }
  ColorConvert() : ImageFilter("1234") {}

 private:
  void filter(const Image& in, Image& out) override {
    const std::string& name = conversion_.text();
    const Conversion& c = conversion_.get();
    if (in.mat.channels() != c.in_channels)
      throw std::invalid_argument(name + " needs a " + std::to_string(c.in_channels) + "-channel image, got " +
                                  std::to_string(in.mat.channels()) + " channels ('" + in.encoding + "')");
    if (c.in_channels == 2 && (in.mat.depth() != CV_8U || in.mat.cols % 2))
      throw std::invalid_argument(name + " needs 8-bit pixel pairs: an even width, got " + std::to_string(in.mat.cols) +
                                  " pixels of depth " + std::to_string(in.mat.depth()) + " ('" + in.encoding + "')");
    cv::cvtColor(in.mat, out.mat, c.code);
    out.encoding = c.out_encoding;
  }
  apex::Choice<Conversion> conversion_{this, kConversion};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ColorConvert, "apex_nodes/ColorConvert");
