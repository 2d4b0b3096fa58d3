// One image_transport for every image node in the process.
//
// pluginlib and class_loader are not thread-safe: two ImageTransport objects
// made at once on two thread groups run rospack at once ("No plugins found!")
// and load or unload libimage_transport_plugins at once (a crash: "Could not
// unload library"). So every image node advertises and subscribes through one
// ImageTransport that lives as long as the process, one call at a time: its
// plugin loaders are made once and never unloaded.
#pragma once

#include <image_transport/image_transport.h>

#include <mutex>
#include <string>

#include "apex/core/declare.hpp"

namespace apex_nodes {

/** @brief Held by every use of pluginlib/class_loader in the node library (image_transport,
 *  rosbag's encryptor plugins when a bag is opened or closed), so no two load or unload at once. */
std::mutex& pluginLoaderMutex();

/** @brief The transport parameter of every image subscriber (a function: static members of the
 *  nodes may be initialised after the registration lines that read them). */
inline apex::ParamDecl<std::string> transportParam() { return apex::param::choice("transport", {"raw", "compressed", "theora"}); }

using ImageCallback = boost::function<void(const sensor_msgs::ImageConstPtr&)>;
using CameraCallback = boost::function<void(const sensor_msgs::ImageConstPtr&, const sensor_msgs::CameraInfoConstPtr&)>;

/** `topic` is resolved by `nh` (its namespace and remappings: the node's, from the host). */
image_transport::Publisher advertiseImage(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size);

image_transport::Subscriber subscribeImage(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size,
                                           const ImageCallback& callback, const std::string& transport);

/** A camera: the image topic and its sibling camera_info (image_transport's pairing by stamp). */
image_transport::CameraPublisher advertiseCamera(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size);

image_transport::CameraSubscriber subscribeCamera(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size,
                                                  const CameraCallback& callback, const std::string& transport);

}  // namespace apex_nodes
