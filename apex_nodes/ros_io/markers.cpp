// MarkerPublisher: clusters' boxes (ClusterFeatures), a plane's outline (a hull), image regions'
// rays (Regions with their camera model), with `tracks` the paths of tracked regions' ids, and
// keypoints (Keypoints, on their rays) as visualization_msgs/MarkerArray, for rviz.
// Like the publishers of topic_sink.hpp it advertises at setup and when its topic changes, and
// builds an array only while someone subscribes. Also ClusterFeatures' inspector: a port of that
// type shows in rviz (~inspect) and is recorded (BagWriter) as the same boxes.
// State across frames: the paths (TrackMarkers) and the count of boxes last drawn, both the node's,
// touched only on its thread group (process, parameterChanged, endOfSequence, the reset slot).
#include "apex_nodes/markers.hpp"

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/features.hpp"

#include <ros/ros.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex/ros/inspect.hpp"
#include "apex/ros/node_handles.hpp"

namespace apex_nodes {
namespace {

constexpr double kMinScale = 0.001;  // rviz hides a box with a zero side: flat clusters keep a thin one

geometry_msgs::Point point(const Eigen::Vector3d& v) {
  geometry_msgs::Point p;
  p.x = v.x(), p.y = v.y(), p.z = v.z();
  return p;
}

geometry_msgs::Vector3 scale(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 s;
  s.x = std::max(v.x(), kMinScale), s.y = std::max(v.y(), kMinScale), s.z = std::max(v.z(), kMinScale);
  return s;
}

geometry_msgs::Quaternion quaternion(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion out;
  out.x = q.x(), out.y = q.y(), out.z = q.z(), out.w = q.w();
  return out;
}

float unit(int channel) { return static_cast<float>(std::clamp(channel, 0, 255)) / 255.f; }

/** A camera's rectified pinhole (P): where a pixel's ray is at depth d along the optical axis. */
struct Pinhole {
  explicit Pinhole(const sensor_msgs::CameraInfo& camera) : fx(camera.P[0]), fy(camera.P[5]), cx(camera.P[2]), cy(camera.P[6]) {
    if (fx == 0 || fy == 0)
      throw std::invalid_argument("camera model on frame '" + camera.header.frame_id +
                                  "' is not calibrated: P has no focal length");
  }
  geometry_msgs::Point at(double u, double v, double d) const {
    geometry_msgs::Point p;
    p.x = (u - cx) / fx * d, p.y = (v - cy) / fy * d, p.z = d;
    return p;
  }
  double fx, fy, cx, cy;
};

/** A marker of `ns` and `id` with `header`, the options' lifetime and a valid (identity) orientation. */
visualization_msgs::Marker marker(const std_msgs::Header& header, const MarkerOptions& options, const std::string& ns, int id,
                                  int action) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = id;
  m.action = action;
  m.pose.orientation.w = 1.0;
  m.lifetime = ros::Duration(std::max(0.0, options.lifetime));
  return m;
}

/** One marker (id 0) of `type` drawn `width` wide in the options' colour: a hull, rays, points. */
visualization_msgs::Marker drawing(const std_msgs::Header& header, const MarkerOptions& options, const std::string& ns, int type,
                                   double width) {
  visualization_msgs::Marker m = marker(header, options, ns, 0, visualization_msgs::Marker::ADD);
  m.type = type;
  m.scale.x = width;
  m.color.r = unit(options.color.r), m.color.g = unit(options.color.g), m.color.b = unit(options.color.b), m.color.a = 1.f;
  return m;
}

}  // namespace

