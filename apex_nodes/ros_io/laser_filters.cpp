// LaserRangeFilter, LaserAngleFilter and LaserMedianFilter: a scan in, the scan filtered out, as
// the ROS package laser_filters' LaserScanRangeFilter and LaserScanAngularBoundsFilter do, and a
// median along one scan (laser_filters' LaserMedianFilter takes each reading's median over the last
// scans, in time; this one over neighbouring readings of the same scan, and keeps no state).
// The header passes unchanged: laser_filters' angular bounds filter moves the stamp to the first
// kept reading's time, but a scan's results here keep the scan's stamp, so that they match by it.
#include <sensor_msgs/LaserScan.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

using Scan = sensor_msgs::LaserScan;

std::string scanName(const Scan& scan) { return "scan on frame '" + scan.header.frame_id + "'"; }

/** Throws std::invalid_argument naming the flaw unless the scan has ranges and, if it has
 *  intensities, as many of them. */
void checkScan(const Scan& scan) {
  if (scan.ranges.empty()) throw std::invalid_argument("received an empty " + scanName(scan) + " (no ranges)");
  if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())
    throw std::invalid_argument(scanName(scan) + " has " + std::to_string(scan.ranges.size()) + " ranges but " +
                                std::to_string(scan.intensities.size()) + " intensities");
}

/** Reading i's angle, as LaserScanToCloud places it. */
double angleOf(const Scan& scan, std::size_t i) { return scan.angle_min + i * static_cast<double>(scan.angle_increment); }

/** Each value of `in` the median of those within `half` places of it (the window cut short at the
 *  ends), NaN left out; of an even count the upper of the middle two, so always one of the values;
 *  NaN if the window holds nothing else. */
void medianAlong(const std::vector<float>& in, std::size_t half, std::vector<float>& out) {
  const std::size_t n = in.size();
  out.resize(n);
  std::vector<float> window;
  for (std::size_t i = 0; i < n; ++i) {
    window.clear();
    for (std::size_t j = i > half ? i - half : 0; j < std::min(n, i + half + 1); ++j)
      if (!std::isnan(in[j])) window.push_back(in[j]);
    if (window.empty()) {
      out[i] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    const auto middle = window.begin() + window.size() / 2;
    std::nth_element(window.begin(), middle, window.end());
    out[i] = *middle;
  }
}

}  // namespace

/** A node shape: one scan in, checked (ranges, as many intensities if any), a copy of it filtered out. */
class ScanFilter : public apex::Node {
 public:
  static inline const apex::InputPort<Scan> kScanIn{"scan"};
  static inline const apex::OutputPort<Scan> kScanOut{"scan", "the scan filtered, with its header"};
  static apex::Manifest filterManifest(std::string description) {
    return apex::Manifest(std::move(description)).inCategory("ROS I/O").input(kScanIn).output(kScanOut);
  }

 protected:
  /** @brief Makes `out`, a copy of `in`, the filtered scan. */
  virtual void filter(const Scan& in, Scan& out) = 0;

 private:
  void process() final {
    const auto in = in_.get();
    checkScan(*in);
    auto out = std::make_shared<Scan>(*in);
    filter(*in, *out);
    out_.publish(std::shared_ptr<const Scan>(std::move(out)));
  }
  apex::Input<Scan> in_{this, kScanIn};
  apex::Output<Scan> out_{this, kScanOut};
};

class LaserRangeFilter : public ScanFilter {
 public:
  enum class Replace { kNan, kInf, kLimits };
  static inline const apex::ParamDecl<apex::Interval> kLimits =
      param::interval("limits")
          .range(0.0, 1000.0)
          .step(0.01)
          .describe("metres: the readings kept, ends included (laser_filters' lower_threshold, upper_threshold)");
  static inline const apex::ParamDecl<bool> kUseMessageLimits =
      param::flag("use_message_range_limits").init(false).describe("the scan's range_min and range_max instead of limits");
  static inline const apex::ChoiceDecl<Replace> kReplaceWith =
      param::choice<Replace>("replace_with", {{"nan", Replace::kNan, "NaN, as laser_filters by default"},
                                              {"inf", Replace::kInf, "-inf below, +inf above (REP 117: too near, no return)"},
                                              {"lower_and_upper", Replace::kLimits, "the nearer limit"}})
          .describe("what a reading outside the limits becomes; a NaN reading stays NaN");
  static apex::Manifest manifest() {
    return filterManifest("Replaces the ranges outside limits (laser_filters' LaserScanRangeFilter)")
        .param(kLimits)
        .param(kUseMessageLimits)
        .param(kReplaceWith);
  }

