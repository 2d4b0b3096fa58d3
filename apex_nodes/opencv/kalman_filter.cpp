// KalmanFilter: smooths the path of one point and predicts it, with a Kalman filter
// (cv::KalmanFilter) of a point moving at a steady speed (constant_velocity.hpp). The point is the
// first region's centroid: Regions are what the library's finders send (Tracker, the detectors,
// BlobDetection), with their frame's header and size, and what DrawRegions draws, so the filter
// sits between them with no conversion; a frame without a region is a frame without a measurement,
// and the filter predicts on through it.
#include <sstream>

#include "apex/core/registry.hpp"
#include "apex_nodes/types.hpp"
#include "constant_velocity.hpp"

namespace apex_nodes {
namespace param = apex::param;

class KalmanFilter : public apex::Node {
 public:
  static inline const apex::InputPort<Regions> kRegions{
      "regions", "the first region's centroid is the measured point; no region: no measurement, the point is predicted"};
  static inline const apex::OutputPort<Regions> kEstimate{
      "estimate",
      "the last measured region moved to the filter's estimate after this frame: its centroid the estimated point, its "
      "box around it; none before the first point"};
  static inline const apex::OutputPort<Regions> kPrediction{
      "prediction", "the same at the point predicted for this frame before its measurement; none on the first point"};
  static inline const apex::OutputPort<std::vector<double>> kState{
      "state", "the estimate: x, y, vx, vy (pixels, pixels per unit of dt); empty before the first point"};
  static inline const apex::ParamDecl<double> kProcessNoise =
      param::number("process_noise")
          .range(0.0, 1000000.0)
          .step(0.01)
          .init(1.0)
          .describe("the variance of the point's acceleration (pixels² per unit of dt⁴): how fast its speed may change");
  static inline const apex::ParamDecl<double> kMeasurementNoise =
      param::number("measurement_noise")
          .range(0.001, 1000000.0)
          .step(0.01)
          .init(10.0)
          .describe("the variance of a measured point, pixels² in x and in y: how far the finder may miss");
  static inline const apex::ParamDecl<double> kDt =
      param::number("dt")
          .range(0.0, 3600.0)
          .step(0.001)
          .init(1.0)
          .describe("the time from one frame to the next (1: velocities per frame); 0: from the regions' stamps, seconds");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Smooths and predicts the path of a point (cv::KalmanFilter, constant velocity): the first region's centroid")
        .inCategory("motion")
        .keepsState("the filter's estimate: a re-run of the held frame measures the point again")
        .input(kRegions)
        .output(kEstimate)
        .output(kPrediction)
        .output(kState)
        .param(kProcessNoise)
        .param(kMeasurementNoise)
        .param(kDt)
        .slot("reset", &KalmanFilter::reset, "forgets the point: the next one starts the filter again");
  }
  /** A new pass of a sequence starts as the first did. */
  void endOfSequence() override {
    reset();
    endSequence();
  }
  void reset() { started_ = false; }

  void process() override {
    const Regions& in = *regions_.get();
    const double dt = started_ ? step(in) : 0;  // first, so that a refused stamp changes nothing
    auto estimate = emptyLike(in), prediction = emptyLike(in);
    std::vector<double> state;
    const bool measured = !in.regions.empty();
    if (measured) last_ = in.regions.front();
    if (started_) {
      setStep(filter_, dt, process_noise_.get(), measurement_noise_.get());
      prediction->regions.push_back(movedTo(pointOf(filter_.predict())));
      if (measured) filter_.correct((cv::Mat_<double>(2, 1) << last_.centroid.x, last_.centroid.y));
    } else if (measured) {
      filter_ = constantVelocityAt(last_.centroid, measurement_noise_.get());
      started_ = true;
    }
    if (started_) {
      estimate->regions.push_back(movedTo(pointOf(filter_.statePost)));
      state.assign(filter_.statePost.begin<double>(), filter_.statePost.end<double>());
      stamp_ = in.header.stamp;
    }
    estimate_.publish(estimate);
    prediction_.publish(prediction);
    state_.publish(std::move(state));
  }

 private:
  /** The time since the last frame: dt, or the stamps' difference when dt is 0 (refused unless it is positive). */
  double step(const Regions& in) const {
    if (dt_.get() > 0) return dt_.get();
    const double seconds = (in.header.stamp - stamp_).toSec();
    if (seconds > 0) return seconds;
    std::ostringstream words;
    words << "the regions' stamps do not advance (" << in.header.stamp << " after " << stamp_
          << "): dt 0 takes the time from one frame to the next from them";
    throw std::invalid_argument(words.str());
  }
  static std::shared_ptr<Regions> emptyLike(const Regions& in) {
    auto out = std::make_shared<Regions>();
    out->header = in.header;
    out->image_size = in.image_size;
    return out;
  }
  /** The last measured region with its centroid at `p` and its box around it. */
  Region movedTo(const cv::Point2d& p) const {
    Region r = last_;
    r.centroid = p;
    r.box = boxAround(p, last_.box.size());
    return r;
  }

  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Regions> estimate_{this, kEstimate};
  apex::Output<Regions> prediction_{this, kPrediction};
  apex::Output<std::vector<double>> state_{this, kState};
  apex::Param<double> process_noise_{this, kProcessNoise};
  apex::Param<double> measurement_noise_{this, kMeasurementNoise};
  apex::Param<double> dt_{this, kDt};
  cv::KalmanFilter filter_;  // CV_64F once started (constantVelocityAt)
  bool started_ = false;
  Region last_;  // the last measured region: its size, label and confidence go on with the estimate
  ros::Time stamp_;  // the last frame's
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::KalmanFilter, "apex_nodes/KalmanFilter");
