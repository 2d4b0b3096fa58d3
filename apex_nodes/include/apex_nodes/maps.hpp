// Maps made from clouds (pcl/maps.cpp) travel as the ROS messages themselves: an occupancy grid as
// nav_msgs/OccupancyGrid (what rviz's Map display and the navigation stack read), a grid's geometry
// (resolution, size, origin) as nav_msgs/MapMetaData beside an image of per-cell values.
#pragma once

#include <nav_msgs/MapMetaData.h>
#include <nav_msgs/OccupancyGrid.h>

#include "apex/core/message.hpp"

APEX_TYPE_NAME(nav_msgs::OccupancyGrid, "nav_msgs/OccupancyGrid");
APEX_TYPE_NAME(nav_msgs::MapMetaData, "nav_msgs/MapMetaData");