visualization_msgs::MarkerArray clusterMarkers(const ClusterFeatures& features, const MarkerOptions& options,
                                               std::size_t last_count) {
  using visualization_msgs::Marker;
  const std::string label_ns = options.ns + "/labels";
  visualization_msgs::MarkerArray out;
  if (features.clusters.size() < last_count)
    out.markers.push_back(marker(features.header, options, options.ns, 0, Marker::DELETEALL));
  for (std::size_t i = 0; i < features.clusters.size(); ++i) {
    const ClusterFeature& f = features.clusters[i];
    const int id = static_cast<int>(i);
    if (f.points == 0) {  // nothing to draw: none of an earlier array's boxes either
      out.markers.push_back(marker(features.header, options, options.ns, id, Marker::DELETE));
      if (options.labels) out.markers.push_back(marker(features.header, options, label_ns, id, Marker::DELETE));
      continue;
    }
    Marker box = marker(features.header, options, options.ns, id, Marker::ADD);
    box.type = Marker::CUBE;
    double half_height = 0;  // how far the box reaches above its centre, in the frame's z
    if (options.oriented) {
      box.pose.position = point(f.oriented.centre);
      box.pose.orientation = quaternion(f.oriented.orientation);
      box.scale = scale(f.oriented.extent);
      const Eigen::Matrix3d r = f.oriented.orientation.toRotationMatrix();
      for (int k = 0; k < 3; ++k) half_height += 0.5 * std::abs(r(2, k)) * f.oriented.extent[k];
    } else {
      box.pose.position = point(f.centre());
      box.scale = scale(f.extent);
      half_height = 0.5 * f.extent.z();
    }
    box.color.r = unit(options.color.r), box.color.g = unit(options.color.g), box.color.b = unit(options.color.b);
    box.color.a = static_cast<float>(std::clamp(options.alpha, 0.0, 1.0));
    out.markers.push_back(box);
    if (!options.labels) continue;
    Marker text = marker(features.header, options, label_ns, id, Marker::ADD);
    text.type = Marker::TEXT_VIEW_FACING;
    text.text = std::to_string(f.label) + ": " + std::to_string(f.points) + " points";
    text.pose.position = box.pose.position;
    text.pose.position.z += half_height + 0.75 * options.text_height;
    text.scale.x = text.scale.y = text.scale.z = std::max(options.text_height, kMinScale);  // rviz reads z: the letters' height
    text.color.r = text.color.g = text.color.b = text.color.a = 1.f;
    out.markers.push_back(text);
  }
  return out;
}

visualization_msgs::Marker hullMarker(const Cloud& hull, const MarkerOptions& options) {
  const auto points = xyzOf(hull);
  if (points->size() < 3) throw std::invalid_argument("a hull of " + std::to_string(points->size()) + " points outlines nothing");
  visualization_msgs::Marker m =
      drawing(hull.header, options, options.ns + "/plane", visualization_msgs::Marker::LINE_STRIP, 0.01);
  for (const auto& p : *points) {
    geometry_msgs::Point q;
    q.x = p.x, q.y = p.y, q.z = p.z;
    m.points.push_back(q);
  }
  m.points.push_back(m.points.front());  // closed
  return m;
}

visualization_msgs::Marker regionRays(const Regions& regions, const sensor_msgs::CameraInfo& camera,
                                      const MarkerOptions& options) {
  const Pinhole pinhole(camera);
  visualization_msgs::Marker m =
      drawing(regions.header, options, options.ns + "/rays", visualization_msgs::Marker::LINE_LIST, 0.005);
  auto at = [&](double u, double v) { return pinhole.at(u, v, options.ray_length); };  // the pixel's point at ray_length
  for (const auto& r : regions.regions) {
    m.points.push_back(geometry_msgs::Point());  // the camera's origin
    m.points.push_back(at(r.centroid.x, r.centroid.y));
    const cv::Rect& b = r.box;
    const geometry_msgs::Point c[4] = {at(b.x, b.y), at(b.x + b.width, b.y), at(b.x + b.width, b.y + b.height),
                                       at(b.x, b.y + b.height)};
    for (int k = 0; k < 4; ++k) m.points.push_back(c[k]), m.points.push_back(c[(k + 1) % 4]);
  }
  return m;
}

visualization_msgs::Marker keypointPoints(const Keypoints& keypoints, const sensor_msgs::CameraInfo& camera,
                                          const MarkerOptions& options) {
  const Pinhole pinhole(camera);
  visualization_msgs::Marker m =
      drawing(keypoints.header, options, options.ns + "/keypoints", visualization_msgs::Marker::POINTS, 0.01);
  m.scale.y = m.scale.x;
  m.points.reserve(keypoints.keypoints.size());
  for (const cv::KeyPoint& k : keypoints.keypoints) m.points.push_back(pinhole.at(k.pt.x, k.pt.y, options.ray_length));
  return m;
}

