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

image_transport::Publisher advertiseImage(const std::string& topic, uint32_t queue_size) {
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  return transport().advertise(topic, queue_size);
}

image_transport::Subscriber subscribeImage(const std::string& topic, uint32_t queue_size,
                                           const ImageCallback& callback,
                                           const std::string& transport_name) {
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  return transport().subscribe(topic, queue_size, callback, ros::VoidPtr(),
                               image_transport::TransportHints(transport_name));
}

}  // namespace apex_nodes
