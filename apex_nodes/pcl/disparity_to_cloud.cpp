// DisparityToCloud: a disparity image (StereoMatcher's) and the left camera's model to a coloured
// cloud in that camera's frame, as image_geometry's StereoCameraModel projects a disparity:
// Z = fx B / (d - (cx_left - cx_right)), X = (u - cx) Z / fx, Y = (v - cy) Z / fy, with the
// intrinsics of the left camera's P (ROI offset and binning applied, as depth.cpp takes them).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::string cameraName(const sensor_msgs::CameraInfo& info) {
  return "camera model " + sizeText(int(info.width), int(info.height)) + " on frame '" + info.header.frame_id + "'";
}

/** A rectified camera's pinhole intrinsics and the size of its images. */
struct Intrinsics {
  double fx, fy, cx, cy, tx;  // tx: P[3] (-fx' B for the right camera of a stereo pair), binned as fx
  int width, height;
};

/** image_geometry's fx(), fy(), cx(), cy(), Tx(): P, its principal point moved by the ROI's
 *  offset, then scaled by binning. Throws naming the camera (`role`) unless it is calibrated. */
Intrinsics intrinsicsOf(const sensor_msgs::CameraInfo& info, const std::string& role) {
  if (std::all_of(info.K.begin(), info.K.end(), [](double k) { return k == 0; }))
    throw std::invalid_argument("the " + role + " " + cameraName(info) + " is not calibrated: K is all zero");
  if (info.P[0] == 0 || info.P[5] == 0)
    throw std::invalid_argument("the " + role + " " + cameraName(info) + " has no projection matrix P (P[0] = " +
                                std::to_string(info.P[0]) + ", P[5] = " + std::to_string(info.P[5]) + ")");
  if (info.width == 0 || info.height == 0)
    throw std::invalid_argument("the " + role + " " + cameraName(info) + " has no image size");
  const double bx = info.binning_x ? info.binning_x : 1, by = info.binning_y ? info.binning_y : 1;
  const auto& roi = info.roi;  // all zero: the full image
  const bool full = roi.x_offset == 0 && roi.y_offset == 0 && roi.width == 0 && roi.height == 0;
  Intrinsics k;
  k.fx = info.P[0] / bx, k.cx = (info.P[2] - roi.x_offset) / bx, k.tx = info.P[3] / bx;
  k.fy = info.P[5] / by, k.cy = (info.P[6] - roi.y_offset) / by;
  k.width = int((full ? info.width : roi.width) / bx), k.height = int((full ? info.height : roi.height) / by);
  return k;
}

/** The colour image's channels and where red, green and blue are in a pixel; throws unless it is
 *  8-bit bgr8, rgb8, bgra8, rgba8 or mono8 of the disparity's size, on its frame (if both name one). */
struct Colour {
  int channels, r, g, b;
};
Colour colourOf(const Image& image, const Image& disparity) {
  const std::string& e = image.encoding;
  const int channels = e == "mono8" ? 1 : e == "rgb8" || e == "bgr8" ? 3 : e == "rgba8" || e == "bgra8" ? 4 : 0;
  if (channels == 0 || image.mat.type() != CV_8UC(channels))
    throw std::invalid_argument("colour image encoding '" + e + "' (" + std::to_string(image.mat.channels()) +
                                " channels) is not bgr8, rgb8, bgra8, rgba8 or mono8");
  if (image.mat.size() != disparity.mat.size())
    throw std::invalid_argument("the colour image is " + sizeText(image.mat.cols, image.mat.rows) + ", the disparity " +
                                sizeText(disparity.mat.cols, disparity.mat.rows) + ": give the rectified left image");
  if (!image.header.frame_id.empty() && !disparity.header.frame_id.empty() && image.header.frame_id != disparity.header.frame_id)
    throw std::invalid_argument("the colour image is on frame '" + image.header.frame_id + "', the disparity on '" +
                                disparity.header.frame_id + "'");
  const bool bgr = e[0] == 'b';
  return {channels, bgr ? 2 : 0, channels == 1 ? 0 : 1, channels == 1 || bgr ? 0 : 2};
}

}  // namespace

