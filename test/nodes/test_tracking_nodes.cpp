// Tracking nodes (tracking.cpp, kalman_filter.cpp, multi_tracker.cpp) on opencv-doc's pedestrians
// (vtest.avi), against the OpenCV calls made directly: Tracker frame by frame against the same
// cv::TrackerKCF, TrackerCSRT and TrackerMIL started on the same box (box-exact: all three are
// repeatable, MIL once its random generators are seeded alike); KalmanFilter against a
// cv::KalmanFilter given the same matrices, over a pedestrian's track; MultiObjectTracker's ids on
// HOG's people detections, and on boxes made to cross, vanish and come back; its least-cost
// assignment against trying every pairing.
#include <gmock/gmock.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <numeric>
#include <opencv2/objdetect.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videoio.hpp>
#include <tuple>

#include "../../apex_nodes/opencv/assignment.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using apex_nodes::Region;
using apex_nodes::Regions;

namespace {

constexpr int kFrames = 50;  // of vtest.avi: 5 s of people walking
constexpr int kTracked = 30;  // frames each tracker follows its pedestrian

/** The first kFrames frames of vtest.avi, bgr8 (read once). */
const std::vector<std::shared_ptr<const Image>>& pedestrians() {
  static const auto frames = [] {
    cv::VideoCapture video(kOpenCvData + "/vtest.avi");
    std::vector<std::shared_ptr<const Image>> out;
    cv::Mat frame;
    while (int(out.size()) < kFrames && video.read(frame)) out.push_back(imageOf(frame.clone(), "bgr8"));
    return out;
  }();
  if (int(frames.size()) != kFrames) ADD_FAILURE() << "cannot read " << kFrames << " frames of " << kOpenCvData << "/vtest.avi";
  return frames;
}

/** HOG's people in each of those frames (OpenCV's default people detector, HOGPeopleDetector's defaults; made once). */
const std::vector<std::vector<cv::Rect>>& people() {
  static const auto found = [] {
    cv::HOGDescriptor hog;
    hog.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
    std::vector<std::vector<cv::Rect>> out;
    for (const auto& frame : pedestrians()) {
      std::vector<cv::Rect> boxes;
      std::vector<double> weights;
      hog.detectMultiScale(frame->mat, boxes, weights, 0, cv::Size(8, 8), cv::Size(), 1.05, 2, false);
      std::sort(boxes.begin(), boxes.end(), [](const cv::Rect& a, const cv::Rect& b) {  // threads find them in any order
        return std::make_tuple(a.x, a.y, a.width, a.height) < std::make_tuple(b.x, b.y, b.width, b.height);
      });
      out.push_back(boxes);
    }
    return out;
  }();
  return found;
}

/** The first frame where HOG finds a person wholly inside it, and the largest such person's box. */
std::pair<int, cv::Rect> firstPerson() {
  for (int f = 0; f < int(people().size()); ++f) {
    const cv::Rect frame(cv::Point(), pedestrians()[f]->mat.size());
    cv::Rect best;
    for (const cv::Rect& b : people()[f])
      if ((b & frame) == b && b.area() > best.area()) best = b;
    if (!best.empty()) return {f, best};
  }
  ADD_FAILURE() << "HOG finds nobody in vtest.avi";
  return {0, cv::Rect(300, 200, 64, 128)};
}

/** A second sink, on another output of the harness's node. */
Collector* tap(NodeHarness& h, const std::string& output) {
  add(h.graph(), "test/Collector", "tap_" + output);
  link(h.graph(), "node", output, "tap_" + output, "in");
  return object<Collector>(h.graph(), "tap_" + output);
}

template <class T>
std::shared_ptr<const T> lastOf(Collector* sink) {
  return sink->size() ? sink->messages().back().as<T>() : nullptr;
}

std::shared_ptr<const Regions> regionsFrom(const Message& m, NodeHarness& h) {
  auto r = m.as<Regions>();
  if (!r) ADD_FAILURE() << "expected regions, got " << m.typeName() << ": " << h.error();
  return r;
}

/** Regions of `boxes` as a detector sends them (label 0, centroid the box's middle). */
std::shared_ptr<const Regions> regionsOf(const std::vector<cv::Rect>& boxes, ros::Time stamp = ros::Time(42, 7)) {
  auto r = std::make_shared<Regions>();
  r->header.stamp = stamp;
  r->header.frame_id = "camera";
  r->image_size = cv::Size(768, 576);
  for (const cv::Rect& b : boxes) {
    Region region;
    region.box = b;
    region.area = b.area();
    region.centroid = cv::Point2d(b.x + (b.width - 1) / 2.0, b.y + (b.height - 1) / 2.0);
    region.label = 0;
    r->regions.push_back(region);
  }
  return r;
}

std::vector<double> valuesOf(const cv::Mat& m) { return std::vector<double>(m.begin<double>(), m.end<double>()); }

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double overlap = (a & b).area();
  return overlap / (a.area() + b.area() - overlap);
}

