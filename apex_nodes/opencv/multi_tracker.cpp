// MultiObjectTracker: gives the regions a detector finds in each frame (HOGPeopleDetector's,
// BlobDetection's, ...) ids that stay with their objects from frame to frame, in the region's
// `label` (Region has no field of its own for an id; the detector's class is replaced). Each object
// is a track: a Kalman filter of its box's middle moving at a steady speed (constant_velocity.hpp,
// one frame a step) and the box's last size. Each frame the tracks predict their boxes, and the
// detections are paired with them at least total cost (assignment.hpp): 1 - the IoU of a predicted
// box and a detection, or the distance of their middles; pairs under min_iou or beyond max_distance
// are never made. A detection left over starts a track; a track left over predicts on, and after
// max_missed such frames in a row it is dropped: its object, if it comes back, gets a new id.
#include <algorithm>

#include "apex/core/registry.hpp"
#include "apex_nodes/types.hpp"
#include "assignment.hpp"
#include "constant_velocity.hpp"

namespace apex_nodes {
namespace param = apex::param;

class MultiObjectTracker : public apex::Node {
 public:
  static inline const apex::InputPort<Regions> kRegionsIn{"regions", "this frame's detections, e.g. HOGPeopleDetector's"};
  static inline const apex::OutputPort<Regions> kRegionsOut{
      "regions",
      "the detections of the tracks detected in min_hits frames or more, in their order, each with its track's id as its "
      "label (ids from 1, never reused)"};
  static inline const apex::OutputPort<int> kCount{"count", "how many regions were sent"};
  enum class Match { kIou, kDistance };
  static inline const apex::ChoiceDecl<Match> kMatch =
      param::choice<Match>("match", {{"iou", Match::kIou, "1 - IoU of the track's predicted box and the detection"},
                                     {"distance", Match::kDistance, "the distance of their middles, pixels"}})
          .describe("the cost of pairing a track with a detection");
  static inline const apex::ParamDecl<double> kMinIou = param::number("min_iou").range(0.0, 1.0).step(0.01).init(0.3).describe(
      "iou: the least overlap (intersection over union) of a track's predicted box and its detection");
  static inline const apex::ParamDecl<double> kMaxDistance =
      param::number("max_distance")
          .range(0.0, 10000.0)
          .step(1.0)
          .init(50.0)
          .describe("distance: the farthest a detection's middle may be from its track's predicted middle, pixels");
  static inline const apex::ParamDecl<int> kMaxMissed =
      param::integer("max_missed")
          .range(0, 1000)
          .step(1)
          .init(5)
          .describe("frames in a row a track lives on without a detection (predicted), then it is dropped");
  static inline const apex::ParamDecl<int> kMinHits =
      param::integer("min_hits")
          .range(1, 1000)
          .step(1)
          .init(3)
          .describe("frames a track must be detected in before its regions are sent: a stray detection never is");
  static inline const apex::ParamDecl<double> kProcessNoise =
      param::number("process_noise")
          .range(0.0, 1000000.0)
          .step(0.01)
          .init(1.0)
          .describe("the variance of a track's acceleration, pixels² per frame⁴: how fast its speed may change");
  static inline const apex::ParamDecl<double> kMeasurementNoise =
      param::number("measurement_noise")
          .range(0.001, 1000000.0)
          .step(0.01)
          .init(10.0)
          .describe("the variance of a detection's middle, pixels² in x and in y");
  static apex::Manifest manifest() {
    return apex::Manifest("Gives detections ids that stay with their objects (a Kalman filter per track, Hungarian pairing)")
        .inCategory("motion")
        .keepsState("its tracks: a re-run of the held frame pairs its detections with them once more")
        .input(kRegionsIn)
        .output(kRegionsOut)
        .output(kCount)
        .param(kMatch)
        .param(kMinIou)
        .param(kMaxDistance)
        .param(kMaxMissed)
        .param(kMinHits)
        .param(kProcessNoise)
        .param(kMeasurementNoise)
        .slot("reset", &MultiObjectTracker::reset, "drops every track: ids start from 1 again");
  }
  /** A new pass of a sequence starts as the first did: each pass gives the same ids. */
  void endOfSequence() override {
    reset();
    endSequence();
  }
  void reset() {
    tracks_.clear();
    next_id_ = 1;
  }

