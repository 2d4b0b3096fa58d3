// MarkerPublisher's tracks (TrackMarkers, markers.hpp): regions with ids (MultiObjectTracker's) as
// paths through their boxes' middles on their rays, with "#id" at the newest, over frames: points
// kept and trimmed, colours by id, DELETEs for an id gone and on reset. No master: nothing here
// advertises.
#include <gmock/gmock.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "apex_nodes/markers.hpp"

namespace {

using visualization_msgs::Marker;

/** The camera of every frame here: 500 and 400 pixels focal length, principal point (320, 240). */
sensor_msgs::CameraInfo trackCamera() {
  sensor_msgs::CameraInfo camera;
  camera.header.frame_id = "camera";
  camera.P = {500, 0, 320, 0, 0, 400, 240, 0, 0, 0, 1, 0};
  return camera;
}

/** Every frame's header, so every marker's: the camera's frame, a stamp of its own. */
std_msgs::Header header() {
  std_msgs::Header h = trackCamera().header;
  h.stamp = ros::Time(1700000000, 123456789);
  h.seq = 7;
  return h;
}

/** One frame of tracked regions: each (id, box), with header(). */
apex_nodes::Regions trackedFrame(const std::vector<std::pair<int, cv::Rect>>& boxes) {
  apex_nodes::Regions out;
  out.header = header();
  out.image_size = cv::Size(640, 480);
  for (const auto& [id, box] : boxes) {
    apex_nodes::Region r;
    r.box = box, r.area = box.area(), r.label = id;
    r.centroid = cv::Point2d(box.x + 3, box.y + 5);  // not the box's middle: the path takes the box's
    out.regions.push_back(r);
  }
  return out;
}

/** The middle of `box` as regionRays draws the box: halfway between its corners (x, y) and
 *  (x + width, y + height), which are its points 2 and 6 (after the ray to the centroid, the
 *  edges from (x, y) round the box, each as two points). */
geometry_msgs::Point drawnMiddle(const cv::Rect& box, const apex_nodes::MarkerOptions& options) {
  apex_nodes::Regions one = trackedFrame({{1, box}});
  const Marker rays = apex_nodes::regionRays(one, trackCamera(), options);
  const geometry_msgs::Point &a = rays.points.at(2), &b = rays.points.at(6);
  geometry_msgs::Point m;
  m.x = (a.x + b.x) / 2, m.y = (a.y + b.y) / 2, m.z = (a.z + b.z) / 2;
  return m;
}

/** The marker of `ns` and `id` in `a`, or nullptr; fails if there are two. */
const Marker* markerOf(const visualization_msgs::MarkerArray& a, const std::string& ns, int id) {
  const Marker* found = nullptr;
  for (const Marker& m : a.markers)
    if (m.ns == ns && m.id == id) {
      EXPECT_EQ(found, nullptr) << ns << " " << id << " twice";
      found = &m;
    }
  return found;
}

void expectPoint(const geometry_msgs::Point& got, const geometry_msgs::Point& want) {
  EXPECT_NEAR(got.x, want.x, 1e-12);
  EXPECT_NEAR(got.y, want.y, 1e-12);
  EXPECT_NEAR(got.z, want.z, 1e-12);
}

/** A path through the middles of `boxes`, oldest first, with the header and the colour. */
void expectPath(const Marker* line, const std::vector<cv::Rect>& boxes, const apex_nodes::MarkerOptions& options,
                const std_msgs::ColorRGBA& colour) {
  ASSERT_NE(line, nullptr);
  EXPECT_EQ(line->type, Marker::LINE_STRIP);
  EXPECT_EQ(line->action, Marker::ADD);
  EXPECT_EQ(line->header, header());
  EXPECT_GT(line->scale.x, 0.0);
  EXPECT_EQ(line->color, colour);
  ASSERT_EQ(line->points.size(), boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    expectPoint(line->points[i], drawnMiddle(boxes[i], options));
  }
}

/** "#id" at the middle of `newest`, in the id's colour (returned). */
std_msgs::ColorRGBA expectText(const Marker* text, int id, const cv::Rect& newest, const apex_nodes::MarkerOptions& options) {
  EXPECT_NE(text, nullptr);
  if (!text) return {};
  EXPECT_EQ(text->type, Marker::TEXT_VIEW_FACING);
  EXPECT_EQ(text->action, Marker::ADD);
  EXPECT_EQ(text->header, header());
  EXPECT_EQ(text->text, "#" + std::to_string(id));
  expectPoint(text->pose.position, drawnMiddle(newest, options));
  EXPECT_DOUBLE_EQ(text->scale.z, options.text_height);
  EXPECT_FLOAT_EQ(text->color.a, 1.f);
  return text->color;
}

// Id 1 walks right in each frame; id 2 is seen in frames 0 and 1, then no more; a region without
// an id is never drawn. Paths keep track_length (3) points, and id 2 is deleted in the third frame
// it is missing from (frame 4), not before.
TEST(MarkerPublisher, TracksArePathsThroughTheirBoxesMiddlesOnTheirRays) {
  apex_nodes::MarkerOptions options;
  options.ns = "people";
  options.ray_length = 4.0;
  options.track_length = 3;
  const auto one = [](int frame) { return cv::Rect(100 + 40 * frame, 200, 40, 80); };
  const cv::Rect two(400, 100, 20, 30);
  const cv::Rect unlabelled(10, 10, 5, 5);
  apex_nodes::TrackMarkers tracks;

  // frame 0: one point each: no line yet (rviz refuses a strip of one point), the ids
  const auto f0 = tracks.update(trackedFrame({{1, one(0)}, {2, two}, {-1, unlabelled}}), trackCamera(), options);
  EXPECT_EQ(f0.markers.size(), 2u);
  EXPECT_EQ(markerOf(f0, "people/tracks", 1), nullptr);
  EXPECT_EQ(markerOf(f0, "people/tracks", 2), nullptr);
  const std_msgs::ColorRGBA colour1 = expectText(markerOf(f0, "people/tracks/ids", 1), 1, one(0), options);
  const std_msgs::ColorRGBA colour2 = expectText(markerOf(f0, "people/tracks/ids", 2), 2, two, options);
  EXPECT_NE(colour1, colour2);
  EXPECT_EQ(markerOf(f0, "people/tracks/ids", -1), nullptr);

  // frame 1: both lines, each in its id's colour
  const auto f1 = tracks.update(trackedFrame({{2, two}, {1, one(1)}}), trackCamera(), options);
  EXPECT_EQ(f1.markers.size(), 4u);
  expectPath(markerOf(f1, "people/tracks", 1), {one(0), one(1)}, options, colour1);
  expectPath(markerOf(f1, "people/tracks", 2), {two, two}, options, colour2);
  EXPECT_EQ(expectText(markerOf(f1, "people/tracks/ids", 1), 1, one(1), options), colour1);
  EXPECT_EQ(expectText(markerOf(f1, "people/tracks/ids", 2), 2, two, options), colour2);

  // frames 2, 3: id 2 missing: nothing of it, its path stays as drawn; id 1's keeps its last 3 points
  for (int frame : {2, 3}) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const auto f = tracks.update(trackedFrame({{1, one(frame)}}), trackCamera(), options);
    EXPECT_EQ(f.markers.size(), 2u);
    std::vector<cv::Rect> last;
    for (int k = std::max(0, frame - 2); k <= frame; ++k) last.push_back(one(k));
    expectPath(markerOf(f, "people/tracks", 1), last, options, colour1);
    EXPECT_EQ(expectText(markerOf(f, "people/tracks/ids", 1), 1, one(frame), options), colour1);
    EXPECT_EQ(markerOf(f, "people/tracks", 2), nullptr);
    EXPECT_EQ(markerOf(f, "people/tracks/ids", 2), nullptr);
  }