namespace {

constexpr double kTrackWidth = 0.01;  // a path's line, metres

/** Track `id`'s colour: a full hue, the golden ratio of a turn from the previous id's, so that
 *  consecutive ids (MultiObjectTracker counts from 1) never look alike; the same id always the same. */
std_msgs::ColorRGBA trackColor(int id) {
  const double hue = std::fmod(id * 0.618033988749895, 1.0) * 6.0;  // in sixths of a turn
  auto channel = [hue](double n) {  // HSV to RGB at full saturation and value
    const double k = std::fmod(n + hue, 6.0);
    return static_cast<float>(1.0 - std::clamp(std::min(k, 4.0 - k), 0.0, 1.0));
  };
  std_msgs::ColorRGBA c;
  c.r = channel(5), c.g = channel(3), c.b = channel(1), c.a = 1.f;
  return c;
}

/** What TrackMarkers draws of a track: a path's line, or its "#id". */
enum class TrackPart { kLine, kText };

/** Part `part` of track `id` as drawTrack adds it or eraseTrack deletes it, in its namespace
 *  ("<ns>/tracks" or "<ns>/tracks/ids"); an ADD also has the part's type and the id's colour. */
visualization_msgs::Marker trackMarker(const std_msgs::Header& header, const MarkerOptions& options, int id, TrackPart part,
                                       int action) {
  using visualization_msgs::Marker;
  const bool text = part == TrackPart::kText;
  Marker m = marker(header, options, options.ns + (text ? "/tracks/ids" : "/tracks"), id, action);
  if (action == Marker::ADD) {
    m.type = text ? Marker::TEXT_VIEW_FACING : Marker::LINE_STRIP;
    m.color = trackColor(id);
  }
  return m;
}

/** Track `id`'s path through `points` (oldest first; rviz refuses a strip of one point) and
 *  "#id" at the newest, in the id's colour. */
void drawTrack(const std_msgs::Header& header, const MarkerOptions& options, int id,
               const std::deque<geometry_msgs::Point>& points, visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  if (points.size() >= 2) {
    Marker line = trackMarker(header, options, id, TrackPart::kLine, Marker::ADD);
    line.scale.x = kTrackWidth;
    line.points.assign(points.begin(), points.end());
    out.markers.push_back(std::move(line));
  }
  Marker text = trackMarker(header, options, id, TrackPart::kText, Marker::ADD);
  text.text = "#" + std::to_string(id);
  text.pose.position = points.back();
  text.scale.x = text.scale.y = text.scale.z = std::max(options.text_height, kMinScale);  // rviz reads z
  out.markers.push_back(std::move(text));
}

/** DELETEs for what drawTrack drew of track `id`: both, as its line may have been drawn (rviz
 *  ignores a DELETE of a marker it does not have). */
void eraseTrack(const std_msgs::Header& header, const MarkerOptions& options, int id, visualization_msgs::MarkerArray& out) {
  for (TrackPart part : {TrackPart::kLine, TrackPart::kText})
    out.markers.push_back(trackMarker(header, options, id, part, visualization_msgs::Marker::DELETE));
}

}  // namespace

visualization_msgs::MarkerArray TrackMarkers::update(const Regions& regions, const sensor_msgs::CameraInfo& camera,
                                                     const MarkerOptions& options) {
  const Pinhole pinhole(camera);  // first: a model that throws changes nothing
  const std::size_t length = static_cast<std::size_t>(std::max(options.track_length, 1));
  header_ = regions.header;
  options_ = options;
  std::set<int> seen;  // the ids that got their point this frame
  for (const Region& r : regions.regions) {
    if (r.label < 0 || !seen.insert(r.label).second) continue;  // no id; an id met already this frame
    const cv::Rect& b = r.box;  // its middle as regionRays draws the box: corners at x and x + width
    Track& t = tracks_[r.label];
    t.points.push_back(pinhole.at(b.x + b.width / 2.0, b.y + b.height / 2.0, options.ray_length));
    while (t.points.size() > length) t.points.pop_front();
  }
  visualization_msgs::MarkerArray out;
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    Track& t = it->second;
    if (seen.count(it->first)) {
      t.unseen = 0;
      drawTrack(header_, options_, it->first, t.points, out);
    } else if (++t.unseen >= length) {  // gone: rviz would keep its path for ever
      eraseTrack(header_, options_, it->first, out);
      it = tracks_.erase(it);
      continue;
    }
    ++it;
  }
  return out;
}

visualization_msgs::MarkerArray TrackMarkers::reset() {
  std_msgs::Header header = header_;
  header.stamp = ros::Time();  // rviz (its tf filter) places a DELETE of stamp 0 at once, however late it comes
  visualization_msgs::MarkerArray out;
  for (const auto& entry : tracks_) eraseTrack(header, options_, entry.first, out);
  tracks_.clear();
  return out;
}