  void process() override {
    const Regions& in = *regions_in_.get();
    const std::vector<Region>& found = in.regions;
    for (Track& t : tracks_) {
      setStep(t.filter, 1.0, process_noise_.get(), measurement_noise_.get());
      t.filter.predict();
    }
    const cv::Mat1d cost = costs(found);
    std::vector<int> found_of(tracks_.size(), -1);  // per track, its detection
    if (!tracks_.empty() && !found.empty()) found_of = leastCostAssignment(cost);
    std::vector<int> id_of(found.size(), 0);  // per detection, its track's id (0: none yet)
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      Track& t = tracks_[i];
      const int d = found_of[i];
      if (d < 0 || cost(int(i), d) >= kUnpaired) {
        ++t.missed;
        continue;
      }
      const cv::Point2d middle = middleOf(found[d].box);
      t.filter.correct((cv::Mat_<double>(2, 1) << middle.x, middle.y));
      t.size = found[d].box.size();
      ++t.hits;
      t.missed = 0;
      id_of[d] = t.id;
    }
    const int max_missed = max_missed_.get();
    tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(), [&](const Track& t) { return t.missed > max_missed; }),
                  tracks_.end());
    for (std::size_t d = 0; d < found.size(); ++d)
      if (id_of[d] == 0) {  // no track took it: a new object
        tracks_.push_back(
            {next_id_, constantVelocityAt(middleOf(found[d].box), measurement_noise_.get()), found[d].box.size(), 1, 0});
        id_of[d] = next_id_++;
      }
    auto out = std::make_shared<Regions>();
    out->header = in.header;
    out->image_size = in.image_size;
    for (std::size_t d = 0; d < found.size(); ++d)
      if (hitsOf(id_of[d]) >= min_hits_.get()) {
        out->regions.push_back(found[d]);
        out->regions.back().label = id_of[d];
      }
    count_.publish(static_cast<int>(out->regions.size()));
    regions_out_.publish(out);
  }

 private:
  /** The cost of a pair that is never made: above any sum of the costs of pairs that may be, so
   *  that the assignment makes as many of those as it can. */
  static constexpr double kUnpaired = 1e9;

  struct Track {
    int id;
    cv::KalmanFilter filter;  // of the box's middle
    cv::Size size;  // the box's, when last detected
    int hits;  // frames it was detected in
    int missed;  // frames in a row without a detection
    /** The box where the filter predicts it (after predict()). */
    cv::Rect2d predicted() const {
      const cv::Point2d p = pointOf(filter.statePre);
      return {p.x - (size.width - 1) / 2.0, p.y - (size.height - 1) / 2.0, double(size.width), double(size.height)};
    }
  };

  /** Tracks x detections: the cost of each pair, kUnpaired where min_iou or max_distance forbids it. */
  cv::Mat1d costs(const std::vector<Region>& found) const {
    cv::Mat1d cost(int(tracks_.size()), int(found.size()));
    for (int i = 0; i < cost.rows; ++i) {
      const cv::Rect2d predicted = tracks_[i].predicted();
      for (int d = 0; d < cost.cols; ++d) {
        const cv::Rect2d box = found[d].box;
        if (match_.get() == Match::kIou) {
          const double overlap = (predicted & box).area(), all = predicted.area() + box.area() - overlap;
          const double iou = all > 0 ? overlap / all : 0;
          cost(i, d) = iou >= min_iou_.get() ? 1 - iou : kUnpaired;
        } else {
          const double distance = cv::norm(middleOf(predicted) - middleOf(box));
          cost(i, d) = distance <= max_distance_.get() ? distance : kUnpaired;
        }
      }
    }
    return cost;
  }
  int hitsOf(int id) const {
    for (const Track& t : tracks_)
      if (t.id == id) return t.hits;
    return 0;
  }

  apex::Input<Regions> regions_in_{this, kRegionsIn};
  apex::Output<Regions> regions_out_{this, kRegionsOut};
  apex::Output<int> count_{this, kCount};
  apex::Choice<Match> match_{this, kMatch};
  apex::Param<double> min_iou_{this, kMinIou};
  apex::Param<double> max_distance_{this, kMaxDistance};
  apex::Param<int> max_missed_{this, kMaxMissed};
  apex::Param<int> min_hits_{this, kMinHits};
  apex::Param<double> process_noise_{this, kProcessNoise};
  apex::Param<double> measurement_noise_{this, kMeasurementNoise};
  std::vector<Track> tracks_;  // in the order they started
  int next_id_ = 1;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::MultiObjectTracker, "apex_nodes/MultiObjectTracker");
