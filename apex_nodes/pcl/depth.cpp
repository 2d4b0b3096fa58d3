// DepthToCloud, DepthColorToCloud and CloudToDepth: a depth image and its camera's model to an
// organised cloud and back. The conversion is depth_image_proc's (ROS noetic, depth_conversions.h
// and point_cloud_xyzrgb.cpp): intrinsics from the model's P, as image_geometry's
// PinholeCameraModel gives them (ROI offset and binning applied), the same float expression, the
// same units (16UC1/mono16: millimetres, 32FC1: metres) and a NaN point for a missing depth.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {
namespace {

constexpr float kBad = std::numeric_limits<float>::quiet_NaN();

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::string cameraName(const sensor_msgs::CameraInfo& info) {
  return "camera model " + sizeText(int(info.width), int(info.height)) + " on frame '" + info.header.frame_id + "'";
}

/** A camera's pinhole intrinsics and the size of its images. */
struct Intrinsics {
  double fx, fy, cx, cy;
  int width, height;
};

/** The intrinsics depth_image_proc uses: image_geometry's fx(), fy(), cx(), cy(), i.e. P (the
 *  rectified image's), its principal point moved by the ROI's offset, then scaled by binning.
 *  Throws naming the camera unless it is calibrated and, when both name a frame, on `frame`
 *  (`what` names the data that is on it). */
Intrinsics intrinsicsOf(const sensor_msgs::CameraInfo& info, const std::string& what, const std::string& frame) {
  if (std::all_of(info.K.begin(), info.K.end(), [](double k) { return k == 0; }))
    throw std::invalid_argument(cameraName(info) + " is not calibrated: K is all zero");
  if (info.P[0] == 0 || info.P[5] == 0)
    throw std::invalid_argument(cameraName(info) + " has no projection matrix P (P[0] = " + std::to_string(info.P[0]) +
                                ", P[5] = " + std::to_string(info.P[5]) + ")");
  if (info.width == 0 || info.height == 0) throw std::invalid_argument(cameraName(info) + " has no image size");
  if (!frame.empty() && !info.header.frame_id.empty() && frame != info.header.frame_id)
    throw std::invalid_argument(cameraName(info) + " is not for " + what + " on frame '" + frame + "'");
  const double bx = info.binning_x ? info.binning_x : 1, by = info.binning_y ? info.binning_y : 1;
  const auto& roi = info.roi;  // all zero: the full image
  const bool full = roi.x_offset == 0 && roi.y_offset == 0 && roi.width == 0 && roi.height == 0;
  Intrinsics k;
  k.fx = info.P[0] * (1.0 / bx), k.cx = (info.P[2] - roi.x_offset) * (1.0 / bx);  // image_geometry's order
  k.fy = info.P[5] * (1.0 / by), k.cy = (info.P[6] - roi.y_offset) * (1.0 / by);
  k.width = int((full ? info.width : roi.width) / bx), k.height = int((full ? info.height : roi.height) / by);
  return k;
}

/** Throws naming both sizes unless `image` is the camera's size. */
void requireSize(const Intrinsics& k, const sensor_msgs::CameraInfo& info, const cv::Mat& image, const std::string& what) {
  if (image.cols != k.width || image.rows != k.height)
    throw std::invalid_argument(cameraName(info) + " is for images of " + sizeText(k.width, k.height) + ", " + what + " is " +
                                sizeText(image.cols, image.rows));
}

/** depth_image_proc's DepthTraits: the unit and which values are missing. */
template <class T>
struct Depth;
template <>
struct Depth<std::uint16_t> {
  static bool valid(std::uint16_t d) { return d != 0; }
  static float toMeters(std::uint16_t d) { return d * 0.001f; }  // millimetres
};
template <>
struct Depth<float> {
  // depth_image_proc (noetic) takes only std::isfinite; a 0.0 there gives the point (0, 0, 0). A 0 m
  // depth is no measurement (16UC1 says so with 0 too), so it is missing here as well.
  static bool valid(float d) { return std::isfinite(d) && d != 0.f; }
  static float toMeters(float d) { return d; }
};

/** x, y, z of every pixel into the organised `points` (laid out as `Point`, sized to the image),
 *  as depth_image_proc's convert<T>() computes them; each point's fourth float 1, as PCL's points
 *  have it. Written into the bytes: no typed cloud to copy again. */
template <class T>
void project(const cv::Mat& depth, const Intrinsics& k, Blob& points) {
  const float center_x = float(k.cx), center_y = float(k.cy);
  const double unit_scaling = Depth<T>::toMeters(T(1));  // unit and 1/f folded into one float
  const float constant_x = float(unit_scaling / k.fx), constant_y = float(unit_scaling / k.fy);
  std::uint8_t* to = points.data.data();
  for (int v = 0; v < depth.rows; ++v) {
    const T* row = depth.ptr<T>(v);
    for (int u = 0; u < depth.cols; ++u, to += points.point_step) {
      const T d = row[u];
      float p[4] = {kBad, kBad, kBad, 1.f};
      if (Depth<T>::valid(d)) {
        p[0] = (u - center_x) * d * constant_x;
        p[1] = (v - center_y) * d * constant_y;
        p[2] = Depth<T>::toMeters(d);
      }
      std::memcpy(to, p, sizeof p);
    }
  }
}

/** The organised cloud of `depth` through `info` into `points`, laid out as PCL's `Point` (x, y, z
 *  set; any other field as it was: zero in new points). */
template <class Point>
void depthPoints(const Image& depth, const sensor_msgs::CameraInfo& info, Blob& points) {
  if (depth.mat.empty()) throw std::invalid_argument("received an empty depth image");
  const Intrinsics k = intrinsicsOf(info, "the depth image", depth.header.frame_id);
  requireSize(k, info, depth.mat, "the depth image");
  const std::string& e = depth.encoding;
  const bool millimetres = e == "16UC1" || e == "mono16";
  if (!millimetres && e != "32FC1")
    throw std::invalid_argument("depth image encoding '" + e + "' is not 16UC1, mono16 (millimetres) or 32FC1 (metres)");
  const int type = millimetres ? CV_16UC1 : CV_32FC1;
  if (depth.mat.type() != type)
    throw std::invalid_argument("depth image '" + e + "' holds pixels of OpenCV type " + std::to_string(depth.mat.type()) +
                                ", not " + std::to_string(type));
  static const Blob kLayout = [] {  // what pcl::toPCLPointCloud2 makes of a pcl::PointCloud<Point>
    Blob b;
    pcl::toPCLPointCloud2(pcl::PointCloud<Point>(), b);
    return b;
  }();
  static_assert(sizeof(Point) >= 4 * sizeof(float), "x, y, z and PCL's fourth float lead the point");
  points.header = kLayout.header;
  points.fields = kLayout.fields;
  points.is_bigendian = false;
  points.point_step = sizeof(Point);
  points.width = std::uint32_t(depth.mat.cols);
  points.height = std::uint32_t(depth.mat.rows);
  points.row_step = points.point_step * points.width;
  points.is_dense = false;
  points.data.resize(std::size_t(points.row_step) * points.height);
  if (millimetres) project<std::uint16_t>(depth.mat, k, points);
  else project<float>(depth.mat, k, points);
}

}  // namespace