namespace {

// A ClusterFeatures port inspected or recorded: its boxes as MarkerPublisher draws them by default.
// Each array clears first: its viewer may have seen any array before it. A MarkerArray has no
// header of its own: a recording takes the features' stamp.
const bool kInspectorRegistered = [] {
  const apex::TypeInfo* type = apex::typeOf<ClusterFeatures>();
  apex::addInspector<ClusterFeatures, visualization_msgs::MarkerArray>(
      [](const ClusterFeatures& f) { return clusterMarkers(f, MarkerOptions(), kUnknownMarkerCount); });
  apex::Inspector inspector = apex::findInspector(type);
  inspector.serialize = [serialize = inspector.serialize](const apex::Message& m) {
    apex::SerializedMessage out = serialize(m);
    if (auto f = m.as<ClusterFeatures>()) out.stamp = f->header.stamp;
    return out;
  };
  apex::registerInspector(type, std::move(inspector));
  apex::addDescribe<ClusterFeatures>([](const ClusterFeatures& f) {
    return std::to_string(f.clusters.size()) + (f.clusters.size() == 1 ? " cluster" : " clusters");
  });
  return true;
}();

}  // namespace

class MarkerPublisher : public apex::Node {
 public:
  static inline const apex::InputPort<ClusterFeatures> kFeatures{"features", "if connected: the clusters to draw", true};
  static inline const apex::InputPort<Regions> kRegions{
      "regions", "if connected: regions of a camera's image, drawn as rays and boxes (needs camera_info)", true};
  static inline const apex::InputPort<Keypoints> kKeypoints{
      "keypoints", "if connected: keypoints of a camera's image, drawn as points on their rays (needs camera_info)", true};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kCamera{"camera_info", "the regions' and keypoints' camera model",
                                                                       true};
  static inline const apex::InputPort<Cloud> kHull{"hull", "if connected: a plane's hull (ConvexHull), drawn as its outline",
                                                   true};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("markers").describe("resolved in the runtime's namespace");
  static inline const apex::ParamDecl<std::string> kNamespace =
      apex::param::text("namespace").init("clusters").describe("the markers' ns; labels go in '<namespace>/labels'");
  static inline const apex::ParamDecl<bool> kOriented =
      apex::param::flag("oriented").describe("oriented boxes (PCA axes) instead of axis-aligned ones");
  static inline const apex::ParamDecl<bool> kLabels =
      apex::param::flag("labels").init(true).describe("each cluster's label and point count above its box");
  static inline const apex::ParamDecl<apex::Color> kColor = apex::param::color("color").init({0, 255, 0});
  static inline const apex::ParamDecl<double> kAlpha =
      apex::param::number("alpha").range(0.0, 1.0).step(0.05).init(0.5).describe("the boxes' opacity");
  static inline const apex::ParamDecl<double> kTextHeight =
      apex::param::number("text_height").range(0.005, 2.0).step(0.005).init(0.15).describe("the labels' letter height, metres");
  static inline const apex::ParamDecl<double> kRayLength =
      apex::param::number("ray_length")
          .range(0.01, 100.0)
          .step(0.01)
          .init(2.0)
          .describe("regions and keypoints: how far from the camera their rays, boxes and points reach, metres");
  static inline const apex::ParamDecl<bool> kTracks = apex::param::flag("tracks").describe(
      "regions: their labels are track ids (MultiObjectTracker's): each id's path through its boxes' middles, with '#id', "
      "in '<namespace>/tracks' and '<namespace>/tracks/ids'");
  static inline const apex::ParamDecl<int> kTrackLength =
      apex::param::integer("track_length")
          .range(2, 1000)
          .step(1)
          .init(30)
          .describe("tracks: the last points each path keeps; an id unseen for as many frames is deleted");
  static inline const apex::ParamDecl<double> kLifetime =
      apex::param::number("lifetime")
          .range(0.0, 3600.0)
          .step(0.1)
          .init(0.0)
          .describe("seconds a box stays without an update; 0: until the next message replaces it");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Publishes clusters' boxes, a plane's outline, image regions' rays (and tracked ones' paths) and keypoints as "
               "visualization_msgs/MarkerArray, for rviz")
        .inCategory("ROS I/O")
        .keepsState("with tracks on, each id's last points: a re-run of the held frame adds its regions' middles again")
        .input(kFeatures)
        .input(kHull)
        .input(kRegions)
        .input(kKeypoints)
        .input(kCamera)
        .param(kTopic)
        .param(kNamespace)
        .param(kOriented)
        .param(kLabels)
        .param(kColor)
        .param(kAlpha)
        .param(kTextHeight)
        .param(kRayLength)
        .param(kTracks)
        .param(kTrackLength)
        .param(kLifetime)
        .slot("reset", &MarkerPublisher::reset, "tracks: forgets every id, and deletes their paths in rviz");
  }

  void setup() override { advertise(); }
  void parameterChanged(const std::string& name) override {
    reset();  // on the topic drawn to, in the namespace drawn in: no path mixes two settings
    if (name == kTopic.name()) advertise();
    last_count_ = kUnknownMarkerCount;  // the next array clears what this one's options drew
  }
  /** A new pass of a sequence starts as the first did: MultiObjectTracker gives its ids again. */
  void endOfSequence() override {
    reset();
    endSequence();
  }
  /** Forgets every track, and tells a viewer to delete their markers. */
  void reset() {
    const visualization_msgs::MarkerArray deletes = track_markers_.reset();
    if (!deletes.markers.empty() && pub_.getNumSubscribers() > 0) pub_.publish(deletes);
  }

  void process() override {
    if (pub_.getNumSubscribers() == 0) {  // a viewer that subscribes later may have seen anything
      last_count_ = kUnknownMarkerCount;
      track_markers_.reset();  // nobody saw them: paths start again when someone looks
      return;
    }
    visualization_msgs::MarkerArray markers;
    if (const auto in = features_.get()) {
      markers = clusterMarkers(*in, options(), last_count_);
      last_count_ = in->clusters.size();
    }
    if (const auto hull = hull_.get()) markers.markers.push_back(hullMarker(*hull, options()));
    auto camera = [this](const char* what) {
      const auto c = camera_.get();
      if (!c) throw std::invalid_argument(std::string(what) + " need their camera's model: connect camera_info");
      return c;
    };
    if (const auto regions = regions_.get()) {
      const auto model = camera("regions");
      markers.markers.push_back(regionRays(*regions, *model, options()));
      if (tracks_.get()) {
        const visualization_msgs::MarkerArray paths = track_markers_.update(*regions, *model, options());
        markers.markers.insert(markers.markers.end(), paths.markers.begin(), paths.markers.end());
      }
    }
    if (const auto keypoints = keypoints_.get())
      markers.markers.push_back(keypointPoints(*keypoints, *camera("keypoints"), options()));
    if (!markers.markers.empty()) pub_.publish(markers);
  }

 private:
  void advertise() { pub_ = apex::nodeHandle(*this).advertise<visualization_msgs::MarkerArray>(topic_.get(), 1); }
  MarkerOptions options() const {
    MarkerOptions o;
    o.ns = namespace_.get();
    o.oriented = oriented_.get();
    o.labels = labels_.get();
    o.color = color_.get();
    o.alpha = alpha_.get();
    o.text_height = text_height_.get();
    o.ray_length = ray_length_.get();
    o.track_length = track_length_.get();
    o.lifetime = lifetime_.get();
    return o;
  }

  apex::Input<ClusterFeatures> features_{this, kFeatures};
  apex::Input<Cloud> hull_{this, kHull};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Input<Keypoints> keypoints_{this, kKeypoints};
  apex::Input<sensor_msgs::CameraInfo> camera_{this, kCamera};
  apex::Param<std::string> topic_{this, kTopic};
  apex::Param<std::string> namespace_{this, kNamespace};
  apex::Param<bool> oriented_{this, kOriented};
  apex::Param<bool> labels_{this, kLabels};
  apex::Param<apex::Color> color_{this, kColor};
  apex::Param<double> alpha_{this, kAlpha};
  apex::Param<double> text_height_{this, kTextHeight};
  apex::Param<double> ray_length_{this, kRayLength};
  apex::Param<bool> tracks_{this, kTracks};
  apex::Param<int> track_length_{this, kTrackLength};
  apex::Param<double> lifetime_{this, kLifetime};
  ros::Publisher pub_;
  std::size_t last_count_ = kUnknownMarkerCount;  // the first array clears what an earlier run left
  TrackMarkers track_markers_;  // empty while tracks is off
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::MarkerPublisher, "apex_nodes/MarkerPublisher");
