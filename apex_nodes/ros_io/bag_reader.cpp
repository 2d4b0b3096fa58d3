// BagReader: plays a bag file directly into the graph, at the bag's pace times
// `rate` (0: as fast as the graph takes them). It never drops: the next message
// waits until the graph has read the last one.
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <memory>

#include "apex/ros/node_plugin.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "shared_image_transport.hpp"

namespace apex_nodes {

class BagReader : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Reads images and point clouds from a bag file")
        .output<Image>("image", "messages of image_topic (sensor_msgs/Image)")
        .output<Cloud>("cloud", "messages of cloud_topic (sensor_msgs/PointCloud2)")
        .output<int>("index", "how many messages were read before this one")
        .trigger("finished", "fires after the last message (each pass when looping)")
        .param(apex::param::path("file", "", apex::PathMode::Read).describe("the bag"))
        .param(apex::param::text("image_topic", "/camera/image_raw"))
        .param(apex::param::text("cloud_topic", "/camera/points"))
        .param(apex::param::range("rate", 0.0, 100.0, 0.1, 1.0).describe("times the recorded pace; 0: as fast as possible"))
        .param(apex::param::boolean("loop", false))
        .param(apex::param::boolean("playing", true))
        .driven();
  }
  ~BagReader() override { close(); }
  void setup() override { open(); }
  void parameterChanged(const std::string& name) override {
    if (name == "file" || name == "image_topic" || name == "cloud_topic") open();
    if (name == "playing" && param<bool>("playing")) notifyNewData();
  }
  void process() override {
    if (!view_ || it_ == view_->end()) return;  // Nothing: not open, or finished
    const rosbag::MessageInstance& m = *it_;
    const ros::Time stamp = m.getTime();
    if (auto image = m.instantiate<sensor_msgs::Image>()) publish<Image>("image", fromRos(image));
    if (auto cloud = m.instantiate<sensor_msgs::PointCloud2>()) publish<Cloud>("cloud", fromRos(cloud));
    publish("index", index_++);
    ++it_;
    if (it_ == view_->end()) {
      trigger("finished");
      if (!param<bool>("loop")) return;
      it_ = view_->begin();
      index_ = 0;
    }
    scheduleNext(stamp);
  }

 private:
  /** rosbag loads and unloads its encryptor plugins through pluginlib when a bag opens and
   *  closes: under the node library's plugin lock, or another thread group's image_transport
   *  set-up crashes the process ("Could not unload library"). */
  void close() {
    std::lock_guard<std::mutex> lock(pluginLoaderMutex());
    view_.reset();
    bag_.reset();
  }
  void open() {
    close();
    const std::string file = param<std::string>("file");
    if (file.empty()) return;
    {
      std::lock_guard<std::mutex> lock(pluginLoaderMutex());
      bag_ = std::make_unique<rosbag::Bag>();
      try {
        bag_->open(file, rosbag::bagmode::Read);
      } catch (const rosbag::BagException& e) {
        bag_.reset();
        throw std::invalid_argument("cannot open bag '" + file + "': " + e.what());
      }
    }
    view_ = std::make_unique<rosbag::View>(
        *bag_, rosbag::TopicQuery({param<std::string>("image_topic"), param<std::string>("cloud_topic")}));
    if (view_->size() == 0)
      log(apex::LogLevel::Warn, "bag '" + file + "' has no messages on " + param<std::string>("image_topic") + " or " +
                                    param<std::string>("cloud_topic"));
    it_ = view_->begin();
    index_ = 0;
    if (param<bool>("playing")) notifyNewData();
  }
  void scheduleNext(const ros::Time& previous) {
    if (!param<bool>("playing")) return;
    const double rate = param<double>("rate");
    if (rate <= 0) return notifyNewData();
    const double gap = std::max(0.0, (it_->getTime() - previous).toSec()) / rate;
    notifyAfter(gap);
  }

  std::unique_ptr<rosbag::Bag> bag_;
  std::unique_ptr<rosbag::View> view_;
  rosbag::View::iterator it_;
  int index_ = 0;
};

}  // namespace apex_nodes

APEX_EXPORT_NODE(apex_nodes, BagReader, apex_nodes::BagReader);