// --- Tracker

/** `method`'s OpenCV tracker made and started as the node makes it (mil: after seeding with the node's seed, 1). */
cv::Ptr<cv::Tracker> startedTracker(const std::string& method, const cv::Mat& frame, const cv::Rect& box) {
  cv::Ptr<cv::Tracker> t;
  if (method == "kcf") {
    t = cv::TrackerKCF::create();
  } else if (method == "csrt") {
    t = cv::TrackerCSRT::create();
  } else {
    cv::setRNGSeed(1);  // MIL's sampler copies this thread's generator,
    std::srand(1);  // and its Haar features are drawn with rand()
    t = cv::TrackerMIL::create();
  }
  t->init(frame, box);
  return t;
}

/** Expects what the node sent on frame `i` to be the direct tracker's: `want` if `found`, else nothing. */
void expectTracked(const std::shared_ptr<const Regions>& got, Collector* found_out, bool found, const cv::Rect& want, int i) {
  ASSERT_TRUE(got);
  ASSERT_TRUE(lastOf<bool>(found_out));
  EXPECT_EQ(*lastOf<bool>(found_out), found) << "frame " << i;
  ASSERT_EQ(got->regions.size(), found ? 1u : 0u) << "frame " << i;
  if (!found) return;
  EXPECT_EQ(got->regions[0].box, want) << "frame " << i;
  EXPECT_EQ(got->regions[0].centroid, cv::Point2d(want.x + (want.width - 1) / 2.0, want.y + (want.height - 1) / 2.0));
}

void setBox(NodeHarness& h, const cv::Rect& b) {
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, int>>{{"x", b.x}, {"y", b.y}, {"width", b.width}, {"height", b.height}})
    h.set(name, std::to_string(value));
}

TEST(TrackingNodes, TrackerFollowsAPedestrianAsOpenCVsTrackersDo) {
  const auto& frames = pedestrians();
  const auto [first, person] = firstPerson();
  ASSERT_LE(first + kTracked, int(frames.size()));
  for (const std::string method : {"kcf", "csrt", "mil"}) {
    SCOPED_TRACE(method);
    NodeHarness h("apex_nodes/Tracker", {"image"}, "regions");
    Collector* found = tap(h, "found");
    h.set("method", method);
    setBox(h, person);
    cv::Ptr<cv::Tracker> tracker = startedTracker(method, frames[first]->mat, person);
    int seen = 0, moved = 0;
    for (int i = first; i < first + kTracked; ++i) {
      cv::Rect want = person;
      const bool ok = i == first || tracker->update(frames[i]->mat, want);
      const auto got = regionsFrom(h.run(frames[i]), h);
      expectTracked(got, found, ok, want, i);
      if (got) expectCameraHeader(got->header);
      seen += ok;
      moved += ok && want != person;
    }
    EXPECT_GE(seen, 5) << "the tracker lost the pedestrian at once: not a test of its boxes";
    EXPECT_GT(moved, 0) << "the box never moved: not a test of tracking";
  }
}