class DepthToCloud : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kDepth{"depth", "16UC1/mono16 (mm) or 32FC1 (m), rectified"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCameraInfo{"camera_info", "the depth camera's model"};
  static inline const apex::OutputPort<Cloud> kCloud{"cloud", "x, y, z per pixel, organised; NaN where no depth"};
  static apex::Manifest manifest() {
    return apex::Manifest("Depth image to point cloud (depth_image_proc's point_cloud_xyz)")
        .inCategory("depth")
        .input(kDepth)
        .input(kCameraInfo)
        .output(kCloud);
  }
  void process() override {
    const auto depth = depth_.get();
    const auto points = points_.next();
    depthPoints<pcl::PointXYZ>(*depth, *camera_info_.get(), *points);
    auto out = std::make_shared<Cloud>();
    out->header = depth->header;
    out->points = points;
    cloud_.publish(out);
  }

 private:
  apex::Input<Image> depth_{this, kDepth};
  apex::Input<sensor_msgs::CameraInfo> camera_info_{this, kCameraInfo};
  apex::Output<Cloud> cloud_{this, kCloud};
  Reused<Blob> points_;  // refilled once nobody holds the last ones: 4.9 MB at 640x480
};

class DepthColorToCloud : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kDepth{"depth", "16UC1/mono16 (mm) or 32FC1 (m), rectified"};
  static inline const apex::InputPort<Image> kColor{"color", "bgr8 or rgb8 (also bgra8, rgba8, mono8), registered to depth"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCameraInfo{"camera_info", "the depth camera's model"};
  static inline const apex::OutputPort<Cloud> kCloud{"cloud", "x, y, z, rgb per pixel, organised; NaN where no depth"};
  static apex::Manifest manifest() {
    return apex::Manifest("Depth and colour images to a coloured point cloud (depth_image_proc's point_cloud_xyzrgb)")
        .inCategory("depth")
        .input(kDepth)
        .input(kColor)
        .input(kCameraInfo)
        .output(kCloud);
  }
  void process() override {
    const auto depth = depth_.get();
    const Image& color = *color_.get();
    const std::string& e = color.encoding;
    const int channels = e == "mono8" ? 1 : e == "rgb8" || e == "bgr8" ? 3 : e == "rgba8" || e == "bgra8" ? 4 : 0;
    if (channels == 0 || color.mat.type() != CV_8UC(channels))
      throw std::invalid_argument("colour image encoding '" + e + "' (" + std::to_string(color.mat.channels()) +
                                  " channels) is not bgr8, rgb8, bgra8, rgba8 or mono8");
    if (color.mat.size() != depth->mat.size())
      throw std::invalid_argument("the colour image is " + sizeText(color.mat.cols, color.mat.rows) + ", the depth image " +
                                  sizeText(depth->mat.cols, depth->mat.rows) + ": register it to the depth camera");
    if (!color.header.frame_id.empty() && !depth->header.frame_id.empty() && color.header.frame_id != depth->header.frame_id)
      throw std::invalid_argument("the colour image is on frame '" + color.header.frame_id + "', the depth image on '" +
                                  depth->header.frame_id + "'");
    const auto points = points_.next();
    depthPoints<pcl::PointXYZRGB>(*depth, *camera_info_.get(), *points);
    // depth_image_proc's offsets of red, green and blue in a pixel of each encoding
    const bool bgr = e[0] == 'b';
    const int r = bgr ? 2 : 0, g = channels == 1 ? 0 : 1, b = channels == 1 || bgr ? 0 : 2;
    const std::uint32_t rgb =
        std::find_if(points->fields.begin(), points->fields.end(), [](const auto& f) { return f.name == "rgb"; })->offset;
    std::uint8_t* to = points->data.data() + rgb;
    for (int v = 0; v < color.mat.rows; ++v) {
      const std::uint8_t* row = color.mat.ptr<std::uint8_t>(v);
      for (int u = 0; u < color.mat.cols; ++u, to += points->point_step) {  // every pixel, with depth or not
        const std::uint8_t* px = row + u * channels;
        const std::uint8_t bgra[4] = {px[b], px[g], px[r], 255};  // PCL's rgba: b, g, r, a in memory
        std::memcpy(to, bgra, sizeof bgra);
      }
    }
    auto out = std::make_shared<Cloud>();
    out->header = depth->header;
    out->points = points;
    cloud_.publish(out);
  }

 private:
  apex::Input<Image> depth_{this, kDepth};
  apex::Input<Image> color_{this, kColor};
  apex::Input<sensor_msgs::CameraInfo> camera_info_{this, kCameraInfo};
  apex::Output<Cloud> cloud_{this, kCloud};
  Reused<Blob> points_;  // refilled once nobody holds the last ones
};