  // frame 4: id 2 missing from 3 frames (track_length): its line and text deleted, in its frame
  const auto f4 = tracks.update(trackedFrame({{1, one(4)}}), trackCamera(), options);
  EXPECT_EQ(f4.markers.size(), 4u);
  expectPath(markerOf(f4, "people/tracks", 1), {one(2), one(3), one(4)}, options, colour1);
  for (const char* ns : {"people/tracks", "people/tracks/ids"}) {
    SCOPED_TRACE(ns);
    const Marker* gone = markerOf(f4, ns, 2);
    ASSERT_NE(gone, nullptr);
    EXPECT_EQ(gone->action, Marker::DELETE);
    EXPECT_EQ(gone->header.frame_id, "camera");
  }

  // frame 5: id 2 forgotten: a new object with that id starts a new path; nothing deleted again
  const auto f5 = tracks.update(trackedFrame({{1, one(5)}, {2, one(0)}}), trackCamera(), options);
  EXPECT_EQ(f5.markers.size(), 3u);
  EXPECT_EQ(markerOf(f5, "people/tracks", 2), nullptr);
  EXPECT_EQ(expectText(markerOf(f5, "people/tracks/ids", 2), 2, one(0), options), colour2);
}

TEST(MarkerPublisher, TracksResetDeletesEveryPathAndStartsAgainInTheSameColours) {
  apex_nodes::MarkerOptions options;
  options.ns = "people";
  options.track_length = 5;
  const cv::Rect a(100, 100, 20, 40), b(300, 200, 10, 10);
  apex_nodes::TrackMarkers tracks;
  EXPECT_TRUE(tracks.reset().markers.empty());  // none yet
  (void)tracks.update(trackedFrame({{7, a}, {8, b}}), trackCamera(), options);
  const auto before = tracks.update(trackedFrame({{7, a}, {8, b}}), trackCamera(), options);
  ASSERT_NE(markerOf(before, "people/tracks", 7), nullptr);
  const std_msgs::ColorRGBA colour7 = markerOf(before, "people/tracks", 7)->color;

  const auto deletes = tracks.reset();
  EXPECT_EQ(deletes.markers.size(), 4u);  // line and text of 7 and 8
  for (int id : {7, 8})
    for (const char* ns : {"people/tracks", "people/tracks/ids"}) {
      SCOPED_TRACE(std::string(ns) + " " + std::to_string(id));
      const Marker* gone = markerOf(deletes, ns, id);
      ASSERT_NE(gone, nullptr);
      EXPECT_EQ(gone->action, Marker::DELETE);
      EXPECT_EQ(gone->header.frame_id, "camera");
    }
  EXPECT_TRUE(tracks.reset().markers.empty());  // all forgotten

  const auto after = tracks.update(trackedFrame({{7, b}}), trackCamera(), options);  // one point again: no line
  EXPECT_EQ(markerOf(after, "people/tracks", 7), nullptr);
  EXPECT_EQ(expectText(markerOf(after, "people/tracks/ids", 7), 7, b, options), colour7);
  EXPECT_EQ(apex_nodes::TrackMarkers().update(trackedFrame({{7, a}}), trackCamera(), options).markers.at(0).color,
            colour7);  // every TrackMarkers: the same colour for an id

  sensor_msgs::CameraInfo uncalibrated = trackCamera();
  uncalibrated.P = {};
  EXPECT_THROW((void)tracks.update(trackedFrame({{7, a}}), uncalibrated, options), std::invalid_argument);
  EXPECT_EQ(tracks.reset().markers.size(), 2u);  // the throw changed nothing: 7 is still there
}

}  // namespace