 private:
  void filter(const Scan& in, Scan& out) override {
    double lower = limits_.get().low, upper = limits_.get().high;
    if (use_message_limits_.get()) {
      lower = in.range_min, upper = in.range_max;
      if (!(lower <= upper))  // NaN too
        throw std::invalid_argument(scanName(in) + " has range_min " + std::to_string(in.range_min) + " above range_max " +
                                    std::to_string(in.range_max));
    }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const Replace how = replace_with_.get();
    const float below = how == Replace::kNan ? nan : how == Replace::kInf ? -inf : static_cast<float>(lower);
    const float above = how == Replace::kNan ? nan : how == Replace::kInf ? inf : static_cast<float>(upper);
    for (float& r : out.ranges) {
      if (r < lower) r = below;
      else if (r > upper) r = above;
    }
  }
  apex::Param<apex::Interval> limits_{this, kLimits};
  apex::Param<bool> use_message_limits_{this, kUseMessageLimits};
  apex::Choice<Replace> replace_with_{this, kReplaceWith};
};

class LaserAngleFilter : public ScanFilter {
 public:
  static constexpr double kTwoPi = 6.283185307179586;
  static inline const apex::ParamDecl<apex::Interval> kAngles =
      param::interval("angles")
          .range(-kTwoPi, kTwoPi)
          .step(0.001)
          .describe(
              "radians: the readings kept, by their angle angle_min + i angle_increment, ends included "
              "(laser_filters' lower_angle, upper_angle); at first all of them");
  static apex::Manifest manifest() {
    return filterManifest(
               "Cuts a scan to the readings within an angle window, angle_min and angle_max set to the first and "
               "last kept (laser_filters' LaserScanAngularBoundsFilter)")
        .param(kAngles);
  }

 private:
  void filter(const Scan& in, Scan& out) override {
    if (!std::isfinite(in.angle_min) || !std::isfinite(in.angle_increment))
      throw std::invalid_argument(scanName(in) + " has a non-finite angle_min or angle_increment");
    const apex::Interval bounds = angles_.get();
    const std::size_t n = in.ranges.size();
    std::size_t first = n, last = 0;  // angles rise (or fall) along the scan: the kept readings are one run
    for (std::size_t i = 0; i < n; ++i) {
      const double a = angleOf(in, i);
      if (a < bounds.low || a > bounds.high) continue;
      first = std::min(first, i);
      last = i;
    }
    if (first == n)
      throw std::invalid_argument(scanName(in) + ": none of its readings, at " + std::to_string(angleOf(in, 0)) + " to " +
                                  std::to_string(angleOf(in, n - 1)) + " rad, lies within angles [" + std::to_string(bounds.low) +
                                  ", " + std::to_string(bounds.high) + "]");
    out.ranges.assign(in.ranges.begin() + first, in.ranges.begin() + last + 1);
    if (!in.intensities.empty()) out.intensities.assign(in.intensities.begin() + first, in.intensities.begin() + last + 1);
    out.angle_min = static_cast<float>(angleOf(in, first));
    out.angle_max = static_cast<float>(angleOf(in, last));
  }
  apex::Param<apex::Interval> angles_{this, kAngles};
};

class LaserMedianFilter : public ScanFilter {
 public:
  static inline const apex::ParamDecl<int> kWindow = param::integer("window").range(1, 101).step(2).init(5).describe(
      "readings, odd: each reading becomes the median of the window centred on it, cut short at the scan's ends; "
      "NaN readings are left out (a NaN among good readings takes their median), infinities take part");
  static apex::Manifest manifest() {
    return filterManifest(
               "Median of each reading's neighbours along the scan, ranges and intensities alike (one scan: no "
               "state between scans)")
        .param(kWindow);
  }

 private:
  void filter(const Scan& in, Scan& out) override {
    const std::size_t half = static_cast<std::size_t>(window_.get()) / 2;
    medianAlong(in.ranges, half, out.ranges);
    if (!in.intensities.empty()) medianAlong(in.intensities, half, out.intensities);
  }
  apex::Param<int> window_{this, kWindow};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::LaserRangeFilter, "apex_nodes/LaserRangeFilter");
APEX_REGISTER_NODE(apex_nodes::LaserAngleFilter, "apex_nodes/LaserAngleFilter");
APEX_REGISTER_NODE(apex_nodes::LaserMedianFilter, "apex_nodes/LaserMedianFilter");
