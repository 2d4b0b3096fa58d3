// ArucoDetector: square fiducial markers (cv::aruco), with their poses when the camera's model is given.
#include <utility>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/camera_model.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/shapes.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
namespace aruco = cv::aruco;
}  // namespace

class ArucoDetector : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCamera{
      "camera_info", "if connected: the image's camera model, for the markers' poses", true};
  static inline const apex::OutputPort<Markers> kMarkers{"markers", "ids and corners; poses with a camera model"};
  using Family = aruco::PREDEFINED_DICTIONARY_NAME;  // a dictionary by its id
  using Refinement = aruco::CornerRefineMethod;
  static inline const apex::ChoiceDecl<Family> kDictionary =
      param::choice<Family>("dictionary", {{"4x4_50", aruco::DICT_4X4_50},
                                           {"4x4_100", aruco::DICT_4X4_100},
                                           {"4x4_250", aruco::DICT_4X4_250},
                                           {"4x4_1000", aruco::DICT_4X4_1000},
                                           {"5x5_50", aruco::DICT_5X5_50},
                                           {"5x5_100", aruco::DICT_5X5_100},
                                           {"5x5_250", aruco::DICT_5X5_250},
                                           {"5x5_1000", aruco::DICT_5X5_1000},
                                           {"6x6_50", aruco::DICT_6X6_50},
                                           {"6x6_100", aruco::DICT_6X6_100},
                                           {"6x6_250", aruco::DICT_6X6_250},
                                           {"6x6_1000", aruco::DICT_6X6_1000},
                                           {"7x7_50", aruco::DICT_7X7_50},
                                           {"7x7_100", aruco::DICT_7X7_100},
                                           {"7x7_250", aruco::DICT_7X7_250},
                                           {"7x7_1000", aruco::DICT_7X7_1000},
                                           {"aruco_original", aruco::DICT_ARUCO_ORIGINAL},
                                           {"apriltag_16h5", aruco::DICT_APRILTAG_16h5},
                                           {"apriltag_25h9", aruco::DICT_APRILTAG_25h9},
                                           {"apriltag_36h10", aruco::DICT_APRILTAG_36h10},
                                           {"apriltag_36h11", aruco::DICT_APRILTAG_36h11}})
          .describe("the markers' family and how many ids it has");
  static inline const apex::ParamDecl<double> kLength =
      param::number("marker_length").range(0.001, 10.0).step(0.001).init(0.05).describe("a marker's side, metres (poses)");
  static inline const apex::ChoiceDecl<Refinement> kRefinement =
      param::choice<Refinement>("corner_refinement", {{"none", aruco::CORNER_REFINE_NONE},
                                                      {"subpix", aruco::CORNER_REFINE_SUBPIX},
                                                      {"contour", aruco::CORNER_REFINE_CONTOUR}})
          .describe("how the corners are refined");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds ArUco (or AprilTag) markers; with the camera's model, each one's pose (cv::aruco)")
        .inCategory("detection")
        .input(kImage)
        .input(kCamera)
        .output(kMarkers)
        .param(kDictionary)
        .param(kLength)
        .param(kRefinement);
  }
  void process() override {
    const Image& in = *image_.get();
    const auto camera = camera_.get();  // nullptr: not connected (or it sent nothing)
    requireImage(in, "134");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image, got '" + in.encoding + "'");
    if (camera) {
      requireCameraFor(*camera, &in);
      if (camera->distortion_model == "equidistant")
        throw std::invalid_argument("the camera model is a fisheye ('equidistant'): poses need a pinhole model");
    }
    const bool rgb = in.encoding.rfind("rgb", 0) == 0;
    if (in.mat.channels() == 3) cv::cvtColor(in.mat, gray_, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
    if (in.mat.channels() == 4) cv::cvtColor(in.mat, gray_, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
    const cv::Mat& gray = in.mat.channels() == 1 ? in.mat : gray_;  // read only

    parameters_->cornerRefinementMethod = refinement_.get();
    auto out = std::make_shared<Markers>();
    out->header = in.header;
    out->image_size = in.mat.size();
    out->dictionary = dictionary_.text();
    out->marker_length = length_.get();
    aruco::detectMarkers(gray, aruco::getPredefinedDictionary(dictionary_.get()), out->corners, out->ids, parameters_);
    if (camera && !out->ids.empty())
      aruco::estimatePoseSingleMarkers(out->corners, static_cast<float>(length_.get()), cv::Matx33d(camera->K.data()),
                                       cv::Mat(camera->D), out->rvecs, out->tvecs);
    markers_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<sensor_msgs::CameraInfo> camera_{this, kCamera};
  apex::Output<Markers> markers_{this, kMarkers};
  apex::Choice<Family> dictionary_{this, kDictionary};
  apex::Param<double> length_{this, kLength};
  apex::Choice<Refinement> refinement_{this, kRefinement};
  cv::Ptr<aruco::DetectorParameters> parameters_ = aruco::DetectorParameters::create();
  cv::Mat gray_;  // a colour frame's gray, reused
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ArucoDetector, "apex_nodes/ArucoDetector");
