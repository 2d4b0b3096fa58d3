// The ROS header of the stamped types APEX's nodes exchange: read (headerOf) and replaced (withHeader), one list.
#pragma once

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>

#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "apex_nodes/cluster_features.hpp"
#include "apex_nodes/types.hpp"

APEX_TYPE_NAME(geometry_msgs::TransformStamped, "geometry_msgs/TransformStamped");
// Poses travel as the ROS messages themselves: one (e.g. an object's), or several in one frame.
APEX_TYPE_NAME(geometry_msgs::PoseStamped, "geometry_msgs/PoseStamped");
APEX_TYPE_NAME(geometry_msgs::PoseArray, "geometry_msgs/PoseArray");

namespace apex_nodes {

/** @brief A list of C++ types, e.g. StampedTypes. */
template <class... Ts>
struct TypeList {};

namespace detail {
/** Calls `f` with the payload (a shared_ptr<const T>) if the message is one of Ts; false if none. */
template <class F, class... Ts>
bool visitAs(const apex::Message& m, F& f, TypeList<Ts...>) {
  auto one = [&](auto payload) {
    if (payload) f(payload);
    return payload != nullptr;
  };
  return (one(m.as<Ts>()) || ...);
}

template <class... Ts>
std::string typeNames(TypeList<Ts...>) {
  std::string names;
  ((names += (names.empty() ? "" : ", ") + apex::typeOf<Ts>()->name), ...);
  return names;
}
}  // namespace detail

/** @brief The types with a ROS header that headerOf reads and withHeader sets: an image, cloud, regions,
 *  clusters, cluster features, scan, camera model, transform or pose(s). A new stamped type is added here. */
using StampedTypes = TypeList<Image, Cloud, Regions, Clusters, ClusterFeatures, sensor_msgs::LaserScan, sensor_msgs::CameraInfo,
                              geometry_msgs::TransformStamped, geometry_msgs::PoseStamped, geometry_msgs::PoseArray>;

/** @brief The message's header, if it is one of StampedTypes. */
inline std::optional<std_msgs::Header> headerOf(const apex::Message& m) {
  std::optional<std_msgs::Header> header;
  auto read = [&](const auto& payload) { header = payload->header; };
  detail::visitAs(m, read, StampedTypes{});
  return header;
}

/** @brief A copy of the message with another header (a new object: messages are immutable; pixels and
 *  points are shared, not copied), if it is one of StampedTypes. */
inline std::optional<apex::Message> withHeader(const apex::Message& m, const std_msgs::Header& header) {
  std::optional<apex::Message> out;
  auto restamp = [&](const auto& payload) {
    using T = std::remove_const_t<typename std::decay_t<decltype(payload)>::element_type>;
    auto copy = std::make_shared<T>(*payload);
    copy->header = header;
    out = apex::Message::share<T>(std::move(copy));
  };
  detail::visitAs(m, restamp, StampedTypes{});
  return out;
}

namespace detail {
template <class T>
std::int64_t headerStampNs(const void* payload) {
  return static_cast<std::int64_t>(static_cast<const T*>(payload)->header.stamp.toNSec());
}
template <class... Ts>
bool readStamps(TypeList<Ts...>) {
  (apex::readStampWith<Ts>(&headerStampNs<Ts>), ...);
  return true;
}
}  // namespace detail

/** @brief Each of StampedTypes names its frame by its header's stamp (apex::Message::frame: what the
 *  frame trace and the latencies follow). Set as a library including this header loads: each
 *  node library's library.cpp does. */
inline const bool kStampsRead = detail::readStamps(StampedTypes{});

/** @brief The names of StampedTypes, for messages: "apex_nodes/Image, apex_nodes/Cloud, ...". */
inline std::string stampedTypeNames() { return detail::typeNames(StampedTypes{}); }

}  // namespace apex_nodes
