// CameraCalibration: a camera's model from views of a chessboard (ChessboardCorners'), by
// cv::calibrateCamera, made as ROS's camera_calibration makes it (R = I, P from
// getOptimalNewCameraMatrix) and written in camera_calibration_parsers' format, whole or not at all.
#include <camera_calibration_parsers/parse_ini.h>
#include <camera_calibration_parsers/parse_yml.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "apex/core/graph_file.hpp"  // writeFileAtomically
#include "apex/core/registry.hpp"
#include "apex_nodes/shapes.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

std::string sizeText(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

/** What a view is, for messages: "a 9x6 pattern in a 640x480 image". */
std::string viewText(const cv::Size& pattern, const cv::Size& image) {
  return "a " + sizeText(pattern) + " pattern in a " + sizeText(image) + " image";
}

/** The board's inner corners in its own plane, in the order cv::findChessboardCorners gives them:
 *  row by row, along a row first. */
std::vector<cv::Point3f> boardPoints(const cv::Size& pattern, double square) {
  std::vector<cv::Point3f> out;
  for (int i = 0; i < pattern.height; ++i)
    for (int j = 0; j < pattern.width; ++j) out.emplace_back(float(j * square), float(i * square), 0.f);
  return out;
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

class CameraCalibration : public apex::Node {
 public:
  static constexpr int kMinViews = 3;

  static inline const apex::InputPort<Corners> kCorners{
      "corners", "ChessboardCorners': each view where the board was found is kept (found = false: skipped)"};
  static inline const apex::OutputPort<sensor_msgs::CameraInfo> kInfo{
      "camera_info", "after a calibration: the model, with the header of the last view kept (else Nothing)"};
  static inline const apex::OutputPort<double> kRms{"rms", "after a calibration: its RMS reprojection error, pixels"};
  static inline const apex::TriggerPort kCalibrated{"calibrated", "after each calibration, once its model is sent"};
  static inline const apex::ParamDecl<double> kSquare =
      param::number("square_size")
          .range(0.001, 1.0)
          .step(0.0005)
          .init(0.025)
          .describe("a square's side, metres (the board's scale; K and D do not depend on it)");
  static inline const apex::ParamDecl<int> kViews = param::integer("views").range(0, 1000).step(1).describe(
      "calibrate when this many views are kept, then keep no more until reset; 0: only on the calibrate slot");
  static inline const apex::ParamDecl<std::string> kFile =
      param::path("output_file")
          .describe(
              "where the model goes: camera_calibration_parsers' YAML (.ini: INI), written whole or not at all; "
              "empty: no file")
          .mode(apex::PathMode::Write);
  static inline const apex::ParamDecl<std::string> kCameraName =
      param::text("camera_name").describe("the camera's name in the file; empty: the views' frame");
  static inline const apex::ParamDecl<bool> kFixAspect =
      param::flag("fix_aspect_ratio").describe("fx = fy (CALIB_FIX_ASPECT_RATIO)");
  static inline const apex::ParamDecl<bool> kFixPrincipal =
      param::flag("fix_principal_point").describe("cx, cy at the image's centre (CALIB_FIX_PRINCIPAL_POINT)");
  static inline const apex::ParamDecl<bool> kZeroTangent =
      param::flag("zero_tangent_dist").describe("no tangential distortion: p1 = p2 = 0 (CALIB_ZERO_TANGENT_DIST)");
  static inline const apex::ParamDecl<bool> kFixK3 =
      param::flag("fix_k3").describe("k3 = 0 (CALIB_FIX_K3; ROS's cameracalibrator sets it unless told otherwise)");
  static inline const apex::ParamDecl<double> kAlpha = param::number("alpha").range(0.0, 1.0).step(0.05).describe(
      "P, the rectified image's camera (getOptimalNewCameraMatrix, as ROS's cameracalibrator): 0 shows only valid "
      "pixels, 1 every pixel of the raw image");

  static apex::Manifest manifest() {
    return apex::Manifest("Calibrates a camera from views of a chessboard (cv::calibrateCamera) and saves its model")
        .inCategory("cameras and stereo")
        .keepsState("the views collected: a re-run may add the held frame again")
        .input(kCorners)
        .output(kInfo)
        .output(kRms)
        .trigger(kCalibrated)
        .param(kSquare)
        .param(kViews)
        .param(kFile)
        .param(kCameraName)
        .param(kFixAspect)
        .param(kFixPrincipal)
        .param(kZeroTangent)
        .param(kFixK3)
        .param(kAlpha)
        .slot("calibrate", &CameraCalibration::calibrate, "calibrates on the views kept so far")
        .slot("reset", &CameraCalibration::reset, "forgets the views");
  }

  /** A setting changed: with `views`, the views kept are calibrated again at the next one. */
  void parameterChanged(const std::string&) override { calibrated_ = false; }

  void process() override {
    const Corners& c = *corners_.get();
    if (!c.found) return;  // no board in this frame: sends Nothing
    const auto want = std::size_t(c.pattern_size.area());
    if (c.pattern_size.width < 2 || c.pattern_size.height < 2 || c.corners.size() != want)
      throw std::invalid_argument("a view of " + viewText(c.pattern_size, c.image_size) + " has " +
                                  std::to_string(c.corners.size()) + " corners, not " + std::to_string(want));
    if (c.image_size.width <= 0 || c.image_size.height <= 0)
      throw std::invalid_argument("a view of " + viewText(c.pattern_size, c.image_size) + " names no image size");
    if (!views_.empty() && (c.pattern_size != pattern_ || c.image_size != image_size_))
      throw std::invalid_argument("a view of " + viewText(c.pattern_size, c.image_size) + " does not fit the " +
                                  std::to_string(views_.size()) + " kept, of " + viewText(pattern_, image_size_) +
                                  ": reset first");
    const int limit = views_param_.get();
    if (limit == 0 || int(views_.size()) < limit) {
      views_.push_back(c.corners);
      pattern_ = c.pattern_size, image_size_ = c.image_size, header_ = c.header;
      calibrated_ = false;
    }
    if (limit > 0 && int(views_.size()) >= limit && !calibrated_) calibrate();
  }

  /** Calibrates on the views kept, writes the file (if one is named), then sends the model. */
  void calibrate() {
    const int n = int(views_.size());
    if (n < kMinViews)
      throw std::invalid_argument("needs at least " + std::to_string(kMinViews) + " views of the board to calibrate, has " +
                                  std::to_string(n));
    const std::vector<std::vector<cv::Point3f>> board(std::size_t(n), boardPoints(pattern_, square_.get()));
    const int flags = (fix_aspect_.get() ? cv::CALIB_FIX_ASPECT_RATIO : 0) |
                      (fix_principal_.get() ? cv::CALIB_FIX_PRINCIPAL_POINT : 0) |
                      (zero_tangent_.get() ? cv::CALIB_ZERO_TANGENT_DIST : 0) | (fix_k3_.get() ? cv::CALIB_FIX_K3 : 0);
    cv::Mat K = cv::Mat::eye(3, 3, CV_64F), D, P;  // K's fx / fy: the ratio CALIB_FIX_ASPECT_RATIO keeps
    std::vector<cv::Mat> rvecs, tvecs;
    double rms = 0;
    try {
      rms = cv::calibrateCamera(board, views_, image_size_, K, D, rvecs, tvecs, flags);
      P = cv::getOptimalNewCameraMatrix(K, D, image_size_, alpha_.get());
    } catch (const cv::Exception& e) {
      throw std::runtime_error("cv::calibrateCamera failed on " + std::to_string(n) + " views of " +
                               viewText(pattern_, image_size_) + ": " + e.err);
    }
    if (!std::isfinite(rms) || !cv::checkRange(K) || !cv::checkRange(D) || !cv::checkRange(P) || D.total() != 5)
      throw std::runtime_error("the calibration on " + std::to_string(n) + " views did not converge (RMS " + std::to_string(rms) +
                               "): take views of the board at more angles and distances");

    auto info = std::make_shared<sensor_msgs::CameraInfo>();
    info->header = header_;
    info->width = std::uint32_t(image_size_.width), info->height = std::uint32_t(image_size_.height);
    info->distortion_model = "plumb_bob";
    info->D.assign(D.begin<double>(), D.end<double>());
    std::copy(K.begin<double>(), K.end<double>(), info->K.begin());
    info->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    info->P = {};
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 3; ++col) info->P[std::size_t(r * 4 + col)] = P.at<double>(r, col);
    save(*info);
    info_.publish(info);
    rms_.publish(rms);
    calibrated_ = true;
    calibrated_trigger_.fire();
  }

  void reset() {
    views_.clear();
    calibrated_ = false;
  }

 private:
  /** The model into `output_file` (none: nothing), replacing it whole: never half a file. */
  void save(const sensor_msgs::CameraInfo& info) const {
    const std::string& path = file_.get();
    if (path.empty()) return;
    std::string name = camera_name_.get();
    if (name.empty()) name = header_.frame_id.empty() ? "camera" : header_.frame_id;
    std::ostringstream text;
    const bool ini = endsWith(path, ".ini");  // camera_calibration_parsers::writeCalibration's choice
    const bool ok = ini ? camera_calibration_parsers::writeCalibrationIni(text, name, info)
                        : camera_calibration_parsers::writeCalibrationYml(text, name, info);
    if (!ok)
      throw std::runtime_error("cannot write the model as camera_calibration_parsers' " + std::string(ini ? "INI" : "YAML"));
    const apex::Status st = apex::writeFileAtomically(path, text.str() + "\n");
    if (!st) throw std::runtime_error(st.message() + " (the calibration was not saved, nor sent)");
  }

  apex::Input<Corners> corners_{this, kCorners};
  apex::Output<sensor_msgs::CameraInfo> info_{this, kInfo};
  apex::Output<double> rms_{this, kRms};
  apex::Trigger calibrated_trigger_{this, kCalibrated};
  apex::Param<double> square_{this, kSquare};
  apex::Param<int> views_param_{this, kViews};
  apex::Param<std::string> file_{this, kFile};
  apex::Param<std::string> camera_name_{this, kCameraName};
  apex::Param<bool> fix_aspect_{this, kFixAspect};
  apex::Param<bool> fix_principal_{this, kFixPrincipal};
  apex::Param<bool> zero_tangent_{this, kZeroTangent};
  apex::Param<bool> fix_k3_{this, kFixK3};
  apex::Param<double> alpha_{this, kAlpha};
  std::vector<std::vector<cv::Point2f>> views_;  // each view's corners, as found
  cv::Size pattern_, image_size_;  // of every view kept
  std_msgs::Header header_;  // the last view's
  bool calibrated_ = false;  // the views kept are calibrated with the parameters as they are
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::CameraCalibration, "apex_nodes/CameraCalibration");
