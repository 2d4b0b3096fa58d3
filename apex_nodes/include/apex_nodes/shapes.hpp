// Shapes and fiducials found in an image: contours, line segments, circles, markers and a
// chessboard's corners. Each keeps the header and size of the image it was found in (like
// Regions), in that image's pixel coordinates. Boxes found by detectors travel as Regions.
#pragma once

#include <string>
#include <vector>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief Contours of a binary image (FindContours), as cv::findContours gives them. */
struct Contours {
  std_msgs::Header header;
  cv::Size image_size;
  std::vector<std::vector<cv::Point>> contours;
  /** Per contour, as cv::findContours: next, previous, first child, parent (-1: none). Empty
   *  when unknown; else one per contour. */
  std::vector<cv::Vec4i> hierarchy;
};

/** @brief Line segments (HoughLines): x1, y1, x2, y2 each, in pixels. */
struct Lines {
  std_msgs::Header header;
  cv::Size image_size;
  std::vector<cv::Vec4f> lines;
};

/** @brief Circles (HoughCircles): centre x, y and radius each, in pixels. */
struct Circles {
  std_msgs::Header header;
  cv::Size image_size;
  std::vector<cv::Vec3f> circles;
};

/** @brief Square fiducials (ArucoDetector): one id and four corners per marker (clockwise from
 *  the marker's top-left, as cv::aruco::detectMarkers gives them); with a camera model, each
 *  marker's pose in the camera's frame (the image's header.frame_id). */
struct Markers {
  std_msgs::Header header;
  cv::Size image_size;
  std::string dictionary;  ///< e.g. "4x4_50": what the ids mean
  double marker_length = 0;  ///< the side the poses assume, metres
  std::vector<int> ids;
  std::vector<std::vector<cv::Point2f>> corners;  ///< 4 each
  std::vector<cv::Vec3d> rvecs, tvecs;  ///< empty without a camera model; else one per marker (Rodrigues, metres)
};

/** @brief A chessboard's inner corners (ChessboardCorners), row by row as
 *  cv::findChessboardCorners orders them; empty with found == false when the board is not seen. */
struct Corners {
  std_msgs::Header header;
  cv::Size image_size;
  cv::Size pattern_size;  ///< inner corners per row (width) and per column (height)
  bool found = false;
  std::vector<cv::Point2f> corners;
};

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::Contours, "apex_nodes/Contours");
APEX_TYPE_NAME(apex_nodes::Lines, "apex_nodes/Lines");
APEX_TYPE_NAME(apex_nodes::Circles, "apex_nodes/Circles");
APEX_TYPE_NAME(apex_nodes::Markers, "apex_nodes/Markers");
APEX_TYPE_NAME(apex_nodes::Corners, "apex_nodes/Corners");
