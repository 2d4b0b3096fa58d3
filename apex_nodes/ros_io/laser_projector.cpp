// LaserProjector: a scan's readings as points by laser_geometry's LaserProjection, the calls ROS
// drivers and filters use: their points, field names and layout, with the channels they can add.
// Without target_frame, projectLaser: the points in the scan's frame. With it, the high-fidelity
// transformLaserScanToPointCloud: each reading moved into target_frame by tf2 at its own time (the
// stamp + index x time_increment; laser_geometry interpolates between the transforms at the first
// and the last reading): the walls a laser sweeps while it moves stay straight, where TfLookup then
// TransformCloud, one transform for the whole cloud, skew them. The transforms come from the node's
// own tf2 buffer (TfListener, tf_listener.hpp, as TfLookup's), filled from /tf and /tf_static from
// setup() on, or from the first scan that needs it.
// LaserScanToCloud (laser.cpp) is the project's own plain form (x, y, z and intensity of the
// readings within range_min..range_max). The projection keeps its sines and cosines between scans
// of the same angles, as laser_geometry means it to.
#include <boost/make_shared.hpp>
#include <laser_geometry/laser_geometry.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "apex/core/registry.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "apex_nodes/types.hpp"
#include "tf_listener.hpp"

namespace apex_nodes {
namespace param = apex::param;

class LaserProjector : public apex::Node {
 public:
  static inline const apex::InputPort<sensor_msgs::LaserScan> kScan{"scan"};
  static inline const apex::OutputPort<Cloud> kCloud{
      "cloud",
      "a point per reading with range_min <= range < range_cutoff, with the channels asked for and the scan's header: in "
      "the scan's frame (z = 0), or in target_frame; no points if none is"};
  static inline const apex::ParamDecl<std::string> kTargetFrame =
      param::text("target_frame")
          .describe(
              "empty: the scan's frame (projectLaser); else each reading moved into it by tf2 at its own time "
              "(transformLaserScanToPointCloud; a fixed frame such as odom, as laser_geometry asks)");
  static inline const apex::ParamDecl<double> kTimeout =
      tfTimeoutParam("seconds to wait for the transform at the scan's last reading (with target_frame)");
  static inline const apex::ParamDecl<double> kRangeCutoff =
      param::number("range_cutoff")
          .range(0.0, 1000.0)
          .step(0.01)
          .init(0.0)
          .describe("metres: readings at or beyond it are left out; 0: the scan's range_max (laser_geometry's -1)");
  static inline const apex::ParamDecl<bool> kIntensity =
      param::flag("intensity")
          .init(true)
          .describe("a float field 'intensity': the reading's intensity (if the scan has intensities)");
  static inline const apex::ParamDecl<bool> kIndex =
      param::flag("index").init(true).describe("an int32 field 'index': the reading's place in the scan");
  static inline const apex::ParamDecl<bool> kDistance =
      param::flag("distance").describe("a float field 'distances': the reading's range");
  static inline const apex::ParamDecl<bool> kTimestamp =
      param::flag("timestamp").describe("a float field 'stamps': seconds after the scan's stamp (index x time_increment)");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Projects a scan into a cloud with laser_geometry, with its optional channels: projectLaser, or into "
               "target_frame by tf2 at each reading's time (transformLaserScanToPointCloud)")
        .inCategory("ROS I/O")
        .input(kScan)
        .output(kCloud)
        .param(kTargetFrame)
        .param(kTimeout)
        .param(kRangeCutoff)
        .param(kIntensity)
        .param(kIndex)
        .param(kDistance)
        .param(kTimestamp);
  }
  void setup() override {
    if (!target_frame_.get().empty()) tf_ = std::make_unique<TfListener>(*this);  // transforms arrive before scans
  }
  void process() override {
    const sensor_msgs::LaserScan& scan = *scan_.get();
    check(scan);
    auto points = boost::make_shared<sensor_msgs::PointCloud2>();
    const double cutoff = range_cutoff_.get() > 0 ? range_cutoff_.get() : -1.0;
    if (target_frame_.get().empty()) projector_.projectLaser(scan, *points, cutoff, channels());
    else transform(scan, *points, cutoff);
    cloud_.publish(fromRos(sensor_msgs::PointCloud2ConstPtr(std::move(points))));
  }

 private:
  /** Refuses a scan laser_geometry cannot project: no ranges, or intensities it would read past. */
  static void check(const sensor_msgs::LaserScan& scan) {
    const std::string name = "scan on frame '" + scan.header.frame_id + "'";
    if (scan.ranges.empty()) throw std::invalid_argument("received an empty " + name + " (no ranges)");
    if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())
      throw std::invalid_argument(name + " has " + std::to_string(scan.ranges.size()) + " ranges but " +
                                  std::to_string(scan.intensities.size()) + " intensities");
  }
  /** laser_geometry's channel_options from the flags. */
  int channels() const {
    namespace channel = laser_geometry::channel_option;
    int options = channel::None;
    if (intensity_.get()) options |= channel::Intensity;
    if (index_.get()) options |= channel::Index;
    if (distance_.get()) options |= channel::Distance;
    if (timestamp_.get()) options |= channel::Timestamp;
    return options;
  }
  /** transformLaserScanToPointCloud into target_frame. It looks tf2 up at the first and the last
   *  reading without waiting, so the wait (timeout) is for the last, the newer when time_increment
   *  is positive. A transform tf2 lacks is the node's error, naming both frames, as TfLookup's: no
   *  cloud this firing, the next scan tried anew. */
  void transform(const sensor_msgs::LaserScan& scan, sensor_msgs::PointCloud2& points, double cutoff) {
    const std::string& target = target_frame_.get();
    const std::string& source = scan.header.frame_id;
    const ros::Time last = scan.header.stamp + ros::Duration((scan.ranges.size() - 1) * scan.time_increment);
    if (!tf_) tf_ = std::make_unique<TfListener>(*this);  // target_frame set after setup()
    try {
      tf_->waitFor(target, source, last, timeout_.get());
      projector_.transformLaserScanToPointCloud(target, scan, points, tf_->buffer(), cutoff, channels());
    } catch (const tf2::TransformException& e) {
      throw std::runtime_error(noTransform(source, target, scan.header.stamp) + " (to " + std::to_string(last.toSec()) +
                               ", the scan's last reading): " + e.what());
    }
  }

  apex::Input<sensor_msgs::LaserScan> scan_{this, kScan};
  apex::Output<Cloud> cloud_{this, kCloud};
  apex::Param<double> range_cutoff_{this, kRangeCutoff};
  apex::Param<bool> intensity_{this, kIntensity};
  apex::Param<bool> index_{this, kIndex};
  apex::Param<bool> distance_{this, kDistance};
  apex::Param<bool> timestamp_{this, kTimestamp};
  apex::Param<std::string> target_frame_{this, kTargetFrame};
  apex::Param<double> timeout_{this, kTimeout};
  laser_geometry::LaserProjection projector_;
  std::unique_ptr<TfListener> tf_;  // the first time target_frame is set (setup() or a scan)
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::LaserProjector, "apex_nodes/LaserProjector");
