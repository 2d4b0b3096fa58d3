// Stamp: sets the stamp of a message's ROS header, or moves it (e.g. a sensor's known latency, a
// recorded frame given the time it is played at).
#include <ros/time.h>

#include <cmath>
#include <cstdint>

#include "apex/core/registry.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Stamp : public apex::Node {
 public:
  static constexpr std::int64_t kLatest = 4294967295LL * 1000000000LL + 999999999LL;  // ros::Time's last nanosecond
  static inline const apex::InputPort<apex::Any> kIn{"in", "a message with a header (an image, cloud, scan, pose...)"};
  static inline const apex::OutputPort<apex::Any> kOut{
      "out", "a copy of `in` with the new stamp (pixels and points shared); frame_id and seq as they were"};
  enum class Mode { kNow, kOffset, kFixed };
  static inline const apex::ChoiceDecl<Mode> kMode =
      param::choice<Mode>("mode", {{"now", Mode::kNow, "the clock's time (ROS time, simulated under /use_sim_time)"},
                                   {"offset", Mode::kOffset, "the stamp plus `offset`"},
                                   {"fixed", Mode::kFixed, "`stamp`"}});
  static inline const apex::ParamDecl<double> kOffset =
      param::number("offset")
          .range(-4294967295.0, 4294967295.0)
          .init(0.0)
          .describe("seconds added to the stamp (mode offset) or to the clock's time (mode now)");
  static inline const apex::ParamDecl<double> kStamp =
      param::number("stamp").range(0.0, 4294967295.0).describe("mode fixed: the stamp, in seconds since 1970");
  static apex::Manifest manifest() {
    return apex::Manifest("Sets the stamp of a message's header to now or a fixed time, or moves it by an offset")
        .inCategory("flow")
        .input(kIn)
        .output(kOut)
        .param(kMode)
        .param(kOffset)
        .param(kStamp);
  }
  void process() override {
    const apex::Message& in = in_.message();
    auto header = headerOf(in);
    if (!header)
      throw std::invalid_argument("cannot stamp a " + in.typeName() + ": it has no header (stamped types: " + stampedTypeNames() +
                                  ")");
    header->stamp = stamp(header->stamp);
    out_.publishMessage(*withHeader(in, *header));
  }

 private:
  ros::Time stamp(const ros::Time& old) const {
    const Mode mode = mode_.get();
    if (mode == Mode::kFixed) return ros::Time(stamp_.get());
    // In nanoseconds, so that offset 0 keeps the stamp exact (a double has ~0.2 us at today's seconds).
    const std::int64_t base = static_cast<std::int64_t>((mode == Mode::kNow ? clockNow() : old).toNSec());
    const std::int64_t t = base + std::llround(offset_.get() * 1e9);
    if (t < 0 || t > kLatest)
      throw std::invalid_argument("stamp " + apex::toText(t * 1e-9) + " s is outside ROS time (0 to 2^32 s): offset " +
                                  apex::toText(offset_.get()) + " s is too far");
    return ros::Time().fromNSec(static_cast<std::uint64_t>(t));
  }
  /** ROS time when the process has a clock (ros::init, or a test's ros::Time::init()), else the system's. */
  static ros::Time clockNow() {
    if (ros::Time::isValid()) return ros::Time::now();
    const ros::WallTime w = ros::WallTime::now();
    return ros::Time(w.sec, w.nsec);
  }
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<apex::Any> out_{this, kOut};
  apex::Choice<Mode> mode_{this, kMode};
  apex::Param<double> offset_{this, kOffset};
  apex::Param<double> stamp_{this, kStamp};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Stamp, "apex_nodes/Stamp");
