// LaserScanSubscriber and LaserScanToCloud.
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <cmath>
#include <mutex>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/types.hpp"
#include "topic_source.hpp"

namespace apex_nodes {

class LaserScanSubscriber : public TopicSource<sensor_msgs::LaserScan> {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Receives sensor_msgs/LaserScan; keeps only the newest")
        .output<sensor_msgs::LaserScan>("scan")
        .param(apex::param::text("topic", "scan"))
        .param(holdParam())
        .driven();
  }

 private:
  void subscribe() override {
    sub_ = apex::nodeHandle(*this).subscribe<sensor_msgs::LaserScan>(topic_.get(), 1,
                                                                     [this](const MsgPtr& s) { received(s); });
  }
  void send(const MsgPtr& scan) override {  // shared with ROS, not copied: boost to std ownership
    scan_.publish(std::shared_ptr<const sensor_msgs::LaserScan>(scan.get(), [scan](auto*) {}));
  }
  apex::Output<sensor_msgs::LaserScan> scan_{this, "scan"};
  apex::Param<std::string> topic_{this, "topic"};
  ros::Subscriber sub_;
};

class LaserScanToCloud : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Turns a scan's valid ranges into points in the scan's plane (z = 0)")
        .input<sensor_msgs::LaserScan>("scan")
        .output<Cloud>("cloud");
  }
  void process() override {
    const auto& scan = *scan_.get();
    if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())
      throw std::invalid_argument("scan on frame '" + scan.header.frame_id + "' has " + std::to_string(scan.ranges.size()) +
                                  " ranges but " + std::to_string(scan.intensities.size()) + " intensities");
    if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment))
      throw std::invalid_argument("scan on frame '" + scan.header.frame_id + "' has a non-finite angle_min or angle_increment");
    auto points = std::make_shared<PclCloud>();
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const float r = scan.ranges[i];
      if (!std::isfinite(r) || r < scan.range_min || r > scan.range_max) continue;
      const double a = scan.angle_min + i * static_cast<double>(scan.angle_increment);
      points->push_back(PointT(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0.f));
    }
    if (points->empty())
      throw std::invalid_argument("scan of " + std::to_string(scan.ranges.size()) + " ranges has none within [" +
                                  std::to_string(scan.range_min) + ", " + std::to_string(scan.range_max) + "]");
    auto out = std::make_shared<Cloud>();
    out->header = scan.header;
    out->points = std::move(points);
    cloud_.publish(out);
  }

 private:
  apex::Input<sensor_msgs::LaserScan> scan_{this, "scan"};
  apex::Output<Cloud> cloud_{this, "cloud"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::LaserScanSubscriber, "apex_nodes/LaserScanSubscriber");
APEX_REGISTER_NODE(apex_nodes::LaserScanToCloud, "apex_nodes/LaserScanToCloud");
