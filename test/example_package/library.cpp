#include "apex/ros/node_library.hpp"

APEX_NODE_LIBRARY(apex_example_nodes)
