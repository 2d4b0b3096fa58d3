// CameraSubscriber and CameraPublisher: an image and its camera model (sensor_msgs/CameraInfo),
// paired by image_transport (the image topic and its sibling camera_info, same stamp).
#include <ros/ros.h>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "shared_image_transport.hpp"
#include "topic_source.hpp"

namespace apex_nodes {

/** One camera frame as image_transport pairs it. */
struct CameraFrame {
  sensor_msgs::ImageConstPtr image;
  sensor_msgs::CameraInfoConstPtr info;
};

class CameraSubscriber : public TopicSource<CameraFrame> {
 public:
  static inline const apex::OutputPort<Image> kImage{"image"};
  static inline const apex::OutputPort<sensor_msgs::CameraInfo> kInfo{"camera_info", "the image's camera model"};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("camera/image_raw").describe("the image topic; its camera_info is beside it");
  static inline const apex::ParamDecl<std::string> kTransport = transportParam();
  static apex::Manifest manifest() {
    return apex::Manifest("Receives a camera's images with their camera_info (image_transport); keeps only the newest")
        .inCategory("ROS I/O")
        .output(kImage)
        .output(kInfo)
        .param(kTopic)
        .param(kTransport)
        .param(holdParam())
        .keepsNewest();
  }

 private:
  void subscribe() override {
    sub_ = subscribeCamera(
        apex::nodeHandle(*this), topic_.get(), kQueue,
        [this](const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& info) {
          received(boost::make_shared<const CameraFrame>(CameraFrame{image, info}));
        },
        transport_.get());
  }
  void send(const MsgPtr& frame) override {
    auto image = fromRos(frame->image);  // checked first: a bad image sends neither
    info_.publish(std::shared_ptr<const sensor_msgs::CameraInfo>(frame->info.get(), [keep = frame->info](const void*) {}));
    image_.publish(image);
  }
  apex::Output<Image> image_{this, kImage};
  apex::Output<sensor_msgs::CameraInfo> info_{this, kInfo};
  apex::Param<std::string> topic_{this, kTopic};
  apex::Param<std::string> transport_{this, kTransport};
  image_transport::CameraSubscriber sub_;
};

class CameraPublisher : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "the frame"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kInfo{"camera_info", "its camera model"};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("camera_out/image").describe("the image topic; camera_info goes beside it");
  static apex::Manifest manifest() {
    return apex::Manifest("Publishes images with their camera_info (image_transport), the image's header on both")
        .inCategory("ROS I/O")
        .input(kImage)
        .input(kInfo)
        .param(kTopic);
  }
  void setup() override { pub_ = advertiseCamera(apex::nodeHandle(*this), topic_.get(), 1); }
  void parameterChanged(const std::string&) override { setup(); }
  void process() override {
    if (pub_.getNumSubscribers() == 0) return;
    const auto image = image_.get();
    auto info = boost::make_shared<sensor_msgs::CameraInfo>(*info_.get());
    info->header = image->header;
    pub_.publish(toRos(*image), info);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<sensor_msgs::CameraInfo> info_{this, kInfo};
  apex::Param<std::string> topic_{this, kTopic};
  image_transport::CameraPublisher pub_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::CameraSubscriber, "apex_nodes/CameraSubscriber");
APEX_REGISTER_NODE(apex_nodes::CameraPublisher, "apex_nodes/CameraPublisher");
