// A bag as a sequence of frames: the messages of the chosen topics whose record
// times lie within a sync window of each other, at most one per topic. Built
// once from the bag's index (no message is read); a frame is then read by a
// rosbag::View over its time range, which rosbag finds by binary search in
// each topic's index: seeking to any frame costs O(log n).
#pragma once

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "apex_nodes/ros_message.hpp"

namespace apex_nodes {

/** @brief Opens a bag for reading under the plugin lock; refuses what is not a regular file
 *  (a FIFO or device would block). Throws std::invalid_argument naming the file. */
std::unique_ptr<rosbag::Bag> openBag(const std::string& file);
/** @brief Creates (or truncates) a bag for writing under the plugin lock. Throws
 *  std::invalid_argument naming the file. */
std::unique_ptr<rosbag::Bag> createBag(const std::string& file);
/** @brief Closes a bag under the plugin lock (rosbag unloads its encryptor plugin). Throws
 *  std::runtime_error naming the file if that fails (a bag being written could not get its
 *  index): the bag is then abandoned, never closed twice. */
void closeBag(std::unique_ptr<rosbag::Bag>& bag);

/** @brief Topic → message type (e.g. "sensor_msgs/Image") of every topic in the bag. */
std::map<std::string, std::string> topicTypes(rosbag::Bag& bag);

struct BagFrame {
  ros::Time start, end;  ///< record times of its first and last message
};

/** @brief The frames of `topics` in `bag`: a frame starts at a message more than `window`
 *  seconds after the frame's first one, or on a topic the frame already has. */
std::vector<BagFrame> indexFrames(rosbag::Bag& bag, const std::vector<std::string>& topics, double window);

/** @brief A message of the bag as it is stored: its connection's type and its bytes (one copy);
 *  with `stamp`, its header's stamp is that instead (a type without a header is left as it is). */
std::shared_ptr<const RosMessage> readMessage(const rosbag::MessageInstance& m, const ros::Time* stamp = nullptr);

/** @brief "/camera/image_raw" → "camera_image_raw": a port name for a topic. */
std::string portForTopic(const std::string& topic);

}  // namespace apex_nodes
