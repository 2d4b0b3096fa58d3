// apex_bench_images' cases of the tracking nodes, each against the OpenCV calls it makes on the same
// frames (image_bench.cpp has the table): Tracker's KCF on the moving patch, KalmanFilter on the
// patch's box, MultiObjectTracker on three boxes walking. The calls use the nodes' own model and
// assignment (constant_velocity.hpp, assignment.hpp): what differs is the node around them.
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>

#include "../apex_nodes/opencv/assignment.hpp"
#include "../apex_nodes/opencv/constant_velocity.hpp"
#include "image_cases.hpp"

namespace apex_bench {

using apex_nodes::Region;
using apex_nodes::Regions;
using RegionsPtr = std::shared_ptr<const Regions>;

namespace {

/** A node of one Regions input ("regions"), fed `frames` in turn, against `call` on the same frame's regions. */
NodeCase regionsCase(std::string label, std::string type, std::string input, std::vector<RegionsPtr> frames, Params params,
                     std::string out_port, std::string sink, std::string call_text, std::function<void(const Regions&)> call) {
  NodeCase c;
  c.label = std::move(label);
  c.type = std::move(type);
  c.input = std::move(input);
  c.feed = feedType<Regions>();
  c.in_ports = {"regions"};
  for (const auto& f : frames) c.frames.push_back({msg(f)});
  c.params = std::move(params);
  c.out_port = std::move(out_port);
  c.sink = std::move(sink);
  c.call_text = std::move(call_text);
  c.call = [frames = std::move(frames), call = std::move(call)](std::size_t i) { call(*frames[i]); };
  return c;
}

/** Regions of `boxes` as a detector sends them: each its box, area and middle. */
RegionsPtr regionsOf(const std::vector<cv::Rect>& boxes) {
  auto r = std::make_shared<Regions>();
  r->header.frame_id = "camera";
  r->image_size = cv::Size(640, 480);
  for (const cv::Rect& b : boxes) {
    Region region;
    region.box = b;
    region.area = b.area();
    region.centroid = apex_nodes::middleOf(b);
    r->regions.push_back(region);
  }
  return r;
}

/** What MultiObjectTracker does per frame, with its defaults (iou 0.3, max_missed 5, noises 1 and 10). */
struct MultiTrackerCall {
  struct Track {
    cv::KalmanFilter filter;
    cv::Size size;
    int missed;
  };
  std::vector<Track> tracks;
  void operator()(const Regions& r) {
    for (Track& t : tracks) {
      apex_nodes::setStep(t.filter, 1, 1, 10);
      t.filter.predict();
    }
    cv::Mat1d cost(int(tracks.size()), int(r.regions.size()));
    for (int i = 0; i < cost.rows; ++i)
      for (int d = 0; d < cost.cols; ++d) {
        const cv::Rect2d predicted(apex_nodes::pointOf(tracks[i].filter.statePre) -
                                       cv::Point2d((tracks[i].size.width - 1) / 2.0, (tracks[i].size.height - 1) / 2.0),
                                   cv::Size2d(tracks[i].size));
        const cv::Rect2d box = r.regions[d].box;
        const double overlap = (predicted & box).area(), iou = overlap / (predicted.area() + box.area() - overlap);
        cost(i, d) = iou >= 0.3 ? 1 - iou : 1e9;
      }
    std::vector<int> pair(tracks.size(), -1);
    if (cost.rows > 0 && cost.cols > 0) pair = apex_nodes::leastCostAssignment(cost);
    std::vector<bool> taken(r.regions.size(), false);
    for (std::size_t i = 0; i < tracks.size(); ++i) {
      if (pair[i] < 0 || cost(int(i), pair[i]) >= 1e9) {
        ++tracks[i].missed;
        continue;
      }
      const cv::Point2d middle = apex_nodes::middleOf(r.regions[pair[i]].box);
      tracks[i].filter.correct((cv::Mat_<double>(2, 1) << middle.x, middle.y));
      tracks[i].size = r.regions[pair[i]].box.size();
      tracks[i].missed = 0;
      taken[pair[i]] = true;
    }
    tracks.erase(std::remove_if(tracks.begin(), tracks.end(), [](const Track& t) { return t.missed > 5; }), tracks.end());
    for (std::size_t d = 0; d < r.regions.size(); ++d)
      if (!taken[d])
        tracks.push_back(
            {apex_nodes::constantVelocityAt(apex_nodes::middleOf(r.regions[d].box), 10), r.regions[d].box.size(), 0});
  }
};

}  // namespace

std::vector<NodeCase> trackingCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const std::string sink = sinkType<Regions>();
  c.push_back(imageCase("Tracker (kcf)", "apex_nodes/Tracker", "8 bgr8 frames, a patch moving", in.moving,
                        {{"method", "kcf"}, {"x", "40"}, {"y", "190"}, {"width", "100"}, {"height", "100"}}, "regions", sink,
                        "TrackerKCF: init on the patch in the first frame, update on the others",
                        [tracker = cv::Ptr<cv::Tracker>(), box = cv::Rect()](const cv::Mat& m) mutable {
                          if (tracker) {
                            tracker->update(m, box);
                            return;
                          }
                          tracker = cv::TrackerKCF::create();
                          tracker->init(m, cv::Rect(40, 190, 100, 100));
                        }));
  std::vector<RegionsPtr> patch, walkers;  // the moving patch's box (image_bench.cpp); three people walking
  for (int i = 0; i < 8; ++i) {
    patch.push_back(regionsOf({cv::Rect(40 + 70 * i, 190, 100, 100)}));
    walkers.push_back(regionsOf(
        {cv::Rect(40 + 20 * i, 40, 60, 120), cv::Rect(500 - 20 * i, 180, 60, 120), cv::Rect(200 + 10 * i, 330, 60, 120)}));
  }
  c.push_back(regionsCase("KalmanFilter", "apex_nodes/KalmanFilter", "the moving patch's box, 8 frames", patch,
                          {{"process_noise", "1"}, {"measurement_noise", "10"}, {"dt", "1"}}, "estimate", sink,
                          "KalmanFilter 4x2 CV_64F, constant velocity: predict, correct",
                          [kf = cv::KalmanFilter(), started = false](const Regions& r) mutable {
                            const cv::Point2d p = r.regions.front().centroid;
                            if (!started) {
                              kf = apex_nodes::constantVelocityAt(p, 10);
                              started = true;
                              return;
                            }
                            apex_nodes::setStep(kf, 1, 1, 10);
                            kf.predict();
                            kf.correct((cv::Mat_<double>(2, 1) << p.x, p.y));
                          }));
  c.push_back(regionsCase("MultiObjectTracker", "apex_nodes/MultiObjectTracker", "3 boxes walking, 8 frames", walkers,
                          {{"match", "iou"}, {"min_iou", "0.3"}, {"max_missed", "5"}, {"min_hits", "3"}}, "regions", sink,
                          "per track KalmanFilter predict; IoU costs, Hungarian assignment; correct, start, drop",
                          [tracks = MultiTrackerCall()](const Regions& r) mutable { tracks(r); }));
  return c;
}

}  // namespace apex_bench