TEST(TrackingNodes, TrackerStartsOnARegionOnANewBoxAndOnRestart) {
  const auto& frames = pedestrians();
  const auto [first, person] = firstPerson();
  ASSERT_LE(first + 18, int(frames.size()));
  const cv::Rect other = (person + cv::Point(10, 6)) & cv::Rect(cv::Point(), frames[0]->mat.size());
  const cv::Rect parameters(200, 150, 64, 128);
  NodeHarness h("apex_nodes/Tracker", {"image", "regions"}, "regions");
  Collector* found = tap(h, "found");
  auto run = [&](int i, const std::vector<cv::Rect>& start) {
    return regionsFrom(h.run({Message::share<Image>(frames[i]), Message::share<Regions>(regionsOf(start))}), h);
  };
  expectTracked(run(first, {}), found, false, {}, first);  // a detector that found nothing yet: nothing to track
  cv::Ptr<cv::Tracker> tracker;
  for (int i = first + 1; i < first + 18; ++i) {
    cv::Rect want;
    bool ok = true;
    std::vector<cv::Rect> start;
    if (i == first + 1 || i == first + 7) {  // a region: (re)starts on it
      want = i == first + 1 ? person : other;
      start = {want};
      tracker = startedTracker("kcf", frames[i]->mat, want);
    } else if (i == first + 12 || i == first + 15) {  // a new box, then the slot: each starts on the parameters' box
      if (i == first + 12) {
        setBox(h, parameters);
      } else {
        ASSERT_TRUE(h.graph().fireSlot("node", "restart"));
        ASSERT_TRUE(h.graph().waitIdle(kWait));
      }
      want = parameters;
      tracker = startedTracker("kcf", frames[i]->mat, want);
    } else {
      ok = tracker->update(frames[i]->mat, want);
    }
    expectTracked(run(i, start), found, ok, want, i);
  }
}

TEST(TrackingNodes, TrackerRefusesWhatItCannotTrack) {
  cv::Mat noise(240, 320, CV_8UC1);
  cv::RNG(5).fill(noise, cv::RNG::UNIFORM, 0, 256);
  NodeHarness h("apex_nodes/Tracker", {"image"}, "regions");
  setBox(h, cv::Rect(100, 80, 64, 64));
  expectNothing(h, h.run(imageOf(cv::Mat(240, 320, CV_16UC1, cv::Scalar::all(9)), "mono16")),
                "the image is 320x240 'mono16' (16UC1); it needs 8-bit pixels");
  expectNothing(h, h.run(imageOf(cv::Mat(240, 320, CV_8UC4, cv::Scalar::all(9)), "bgra8")),
                "cannot handle 4-channel images (encoding 'bgra8'); needs 1 or 3 channels");
  setBox(h, cv::Rect(318, 10, 64, 64));
  expectNothing(h, h.run(imageOf(noise, "mono8")),
                "the box 318,10 64x64 has less than 4x4 pixels in the image 320x240 'mono8' (8UC1)");
  setBox(h, cv::Rect(0, 0, 320, 240));
  expectNothing(h, h.run(imageOf(noise, "mono8")),
                "the box 0,0 320x240 leaves less than 4 pixels of the image 320x240 'mono8' (8UC1) beside it");
  setBox(h, cv::Rect(100, 80, 64, 64));  // a box it can track: it goes on
  const auto got = regionsFrom(h.run(imageOf(noise, "mono8")), h);
  ASSERT_TRUE(got);
  ASSERT_EQ(got->regions.size(), 1u);
  EXPECT_EQ(got->regions[0].box, cv::Rect(100, 80, 64, 64));
}

// --- KalmanFilter

