// The readers behind loadTruth: apex_make_demo_bag's YAML (truth.cpp) and the files labelling
// tools write (COCO, Pascal VOC, YOLO, labelme; one .cpp each), with what they share: a frame's
// stamp from its image's name, a label's digit, a box from its corners, the errors.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "apex_nodes/truth.hpp"

namespace YAML {
class Node;
}

namespace apex_nodes {
namespace truth_formats {

/** @brief Throws std::invalid_argument "the ground truth 'FILE': WHAT". */
[[noreturn]] void fail(const std::string& file, const std::string& what);

/** @brief The stamp (ns) an image's file name carries: the number that ends its name without the
 *  extension, seconds with a point (`frame_1700000000.033333333.png`) or nanoseconds without one
 *  if it has at least 10 digits (`1700000000033333333.png`). Folders before the name are ignored.
 *  Throws naming `file` and `where` (the entry that names the image) for any other name. */
std::uint64_t stampOfImage(const std::string& image, const std::string& file, const std::string& where);

/** @brief A sign from a box's corners (rounded to whole pixels) and its label: the digit if the
 *  label is one of "0".."9", else -1. */
TruthSign signOf(double x0, double y0, double x1, double y1, const std::string& label);

/** @brief The frame at `stamp`, new and empty; throws naming `file` and `where` if `t` has one. */
std::vector<TruthSign>& newFrame(Truth& t, std::uint64_t stamp, const std::string& file, const std::string& where);

/** @brief Ends a labelling tool's truth: the labels are digits if every one is; throws naming
 *  `source` if there are no frames. */
void finishLabelled(Truth& t, const std::string& source);

/** @brief The JSON or YAML text of `file`; throws naming it (and the line) if it does not parse. */
YAML::Node loadJson(const std::string& file);
/** @brief `node[key]`; throws naming `file` and `where` if it is missing. */
YAML::Node need(const YAML::Node& node, const char* key, const std::string& file, const std::string& where);
/** @brief `node` as a number; throws naming `file`, `where` and the text if it is not one. */
double number(const YAML::Node& node, const std::string& file, const std::string& where);
/** @brief `node` as text; throws naming `file` and `where` if it is a list or a map. */
std::string text(const YAML::Node& node, const std::string& file, const std::string& where);

/** @brief apex_make_demo_bag's truth file (truth.cpp). */
Truth readDemoYaml(const std::string& file);
/** @brief A COCO file: every image a frame, its annotations' boxes and categories. */
Truth readCoco(const YAML::Node& root, const std::string& file);
/** @brief One labelme file's frame (its imagePath's stamp; rectangles and polygons' bounding boxes). */
void readLabelme(const YAML::Node& root, const std::string& file, Truth& t);
/** @brief One Pascal VOC file's frame (its <filename>'s stamp). */
void readVoc(const std::string& file, Truth& t);
/** @brief The class names for a YOLO file: `classes.txt` beside it or in the folder above (a name
 *  a line, the first is class 0), else none (the class number is the label). */
std::vector<std::string> yoloClasses(const std::string& file);
/** @brief One YOLO file's frame (its own name's stamp; the size from the image beside it). */
void readYolo(const std::string& file, const std::vector<std::string>& classes, Truth& t);

}  // namespace truth_formats
}  // namespace apex_nodes
