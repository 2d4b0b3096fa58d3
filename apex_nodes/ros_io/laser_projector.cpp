// LaserProjector: a scan's readings as points by laser_geometry's LaserProjection::projectLaser, the
// call ROS drivers and filters use: its points, field names and layout, with the channels it can
// add. LaserScanToCloud (laser.cpp) is the project's own plain form (x, y, z and intensity of the
// readings within range_min..range_max). The projection keeps its sines and cosines between scans
// of the same angles, as laser_geometry means it to.
// Only projectLaser: transformLaserScanToPointCloud (each reading moved by tf at its own time) needs
// a tf2 buffer, which a node fills from /tf through a ROS master (as TfLookup does); TfLookup then
// TransformCloud move the cloud as a whole.
#include <boost/make_shared.hpp>
#include <laser_geometry/laser_geometry.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <stdexcept>
#include <string>

#include "apex/core/registry.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {
namespace param = apex::param;

class LaserProjector : public apex::Node {
 public:
  static inline const apex::InputPort<sensor_msgs::LaserScan> kScan{"scan"};
  static inline const apex::OutputPort<Cloud> kCloud{
      "cloud",
      "a point (z = 0) per reading with range_min <= range < range_cutoff, with the channels asked for and the scan's header; "
      "no points if none is"};
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
    return apex::Manifest("Projects a scan into a cloud with laser_geometry (projectLaser), with its optional channels")
        .inCategory("ROS I/O")
        .input(kScan)
        .output(kCloud)
        .param(kRangeCutoff)
        .param(kIntensity)
        .param(kIndex)
        .param(kDistance)
        .param(kTimestamp);
  }
  void process() override {
    const sensor_msgs::LaserScan& scan = *scan_.get();
    const std::string name = "scan on frame '" + scan.header.frame_id + "'";
    if (scan.ranges.empty()) throw std::invalid_argument("received an empty " + name + " (no ranges)");
    if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())  // projectLaser would read past them
      throw std::invalid_argument(name + " has " + std::to_string(scan.ranges.size()) + " ranges but " +
                                  std::to_string(scan.intensities.size()) + " intensities");
    namespace channel = laser_geometry::channel_option;
    int channels = channel::None;
    if (intensity_.get()) channels |= channel::Intensity;
    if (index_.get()) channels |= channel::Index;
    if (distance_.get()) channels |= channel::Distance;
    if (timestamp_.get()) channels |= channel::Timestamp;
    auto points = boost::make_shared<sensor_msgs::PointCloud2>();
    projector_.projectLaser(scan, *points, range_cutoff_.get() > 0 ? range_cutoff_.get() : -1.0, channels);
    cloud_.publish(fromRos(sensor_msgs::PointCloud2ConstPtr(std::move(points))));
  }

 private:
  apex::Input<sensor_msgs::LaserScan> scan_{this, kScan};
  apex::Output<Cloud> cloud_{this, kCloud};
  apex::Param<double> range_cutoff_{this, kRangeCutoff};
  apex::Param<bool> intensity_{this, kIntensity};
  apex::Param<bool> index_{this, kIndex};
  apex::Param<bool> distance_{this, kDistance};
  apex::Param<bool> timestamp_{this, kTimestamp};
  laser_geometry::LaserProjection projector_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::LaserProjector, "apex_nodes/LaserProjector");