/** A cv::KalmanFilter of a point at a steady speed (state x, y, vx, vy; measured x, y), CV_64F, made
 *  here from the model's definition: at `p` at rest, position variance r, speed variance 1e4. */
cv::KalmanFilter directFilter(const cv::Point2d& p, double r) {
  cv::KalmanFilter kf(4, 2, 0, CV_64F);
  kf.measurementMatrix = (cv::Mat_<double>(2, 4) << 1, 0, 0, 0, 0, 1, 0, 0);
  kf.statePost = (cv::Mat_<double>(4, 1) << p.x, p.y, 0, 0);
  kf.errorCovPost = (cv::Mat_<double>(4, 4) << r, 0, 0, 0, 0, r, 0, 0, 0, 0, 1e4, 0, 0, 0, 0, 1e4);
  return kf;
}

/** A step of dt: white-noise acceleration of variance q (G = (dt²/2, dt) per axis, Q = q G Gᵀ), measurements of variance r. */
void directStep(cv::KalmanFilter& kf, double dt, double q, double r) {
  kf.transitionMatrix = (cv::Mat_<double>(4, 4) << 1, 0, dt, 0, 0, 1, 0, dt, 0, 0, 1, 0, 0, 0, 0, 1);
  const double pp = q * dt * dt * dt * dt / 4, pv = q * dt * dt * dt / 2, vv = q * dt * dt;
  kf.processNoiseCov = (cv::Mat_<double>(4, 4) << pp, 0, pv, 0, 0, pp, 0, pv, pv, 0, vv, 0, 0, pv, 0, vv);
  kf.measurementNoiseCov = (cv::Mat_<double>(2, 2) << r, 0, 0, r);
}

/** Expects `got` to hold one region at the state's point, its box of `size` around it. */
void expectAt(const std::shared_ptr<const Regions>& got, const cv::Mat& state, const cv::Size& size, int i) {
  ASSERT_TRUE(got);
  ASSERT_EQ(got->regions.size(), 1u) << "frame " << i;
  const double x = state.at<double>(0), y = state.at<double>(1);
  EXPECT_DOUBLE_EQ(got->regions[0].centroid.x, x) << "frame " << i;
  EXPECT_DOUBLE_EQ(got->regions[0].centroid.y, y) << "frame " << i;
  EXPECT_EQ(got->regions[0].box,
            cv::Rect(cvRound(x - (size.width - 1) / 2.0), cvRound(y - (size.height - 1) / 2.0), size.width, size.height));
}

TEST(TrackingNodes, KalmanFilterEqualsOpenCVsOnAPedestriansTrack) {
  const auto& frames = pedestrians();
  const auto [first, person] = firstPerson();
  ASSERT_LE(first + 40, int(frames.size()));
  std::vector<std::vector<cv::Rect>> track{{person}};  // KCF's boxes of the pedestrian; none where it lost them
  cv::Ptr<cv::Tracker> kcf = startedTracker("kcf", frames[first]->mat, person);
  for (int i = first + 1; i < first + 40; ++i) {
    cv::Rect box;
    const bool ok = kcf->update(frames[i]->mat, box);
    track.push_back(ok && i != first + 12 && i != first + 13 ? std::vector<cv::Rect>{box} : std::vector<cv::Rect>{});
  }
  NodeHarness h("apex_nodes/KalmanFilter", {"regions"}, "estimate");
  Collector* prediction = tap(h, "prediction");
  Collector* state = tap(h, "state");
  h.set("process_noise", "0.5");
  h.set("measurement_noise", "4");
  cv::KalmanFilter kf;
  cv::Size size;
  for (int i = 0; i < int(track.size()); ++i) {
    const auto in = regionsOf(track[i]);
    const auto got = regionsFrom(h.run(in), h);
    if (!track[i].empty()) size = track[i][0].size();
    const cv::Point2d measured = track[i].empty() ? cv::Point2d() : in->regions[0].centroid;
    if (i == 0) {
      kf = directFilter(measured, 4);
      ASSERT_TRUE(lastOf<Regions>(prediction));
      EXPECT_TRUE(lastOf<Regions>(prediction)->regions.empty());  // nothing predicted yet
    } else {
      directStep(kf, 1, 0.5, 4);
      kf.predict();
      expectAt(lastOf<Regions>(prediction), kf.statePre, size, i);
      if (!track[i].empty()) kf.correct((cv::Mat_<double>(2, 1) << measured.x, measured.y));
    }
    expectAt(got, kf.statePost, size, i);
    ASSERT_TRUE(lastOf<std::vector<double>>(state));
    EXPECT_THAT(*lastOf<std::vector<double>>(state), ::testing::Pointwise(::testing::DoubleEq(), valuesOf(kf.statePost)));
  }
}

