// The image library's results as this package's ROS messages (ros_results.hpp).
#include "apex_nodes/ros_results.hpp"

#include <algorithm>
#include <cmath>

namespace apex_nodes {
namespace {

/** A size as the messages' width and height: never negative. */
template <class Msg>
void setSize(Msg& msg, const cv::Size& size) {
  msg.width = static_cast<std::uint32_t>(std::max(0, size.width));
  msg.height = static_cast<std::uint32_t>(std::max(0, size.height));
}

geometry_msgs::Point32 point32(const cv::Point2f& p) {
  geometry_msgs::Point32 out;
  out.x = p.x, out.y = p.y;
  return out;
}

std::vector<geometry_msgs::Point32> points32(const std::vector<cv::Point2f>& points) {
  std::vector<geometry_msgs::Point32> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(point32(p));
  return out;
}

/** A Rodrigues rotation vector as a quaternion: the angle is its length, the axis its direction. */
geometry_msgs::Quaternion quaternion(const cv::Vec3d& r) {
  geometry_msgs::Quaternion q;
  const double angle = cv::norm(r);
  if (angle < 1e-12) {
    q.w = 1.0;
    return q;
  }
  const double s = std::sin(angle / 2) / angle;
  q.x = r[0] * s, q.y = r[1] * s, q.z = r[2] * s, q.w = std::cos(angle / 2);
  return q;
}

}  // namespace

apex::Regions toRos(const Regions& regions) {
  apex::Regions out;
  out.header = regions.header;
  setSize(out, regions.image_size);
  out.regions.reserve(regions.regions.size());
  for (const Region& r : regions.regions) {
    apex::Region m;
    m.x = r.box.x, m.y = r.box.y, m.width = r.box.width, m.height = r.box.height;
    m.area = r.area;
    m.centroid_x = r.centroid.x, m.centroid_y = r.centroid.y;
    m.label = r.label;
    m.confidence = r.confidence;
    out.regions.push_back(m);
  }
  return out;
}

Regions fromRos(const apex::Regions& msg) {
  Regions out;
  out.header = msg.header;
  out.image_size = cv::Size(static_cast<int>(msg.width), static_cast<int>(msg.height));
  out.regions.reserve(msg.regions.size());
  for (const apex::Region& m : msg.regions) {
    Region r;
    r.box = cv::Rect(m.x, m.y, m.width, m.height);
    r.area = m.area;
    r.centroid = cv::Point2d(m.centroid_x, m.centroid_y);
    r.label = m.label;
    r.confidence = m.confidence;
    out.regions.push_back(r);
  }
  return out;
}

apex::Contours toRos(const Contours& contours) {
  apex::Contours out;
  out.header = contours.header;
  setSize(out, contours.image_size);
  out.contours.reserve(contours.contours.size());
  for (const auto& c : contours.contours) {
    apex::Contour m;
    m.x.reserve(c.size()), m.y.reserve(c.size());
    for (const cv::Point& p : c) m.x.push_back(p.x), m.y.push_back(p.y);
    out.contours.push_back(std::move(m));
  }
  out.hierarchy.reserve(4 * contours.hierarchy.size());
  for (const cv::Vec4i& h : contours.hierarchy) out.hierarchy.insert(out.hierarchy.end(), h.val, h.val + 4);
  return out;
}

apex::LineSegments toRos(const Lines& lines) {
  apex::LineSegments out;
  out.header = lines.header;
  setSize(out, lines.image_size);
  out.lines.reserve(lines.lines.size());
  for (const cv::Vec4f& l : lines.lines) {
    apex::LineSegment m;
    m.x1 = l[0], m.y1 = l[1], m.x2 = l[2], m.y2 = l[3];
    out.lines.push_back(m);
  }
  return out;
}

apex::Circles toRos(const Circles& circles) {
  apex::Circles out;
  out.header = circles.header;
  setSize(out, circles.image_size);
  out.circles.reserve(circles.circles.size());
  for (const cv::Vec3f& c : circles.circles) {
    apex::Circle m;
    m.x = c[0], m.y = c[1], m.radius = c[2];
    out.circles.push_back(m);
  }
  return out;
}

apex::FiducialMarkers toRos(const Markers& markers) {
  apex::FiducialMarkers out;
  out.header = markers.header;
  setSize(out, markers.image_size);
  out.dictionary = markers.dictionary;
  out.marker_length = markers.marker_length;
  out.markers.resize(markers.ids.size());
  for (std::size_t i = 0; i < markers.ids.size(); ++i) {
    out.markers[i].id = markers.ids[i];
    if (i < markers.corners.size()) out.markers[i].corners = points32(markers.corners[i]);
  }
  const std::size_t poses = std::min(markers.rvecs.size(), markers.tvecs.size());
  out.poses.resize(poses);
  for (std::size_t i = 0; i < poses; ++i) {
    const cv::Vec3d& t = markers.tvecs[i];
    out.poses[i].position.x = t[0], out.poses[i].position.y = t[1], out.poses[i].position.z = t[2];
    out.poses[i].orientation = quaternion(markers.rvecs[i]);
  }
  return out;
}

apex::ChessboardCorners toRos(const Corners& corners) {
  apex::ChessboardCorners out;
  out.header = corners.header;
  setSize(out, corners.image_size);
  out.pattern_width = static_cast<std::uint32_t>(std::max(0, corners.pattern_size.width));
  out.pattern_height = static_cast<std::uint32_t>(std::max(0, corners.pattern_size.height));
  out.found = corners.found;
  out.corners = points32(corners.corners);
  return out;
}

apex::Keypoints toRos(const Keypoints& keypoints) {
  apex::Keypoints out;
  out.header = keypoints.header;
  setSize(out, keypoints.image_size);
  out.method = keypoints.method;
  out.norm_type = keypoints.norm_type;
  out.keypoints.reserve(keypoints.keypoints.size());
  for (const cv::KeyPoint& k : keypoints.keypoints) {
    apex::Keypoint m;
    m.x = k.pt.x, m.y = k.pt.y;
    m.size = k.size;
    m.angle = k.angle;
    m.response = k.response;
    m.octave = k.octave;
    m.class_id = k.class_id;
    out.keypoints.push_back(m);
  }
  const cv::Mat& d = keypoints.descriptors;
  if (d.empty()) return out;
  const cv::Mat rows = d.reshape(1);  // channels as columns
  out.descriptor_rows = static_cast<std::uint32_t>(rows.rows);
  out.descriptor_cols = static_cast<std::uint32_t>(rows.cols);
  if (rows.depth() == CV_8U) {
    out.descriptors_binary.reserve(rows.total());
    for (int r = 0; r < rows.rows; ++r)
      out.descriptors_binary.insert(out.descriptors_binary.end(), rows.ptr<uchar>(r), rows.ptr<uchar>(r) + rows.cols);
  } else {
    cv::Mat floats;
    rows.convertTo(floats, CV_32F);
    out.descriptors_float.reserve(floats.total());
    for (int r = 0; r < floats.rows; ++r)
      out.descriptors_float.insert(out.descriptors_float.end(), floats.ptr<float>(r), floats.ptr<float>(r) + floats.cols);
  }
  return out;
}

apex::Matches toRos(const Matches& matches) {
  apex::Matches out;
  out.header = matches.header;
  out.matches.reserve(matches.matches.size());
  for (const cv::DMatch& d : matches.matches) {
    apex::Match m;
    m.query_idx = d.queryIdx, m.train_idx = d.trainIdx, m.img_idx = d.imgIdx;
    m.distance = d.distance;
    out.matches.push_back(m);
  }
  if (matches.query) out.query = toRos(*matches.query);
  if (matches.train) out.train = toRos(*matches.train);
  return out;
}

apex::Homography toRos(const Homography& homography) {
  apex::Homography out;
  out.header = homography.header;
  setSize(out, homography.image_size);
  out.found = homography.matrix.rows == 3 && homography.matrix.cols == 3 && homography.matrix.channels() == 1;
  if (out.found) {
    cv::Mat h;
    homography.matrix.convertTo(h, CV_64F);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.matrix[r * 3 + c] = h.at<double>(r, c);
  }
  out.inliers = homography.inliers;
  out.inlier_mask.assign(homography.inlier_mask.begin(), homography.inlier_mask.end());
  return out;
}

apex::Tracks toRos(const Tracks& tracks) {
  apex::Tracks out;
  out.header = tracks.header;
  setSize(out, tracks.image_size);
  out.previous = points32(tracks.previous);
  out.current = points32(tracks.current);
  out.status.assign(tracks.status.begin(), tracks.status.end());
  return out;
}

}  // namespace apex_nodes
