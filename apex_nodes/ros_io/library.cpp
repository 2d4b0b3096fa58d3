// The library apex_nodes_ros: topics, bags, tf and laser scans (ROS). Its node types register themselves
// (APEX_REGISTER_NODE next to each class); this hands them to the ROS host.
#include "apex/ros/node_library.hpp"
#include "apex_nodes/stamp.hpp"  // its stamped types name their frames (kStampsRead)

APEX_NODE_LIBRARY(apex_nodes_ros)