TEST(TrackingNodes, KalmanFilterTakesItsStepsFromTheStampsWithDt0) {
  NodeHarness h("apex_nodes/KalmanFilter", {"regions"}, "state");
  h.set("dt", "0");
  cv::KalmanFilter kf;
  ros::Time before;
  auto point = [](int k) { return cv::Point2d(10 + 3 * k + 0.1 * k * k, 50 + 2.5 * k); };
  for (int k = 0; k < 12; ++k) {
    const ros::Time stamp(100 + k / 10, (k % 10) * 100000000 + (k % 3) * 7000000);  // 0.1 s apart, give or take
    auto in = std::make_shared<Regions>(*regionsOf({cv::Rect(0, 0, 20, 20)}, stamp));
    in->regions[0].centroid = point(k);  // the measured point is the centroid, not the box's middle
    const Message got = h.run(std::shared_ptr<const Regions>(in));
    if (k == 0) {
      kf = directFilter(point(k), 10);
    } else {
      directStep(kf, (stamp - before).toSec(), 1, 10);
      kf.predict();
      kf.correct((cv::Mat_<double>(2, 1) << point(k).x, point(k).y));
    }
    before = stamp;
    ASSERT_TRUE(got.as<std::vector<double>>()) << h.error();
    EXPECT_THAT(*got.as<std::vector<double>>(), ::testing::Pointwise(::testing::DoubleEq(), valuesOf(kf.statePost)));
  }
  expectNothing(h, h.run(regionsOf({cv::Rect(0, 0, 20, 20)}, before)), "the regions' stamps do not advance (");
  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));  // forgets the point: the next one starts again
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  const Message again = h.run(regionsOf({cv::Rect(0, 0, 20, 20)}, before));
  ASSERT_TRUE(again.as<std::vector<double>>()) << h.error();
  EXPECT_EQ(*again.as<std::vector<double>>(), std::vector<double>({9.5, 9.5, 0, 0}));
}

// --- MultiObjectTracker

/** The id (label) the node gave the region of `box`; -1 if it sent none. */
int idOf(const Regions& got, const cv::Rect& box) {
  for (const Region& r : got.regions)
    if (r.box == box) return r.label;
  return -1;
}

