// Rotate: by 90, 180 or 270 degrees exactly (cv::rotate), or by any angle (warpAffine).
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class Rotate : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Rotates an image counter-clockwise; multiples of 90 degrees are exact")
        .input<Image>("image")
        .output<Image>("image")
        .param(apex::param::angle("angle", M_PI / 2, -2 * M_PI, 2 * M_PI).describe("radians, counter-clockwise"));
  }
  void process() override {
    const Image& in = *image_in_.get();
    requireImage(in);
    auto out = buffer_.next(in);
    out->encoding = in.encoding;
    const double quarter = angle_.get() / (M_PI / 2);
    const long turns = std::lround(quarter);
    if (std::abs(quarter - turns) < 1e-9) {
      const int q = static_cast<int>(((turns % 4) + 4) % 4);
      if (q == 0) in.mat.copyTo(out->mat);
      if (q == 1) cv::rotate(in.mat, out->mat, cv::ROTATE_90_COUNTERCLOCKWISE);
      if (q == 2) cv::rotate(in.mat, out->mat, cv::ROTATE_180);
      if (q == 3) cv::rotate(in.mat, out->mat, cv::ROTATE_90_CLOCKWISE);
    } else {
      const cv::Point2f center(in.mat.cols / 2.0f, in.mat.rows / 2.0f);
      const cv::Mat m = cv::getRotationMatrix2D(center, angle_.get() * 180.0 / M_PI, 1.0);
      cv::warpAffine(in.mat, out->mat, m, in.mat.size());
    }
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<double> angle_{this, "angle"};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Rotate, "apex_nodes/Rotate");
