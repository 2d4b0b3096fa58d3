// SolvePnP: a chessboard's pose in the camera's frame (cv::solvePnP), from ChessboardCorners'
// corners (the image points) and the camera's model. The matching object points are the board's
// own inner corners: in its plane z = 0, square_size apart, row by row as findChessboardCorners
// orders them, the first at the origin. The pose is the board's origin and axes as seen from the
// camera (x right, y down, z forward), as ArucoDetector's marker poses are; with it the RMS
// reprojection error, which says how well the model and the corners agree.
#include <geometry_msgs/PoseStamped.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/quaternion.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/camera_model.hpp"
#include "apex_nodes/shapes.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** The board's inner corners in its own plane, in the order cv::findChessboardCorners gives them. */
std::vector<cv::Point3f> boardPoints(const cv::Size& pattern, double square) {
  std::vector<cv::Point3f> out;
  for (int i = 0; i < pattern.height; ++i)
    for (int j = 0; j < pattern.width; ++j) out.emplace_back(float(j * square), float(i * square), 0.f);
  return out;
}

}  // namespace

class SolvePnP : public apex::Node {
 public:
  static inline const apex::InputPort<Corners> kCorners{
      "corners", "ChessboardCorners': the image points (found = false: no pose this frame)"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCamera{
      "camera_info", "the model (K, D) of the camera the corners were seen by: a pinhole one, for their image's size"};
  static inline const apex::OutputPort<geometry_msgs::PoseStamped> kPose{
      "pose", "the board's pose in the camera's frame (the corners' header), metres; Nothing when the board is not seen"};
  static inline const apex::OutputPort<double> kError{
      "error", "the RMS distance, pixels, from each corner to the board's corner projected at that pose"};
  static inline const apex::ParamDecl<double> kSquare =
      param::number("square_size").range(0.0001, 10.0).step(0.0005).init(0.025).describe("a square's side, metres");
  static inline const apex::ChoiceDecl<int> kMethod =
      param::choice<int>("method", {{"iterative", cv::SOLVEPNP_ITERATIVE, "Levenberg-Marquardt from a homography's pose"},
                                    {"epnp", cv::SOLVEPNP_EPNP, "EPnP: four control points, closed form"},
                                    {"ippe", cv::SOLVEPNP_IPPE, "infinitesimal plane-based: for planar targets such as a board"},
                                    {"sqpnp", cv::SOLVEPNP_SQPNP, "SQPnP: globally optimal"}})
          .describe("cv::solvePnP's flags");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "A chessboard's pose from its corners and the camera's model (cv::solvePnP), and its reprojection error")
        .inCategory("cameras and stereo")
        .input(kCorners)
        .input(kCamera)
        .output(kPose)
        .output(kError)
        .param(kSquare)
        .param(kMethod);
  }

  void process() override {
    const Corners& c = *corners_.get();
    const sensor_msgs::CameraInfo& camera = *camera_.get();
    requireCameraFor(camera);
    if (camera.distortion_model == "equidistant")
      throw std::invalid_argument("the camera model is a fisheye ('equidistant'): solvePnP needs a pinhole model");
    if (int(camera.width) != c.image_size.width || int(camera.height) != c.image_size.height)
      throw std::invalid_argument("the camera model is for " + std::to_string(camera.width) + "x" +
                                  std::to_string(camera.height) + " images; the corners were found in a " +
                                  std::to_string(c.image_size.width) + "x" + std::to_string(c.image_size.height) + " one");
    if (!c.found) return;  // no board, no pose
    const std::vector<cv::Point3f> board = boardPoints(c.pattern_size, square_.get());
    if (c.corners.size() != board.size())
      throw std::invalid_argument(std::to_string(c.corners.size()) + " corners for a " + std::to_string(c.pattern_size.width) +
                                  "x" + std::to_string(c.pattern_size.height) + " pattern: it has " +
                                  std::to_string(board.size()));
    const cv::Matx33d K(camera.K.data());
    const cv::Mat D(camera.D);
    cv::Vec3d rvec, tvec;
    if (!cv::solvePnP(board, c.corners, K, D, rvec, tvec, false, method_.get()))
      throw std::invalid_argument("cv::solvePnP (" + method_.text() + ") found no pose for the " +
                                  std::to_string(c.corners.size()) + " corners");

    std::vector<cv::Point2f> projected;
    cv::projectPoints(board, rvec, tvec, K, D, projected);
    double sum = 0;
    for (std::size_t i = 0; i < projected.size(); ++i) {
      const cv::Point2f d = projected[i] - c.corners[i];
      sum += double(d.x) * d.x + double(d.y) * d.y;
    }
    auto pose = std::make_shared<geometry_msgs::PoseStamped>();
    pose->header = c.header;
    if (pose->header.frame_id.empty()) pose->header.frame_id = camera.header.frame_id;
    pose->pose.position.x = tvec[0], pose->pose.position.y = tvec[1], pose->pose.position.z = tvec[2];
    const cv::Quatd q = cv::Quatd::createFromRvec(rvec);
    pose->pose.orientation.w = q.w, pose->pose.orientation.x = q.x, pose->pose.orientation.y = q.y,
    pose->pose.orientation.z = q.z;
    pose_.publish(std::move(pose));
    error_.publish(std::sqrt(sum / double(projected.size())));
  }

 private:
  apex::Input<Corners> corners_{this, kCorners};
  apex::Input<sensor_msgs::CameraInfo> camera_{this, kCamera};
  apex::Output<geometry_msgs::PoseStamped> pose_{this, kPose};
  apex::Output<double> error_{this, kError};
  apex::Param<double> square_{this, kSquare};
  apex::Choice<int> method_{this, kMethod};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::SolvePnP, "apex_nodes/SolvePnP");