class DisparityToCloud : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kDisparity{
      "disparity", "32FC1, pixels, of the rectified left image (StereoMatcher's); NaN: no match"};
  static inline const apex::InputPort<Image> kImage{
      "image", "the rectified left image (bgr8, rgb8, bgra8, rgba8 or mono8): the points' colour; without it, white", true};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCameraInfo{"camera_info", "the left camera's model (its P)"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kRightInfo{
      "right_camera_info", "the right camera's model: its P gives the baseline (P[3] = Tx = -fx B) in place of 'baseline'", true};
  static inline const apex::OutputPort<Cloud> kCloud{
      "cloud", "x, y, z, rgb in the left camera's frame: a point per valid disparity (organized: per pixel, NaN where none)"};
  static inline const apex::ParamDecl<double> kBaseline =
      param::number("baseline")
          .range(0.0, 10.0)
          .step(0.001)
          .describe("metres between the cameras' centres, used without right_camera_info");
  static inline const apex::ParamDecl<double> kMinDisparity =
      param::number("min_disparity")
          .range(-1024.0, 1024.0)
          .step(0.5)
          .init(0.0)
          .describe(
              "disparities at or below this (pixels) give no point; nor do NaN, infinite, or ones that put the point behind the "
              "camera");
  static inline const apex::ParamDecl<bool> kOrganized =
      param::flag("organized").describe("keep the image's grid: a point per pixel, NaN where there is none");

  static apex::Manifest manifest() {
    return apex::Manifest(
               "Disparity image to a coloured point cloud through the left camera's model (stereo_image_proc's point_cloud2)")
        .inCategory("cameras and stereo")
        .input(kDisparity)
        .input(kImage)
        .input(kCameraInfo)
        .input(kRightInfo)
        .output(kCloud)
        .param(kBaseline)
        .param(kMinDisparity)
        .param(kOrganized);
  }

  void process() override {
    const auto disparity = disparity_.get();
    const Image& disp = *disparity;
    const sensor_msgs::CameraInfo& info = *camera_info_.get();
    if (disp.mat.empty()) throw std::invalid_argument("received an empty disparity image");
    if (disp.encoding != "32FC1" || disp.mat.type() != CV_32FC1)
      throw std::invalid_argument("disparity image encoding '" + disp.encoding + "' (OpenCV type " +
                                  std::to_string(disp.mat.type()) + ") is not 32FC1, disparities in pixels (StereoMatcher's)");
    const Intrinsics k = intrinsicsOf(info, "left");
    if (disp.mat.cols != k.width || disp.mat.rows != k.height)
      throw std::invalid_argument("the left " + cameraName(info) + " is for images of " + sizeText(k.width, k.height) +
                                  ", the disparity is " + sizeText(disp.mat.cols, disp.mat.rows));
    if (!disp.header.frame_id.empty() && !info.header.frame_id.empty() && disp.header.frame_id != info.header.frame_id)
      throw std::invalid_argument("the left " + cameraName(info) + " is not for the disparity on frame '" + disp.header.frame_id +
                                  "'");

    double baseline = baseline_.get(), offset = 0;  // offset: cx_left - cx_right, the disparity of a point at infinity
    if (right_info_.has()) {
      const sensor_msgs::CameraInfo& right_info = *right_info_.get();
      const Intrinsics right = intrinsicsOf(right_info, "right");
      baseline = -right.tx / right.fx;
      if (!(baseline > 0))
        throw std::invalid_argument("the right " + cameraName(right_info) +
                                    " has P[3] = Tx = " + std::to_string(right_info.P[3]) +
                                    ": a right camera's Tx is -fx x baseline, below zero (was the left camera's model given?)");
      offset = k.cx - right.cx;
    } else if (!(baseline > 0)) {
      throw std::invalid_argument("no baseline: set 'baseline' (metres) or connect right_camera_info");
    }

    const auto image = image_.get();  // nullptr without one
    Colour colour{0, 0, 0, 0};
    if (image) colour = colourOf(*image, disp);

    const bool organized = organized_.get();
    const double lowest = min_disparity_.get(), fb = k.fx * baseline;
    pcl::PointCloud<pcl::PointXYZRGB> points;
    if (organized) points = pcl::PointCloud<pcl::PointXYZRGB>(std::uint32_t(disp.mat.cols), std::uint32_t(disp.mat.rows));
    constexpr float kBad = std::numeric_limits<float>::quiet_NaN();
    for (int v = 0; v < disp.mat.rows; ++v) {
      const float* row = disp.mat.ptr<float>(v);
      const std::uint8_t* pixels = image ? image->mat.ptr<std::uint8_t>(v) : nullptr;
      for (int u = 0; u < disp.mat.cols; ++u) {
        const double d = row[u] - offset;
        const bool valid = std::isfinite(row[u]) && row[u] > lowest && d > 0;
        if (!valid && !organized) continue;
        pcl::PointXYZRGB p;
        if (valid) {
          const double z = fb / d;
          p.x = float((u - k.cx) * z / k.fx), p.y = float((v - k.cy) * z / k.fy), p.z = float(z);
        } else {
          p.x = p.y = p.z = kBad;
        }
        if (pixels) {
          const std::uint8_t* px = pixels + u * colour.channels;
          p.r = px[colour.r], p.g = px[colour.g], p.b = px[colour.b];
        } else {
          p.r = p.g = p.b = 255;
        }
        p.a = 255;
        if (organized) points.at(u, v) = p;
        else points.push_back(p);
      }
    }
    points.is_dense = !organized;
    std_msgs::Header header = disp.header;
    if (header.frame_id.empty()) header.frame_id = info.header.frame_id;
    cloud_.publish(makeCloud(header, points));
  }

 private:
  apex::Input<Image> disparity_{this, kDisparity};
  apex::Input<Image> image_{this, kImage};
  apex::Input<sensor_msgs::CameraInfo> camera_info_{this, kCameraInfo};
  apex::Input<sensor_msgs::CameraInfo> right_info_{this, kRightInfo};
  apex::Output<Cloud> cloud_{this, kCloud};
  apex::Param<double> baseline_{this, kBaseline};
  apex::Param<double> min_disparity_{this, kMinDisparity};
  apex::Param<bool> organized_{this, kOrganized};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DisparityToCloud, "apex_nodes/DisparityToCloud");