/** The least total cost of pairing min(rows, cols) rows and columns, by trying every pairing. */
double leastCostByTrying(const cv::Mat1d& cost) {
  const cv::Mat1d c = cost.rows <= cost.cols ? cost : cv::Mat1d(cost.t());
  std::vector<int> cols(c.cols);
  std::iota(cols.begin(), cols.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {  // every order of the columns; its first c.rows pair with the rows
    double sum = 0;
    for (int r = 0; r < c.rows; ++r) sum += c(r, cols[r]);
    best = std::min(best, sum);
  } while (std::next_permutation(cols.begin(), cols.end()));
  return best;
}

TEST(TrackingNodes, LeastCostAssignmentIsTheBestPairing) {
  cv::RNG rng(7);
  for (const auto& [rows, cols] :
       std::vector<std::pair<int, int>>{{1, 1}, {3, 3}, {4, 6}, {6, 4}, {1, 5}, {5, 1}, {6, 6}, {7, 5}}) {
    for (int trial = 0; trial < 20; ++trial) {
      cv::Mat1d cost(rows, cols);
      rng.fill(cost, cv::RNG::UNIFORM, 0.0, 10.0);
      if (trial % 2) cost.setTo(1e9, cost > 8.0);  // pairs never to make, as MultiObjectTracker marks them
      const std::vector<int> col_of = apex_nodes::leastCostAssignment(cost);
      ASSERT_EQ(int(col_of.size()), rows);
      std::vector<int> used;
      double sum = 0;
      for (int r = 0; r < rows; ++r)
        if (col_of[r] >= 0) used.push_back(col_of[r]), sum += cost(r, col_of[r]);
      std::sort(used.begin(), used.end());
      EXPECT_EQ(int(used.size()), std::min(rows, cols)) << rows << "x" << cols;
      EXPECT_TRUE(std::adjacent_find(used.begin(), used.end()) == used.end()) << "a column paired twice";
      EXPECT_NEAR(sum, leastCostByTrying(cost), 1e-6) << rows << "x" << cols << ", trial " << trial;
    }
  }
  EXPECT_TRUE(apex_nodes::leastCostAssignment(cv::Mat1d(0, 3)).empty());
  EXPECT_EQ(apex_nodes::leastCostAssignment(cv::Mat1d(2, 0)), std::vector<int>({-1, -1}));
}

TEST(TrackingNodes, MultiObjectTrackerKeepsTheIdsOfTwoBoxesThatCross) {
  for (const std::string match : {"iou", "distance"}) {
    SCOPED_TRACE(match);
    NodeHarness h("apex_nodes/MultiObjectTracker", {"regions"}, "regions");
    h.set("match", match);
    for (int f = 0; f < 30; ++f) {  // a goes right, b left, 30 pixels lower: they meet at frame 14
      const cv::Rect a(10 + 10 * f, 100, 40, 80), b(300 - 10 * f, 130, 40, 80);
      // first and second in the list in turn: the ids follow the boxes, not their places
      const auto got = regionsFrom(h.run(regionsOf(f % 2 ? std::vector<cv::Rect>{b, a} : std::vector<cv::Rect>{a, b})), h);
      ASSERT_TRUE(got);
      if (f < 2) {
        EXPECT_TRUE(got->regions.empty()) << "frame " << f << ": sent before min_hits (3) frames";
        continue;
      }
      ASSERT_EQ(got->regions.size(), 2u) << "frame " << f;
      EXPECT_EQ(idOf(*got, a), 1) << "frame " << f;  // ids from 1, in the order the objects came
      EXPECT_EQ(idOf(*got, b), 2) << "frame " << f;
      EXPECT_EQ(got->header, regionsOf({})->header);
    }
  }
}

TEST(TrackingNodes, MultiObjectTrackerKeepsAnIdThroughAMissedFrameAndNeverSendsAStray) {
  NodeHarness h("apex_nodes/MultiObjectTracker", {"regions"}, "regions");
  Collector* count = tap(h, "count");
  for (int f = 0; f < 12; ++f) {
    const cv::Rect walker(100 + 5 * f, 200, 40, 80);
    std::vector<cv::Rect> boxes;
    if (f != 6) boxes.push_back(walker);  // not detected in frame 6
    if (f == 4) boxes.push_back(cv::Rect(600, 50, 40, 80));  // a stray detection, one frame only
    const auto got = regionsFrom(h.run(regionsOf(boxes)), h);
    ASSERT_TRUE(got);
    const std::size_t sent = f < 2 || f == 6 ? 0 : 1;
    ASSERT_EQ(got->regions.size(), sent) << "frame " << f;
    ASSERT_TRUE(lastOf<int>(count));
    EXPECT_EQ(*lastOf<int>(count), int(sent));
    if (sent) {
      EXPECT_EQ(idOf(*got, walker), 1) << "frame " << f;
    }
  }
}

TEST(TrackingNodes, MultiObjectTrackerDropsATrackAfterMaxMissedFrames) {
  NodeHarness h("apex_nodes/MultiObjectTracker", {"regions"}, "regions");
  h.set("max_missed", "2");
  h.set("min_hits", "1");
  const cv::Rect box(100, 100, 40, 80);
  const std::vector<int> want{1, 1, 1, 1, -1, -1, 1, -1, -1, -1, 2};  // gone 2 frames: kept; 3 frames: dropped
  for (int f = 0; f < int(want.size()); ++f) {
    const auto got = regionsFrom(h.run(regionsOf(want[f] < 0 ? std::vector<cv::Rect>{} : std::vector<cv::Rect>{box})), h);
    ASSERT_TRUE(got);
    EXPECT_EQ(idOf(*got, box), want[f]) << "frame " << f;
  }
  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));  // every track dropped: ids from 1 again
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  EXPECT_EQ(idOf(*regionsFrom(h.run(regionsOf({box})), h), box), 1);
}

