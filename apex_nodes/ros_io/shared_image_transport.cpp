#include "shared_image_transport.hpp"

#include <mutex>

namespace apex_nodes {

std::mutex& pluginLoaderMutex() {
  static std::mutex m;
  return m;
}

namespace {

/** Made on first use, after ros::init; never destroyed, so its plugin libraries are never unloaded
 *  while another thread loads them (and not at exit, after class_loader's own statics are gone). */
image_transport::ImageTransport& transport() {
  static auto* it = new image_transport::ImageTransport(ros::NodeHandle());
  return *it;
}

}  // namespace

image_transport::Publisher advertiseImage(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size) {
  const std::string resolved = nh.resolveName(topic);  // the shared transport's own handle is the root
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  return transport().advertise(resolved, queue_size);
}

image_transport::Subscriber subscribeImage(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size,
                                           const ImageCallback& callback, const std::string& transport_name) {
  const std::string resolved = nh.resolveName(topic);
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  return transport().subscribe(resolved, queue_size, callback, ros::VoidPtr(), image_transport::TransportHints(transport_name));
}

image_transport::CameraPublisher advertiseCamera(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size) {
  const std::string resolved = nh.resolveName(topic);
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  return transport().advertiseCamera(resolved, queue_size);
}

image_transport::CameraSubscriber subscribeCamera(const ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size,
                                                  const CameraCallback& callback, const std::string& transport_name) {
  const std::string resolved = nh.resolveName(topic);
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  return transport().subscribeCamera(resolved, queue_size, callback, ros::VoidPtr(),
                                     image_transport::TransportHints(transport_name));
}

}  // namespace apex_nodes
