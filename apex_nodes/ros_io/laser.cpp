// LaserScanSubscriber and LaserScanToCloud.
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <mutex>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "apex_nodes/types.hpp"
#include "topic_source.hpp"

namespace apex_nodes {

class LaserScanSubscriber : public TopicSource<sensor_msgs::LaserScan> {
 public:
  static inline const apex::OutputPort<sensor_msgs::LaserScan> kScan{"scan"};
  static inline const apex::ParamDecl<std::string> kTopic = apex::param::text("topic").init("scan");
  static apex::Manifest manifest() {
    return apex::Manifest("Receives sensor_msgs/LaserScan; keeps only the newest")
        .inCategory("ROS I/O")
        .output(kScan)
        .param(kTopic)
        .param(holdParam())
        .keepsNewest();
  }

 private:
  void subscribe() override {
    sub_ =
        apex::nodeHandle(*this).subscribe<sensor_msgs::LaserScan>(topic_.get(), kQueue, [this](const MsgPtr& s) { received(s); });
  }
  void send(const MsgPtr& scan) override {  // shared with ROS, not copied: boost to std ownership
    scan_.publish(std::shared_ptr<const sensor_msgs::LaserScan>(scan.get(), [scan](auto*) {}));
  }
  apex::Output<sensor_msgs::LaserScan> scan_{this, kScan};
  apex::Param<std::string> topic_{this, kTopic};
  ros::Subscriber sub_;
};

class LaserScanToCloud : public apex::Node {
 public:
  static inline const apex::InputPort<sensor_msgs::LaserScan> kScan{"scan"};
  static inline const apex::OutputPort<Cloud> kCloud{"cloud"};
  static apex::Manifest manifest() {
    return apex::Manifest("Turns a scan's valid ranges into points in the scan's plane (z = 0)")
        .inCategory("ROS I/O")
        .input(kScan)
        .output(kCloud);
  }
  void process() override { cloud_.publish(scanToCloud(*scan_.get())); }

 private:
  apex::Input<sensor_msgs::LaserScan> scan_{this, kScan};
  apex::Output<Cloud> cloud_{this, kCloud};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::LaserScanSubscriber, "apex_nodes/LaserScanSubscriber");
APEX_REGISTER_NODE(apex_nodes::LaserScanToCloud, "apex_nodes/LaserScanToCloud");