/** How many ids the detections get linked frame to frame, each to the box of the frame before it
 *  overlaps most (IoU 0.3 or more, each box once), any other starting an id: ids with no prediction,
 *  no gap bridged, no stray left out. */
int frameToFrameIds(const std::vector<std::vector<cv::Rect>>& frames) {
  int ids = 0;
  std::vector<cv::Rect> before;
  for (const auto& boxes : frames) {
    std::vector<bool> taken(before.size(), false);
    for (const cv::Rect& b : boxes) {
      int best = -1;
      double most = 0.3;
      for (std::size_t j = 0; j < before.size(); ++j)
        if (!taken[j] && iou(b, before[j]) >= most) best = int(j), most = iou(b, before[j]);
      if (best >= 0) taken[best] = true;
      else ++ids;
    }
    before = boxes;
  }
  return ids;
}

TEST(TrackingNodes, MultiObjectTrackerKeepsPedestriansIdsOnHogDetections) {
  const auto& detections = people();
  ASSERT_EQ(int(detections.size()), kFrames);
  NodeHarness h("apex_nodes/MultiObjectTracker", {"regions"}, "regions");  // its defaults: iou 0.3, max_missed 5, min_hits 3
  std::map<int, int> frames_of;  // per id, the frames it was sent in
  std::map<int, std::pair<int, cv::Rect>> last;  // per id, the frame and box it was last sent with
  int jumps = 0;  // an id sent in two frames in a row with boxes that hardly overlap: it went to another person
  for (int f = 0; f < kFrames; ++f) {
    const auto got = regionsFrom(h.run(regionsOf(detections[f])), h);
    ASSERT_TRUE(got);
    for (const Region& r : got->regions) {
      EXPECT_NE(std::find(detections[f].begin(), detections[f].end(), r.box), detections[f].end()) << "not a detection";
      ++frames_of[r.label];
      const auto it = last.find(r.label);
      if (it != last.end() && it->second.first == f - 1 && iou(it->second.second, r.box) < 0.3) ++jumps;
      last[r.label] = {f, r.box};
    }
  }
  int longest = 0;
  for (const auto& [id, frames] : frames_of) longest = std::max(longest, frames);
  const int linked = frameToFrameIds(detections);
  std::cout << "vtest.avi, " << kFrames << " frames of HOG's people: " << frames_of.size() << " ids (" << linked
            << " linked frame to frame), the longest sent in " << longest << " frames, " << jumps << " jumps\n";
  EXPECT_LE(jumps, 1);
  EXPECT_LT(int(frames_of.size()), linked);
  EXPECT_GE(longest, 15);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
