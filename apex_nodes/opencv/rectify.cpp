// Rectify: an image undistorted (and rectified, for a stereo camera) by its camera model, as
// image_proc does: image_geometry's pinhole model, whose maps are made once per model.
#include <image_geometry/pinhole_camera_model.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/camera_model.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Rectify : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "the camera's raw frame"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kInfo{"camera_info", "its model"};
  static inline const apex::OutputPort<Image> kRectified{"image", "the frame undistorted and rectified"};
  static inline const apex::ChoiceDecl<int> kInterpolation =
      param::choice<int>("interpolation", {{"linear", cv::INTER_LINEAR},
                                           {"nearest", cv::INTER_NEAREST},
                                           {"cubic", cv::INTER_CUBIC},
                                           {"area", cv::INTER_AREA},
                                           {"lanczos4", cv::INTER_LANCZOS4}});
  static apex::Manifest manifest() {
    return apex::Manifest("Undistorts and rectifies an image by its camera model (image_proc's rectify)")
        .inCategory("cameras and stereo")
        .input(kImage)
        .input(kInfo)
        .output(kRectified)
        .param(kInterpolation);
  }
  void process() override {
    const Image& in = *image_.get();
    const auto info = info_.get();
    requireImage(in);
    requireCameraFor(*info, &in);
    model_.fromCameraInfo(*info);  // keeps its maps while the model is the same
    auto out = buffer_.next(in);
    out->encoding = in.encoding;
    model_.rectifyImage(in.mat, out->mat, interpolation_.get());
    out_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<sensor_msgs::CameraInfo> info_{this, kInfo};
  apex::Output<Image> out_{this, kRectified};
  apex::Choice<int> interpolation_{this, kInterpolation};
  image_geometry::PinholeCameraModel model_;
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Rectify, "apex_nodes/Rectify");
