// Rotate: by 90, 180 or 270 degrees exactly (cv::rotate), or by any angle (warpAffine).
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {

class Rotate : public ImageFilter {
 public:
  static inline const apex::ParamDecl<double> kAngle =
      apex::param::angle("angle").range(-2 * M_PI, 2 * M_PI).init(M_PI / 2).describe("radians, counter-clockwise");
  static apex::Manifest manifest() {
    return filterManifest("Rotates an image counter-clockwise; multiples of 90 degrees are exact").param(kAngle);
  }

 private:
  /** The angle in quarter turns, 0..3, if it is a whole number of them (to 1e-9); else -1. */
  int quarterTurns() const {
    const double quarter = angle_.get() / (M_PI / 2);
    const long turns = std::lround(quarter);
    return std::abs(quarter - turns) < 1e-9 ? static_cast<int>(((turns % 4) + 4) % 4) : -1;
  }
  /** 0 or a whole turn: the frame as it is. */
  bool passesThrough(const Image&) const override { return quarterTurns() == 0; }
  void filter(const Image& in, Image& out) override {
    const int q = quarterTurns();
    if (q >= 0) {
      if (q == 0) in.mat.copyTo(out.mat);  // not reached (passesThrough)
      if (q == 1) cv::rotate(in.mat, out.mat, cv::ROTATE_90_COUNTERCLOCKWISE);
      if (q == 2) cv::rotate(in.mat, out.mat, cv::ROTATE_180);
      if (q == 3) cv::rotate(in.mat, out.mat, cv::ROTATE_90_CLOCKWISE);
    } else {
      const cv::Point2f center(in.mat.cols / 2.0f, in.mat.rows / 2.0f);
      cv::warpAffine(in.mat, out.mat, cv::getRotationMatrix2D(center, angle_.get() * 180.0 / M_PI, 1.0), in.mat.size());
    }
  }
  apex::Param<double> angle_{this, kAngle};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Rotate, "apex_nodes/Rotate");
