// CameraInfoFile: a calibration file's camera model, sent with each image's header, for a camera
// whose driver sends no camera_info (or a bag recorded without it).
#include "apex/core/registry.hpp"
#include "apex_nodes/camera_model.hpp"

namespace apex_nodes {
namespace param = apex::param;

class CameraInfoFile : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "the frames the model belongs to"};
  static inline const apex::OutputPort<sensor_msgs::CameraInfo> kInfo{"camera_info", "the model, with the image's header"};
  static inline const apex::ParamDecl<std::string> kFile = param::path("file").describe(
      "a calibration: ROS camera_calibration YAML or INI, or OpenCV's (camera_matrix, distortion_coefficients)");
  static apex::Manifest manifest() {
    return apex::Manifest("Sends a calibration file's camera model with each image's header")
        .inCategory("cameras and stereo")
        .input(kImage)
        .output(kInfo)
        .param(kFile);
  }
  void parameterChanged(const std::string&) override { model_.reset(); }
  void process() override {
    if (!model_) model_ = std::make_shared<const sensor_msgs::CameraInfo>(readCameraFile(file_.get()));
    const Image& image = *image_.get();
    auto out = std::make_shared<sensor_msgs::CameraInfo>(*model_);
    out->header = image.header;
    requireCameraFor(*out, &image);
    info_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<sensor_msgs::CameraInfo> info_{this, kInfo};
  apex::Param<std::string> file_{this, kFile};
  std::shared_ptr<const sensor_msgs::CameraInfo> model_;  // read when first needed after a change
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::CameraInfoFile, "apex_nodes/CameraInfoFile");
