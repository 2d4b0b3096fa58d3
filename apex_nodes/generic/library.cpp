// The library apex_nodes_generic: relays, clocks, counters, arithmetic, logging, time sync, selection, and the flow
// nodes (Delay, Buffer, Accumulate, Demux, Latch, Switch, Statistics, Compare, Stamp). Its node types register
// themselves (APEX_REGISTER_NODE next to each class); this hands them to the ROS host.
#include "apex/ros/node_library.hpp"
#include "apex_nodes/stamp.hpp"  // its stamped types name their frames (kStampsRead)

APEX_NODE_LIBRARY(apex_nodes_generic)