class CloudToDepth : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud", "points in the camera's frame"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCameraInfo{"camera_info", "the camera to project into"};
  static inline const apex::OutputPort<Image> kDepth{"depth", "32FC1 (m), the nearest point per pixel; NaN where none"};
  static apex::Manifest manifest() {
    return apex::Manifest("Projects a cloud into a camera: its depth image")
        .inCategory("depth")
        .input(kCloud)
        .input(kCameraInfo)
        .output(kDepth);
  }
  void process() override {
    const auto cloud = cloud_.get();
    const auto& info = *camera_info_.get();
    for (const char* xyz : {"x", "y", "z"}) requireField(*cloud, xyz);
    const Intrinsics k = intrinsicsOf(info, "the cloud", cloud->header.frame_id);
    auto out = std::make_shared<Image>();
    out->header = cloud->header;
    if (out->header.frame_id.empty()) out->header.frame_id = info.header.frame_id;
    out->encoding = "32FC1";
    out->mat = cv::Mat(k.height, k.width, CV_32FC1, cv::Scalar(kBad));
    for (const pcl::PointXYZ& p : typedPoints<pcl::PointXYZ>(*cloud)) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || p.z <= 0) continue;
      const double u = k.fx * p.x / p.z + k.cx, v = k.fy * p.y / p.z + k.cy;
      if (!(u >= -0.5 && u < k.width - 0.5 && v >= -0.5 && v < k.height - 0.5)) continue;  // off the image
      float& d = out->mat.at<float>(int(std::floor(v + 0.5)), int(std::floor(u + 0.5)));  // the nearest pixel
      if (std::isnan(d) || p.z < d) d = p.z;  // the nearest point
    }
    depth_.publish(out);
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Input<sensor_msgs::CameraInfo> camera_info_{this, kCameraInfo};
  apex::Output<Image> depth_{this, kDepth};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DepthToCloud, "apex_nodes/DepthToCloud");
APEX_REGISTER_NODE(apex_nodes::DepthColorToCloud, "apex_nodes/DepthColorToCloud");
APEX_REGISTER_NODE(apex_nodes::CloudToDepth, "apex_nodes/CloudToDepth");
