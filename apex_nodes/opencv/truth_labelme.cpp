// Ground truth from a labelme file (one per image: imagePath, shapes[] with label, shape_type and
// points), read through yaml-cpp: JSON is YAML's flow style.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "truth_formats.hpp"

namespace apex_nodes {
namespace truth_formats {
namespace {

/** A rectangle's two corners, or a polygon's bounding box; other shapes are no sign. */
TruthSign shapeSign(const YAML::Node& shape, const std::string& file, const std::string& where) {
  const std::string label = text(need(shape, "label", file, where), file, where + ".label");
  const YAML::Node type = shape["shape_type"];  // older labelme: none, a polygon
  const std::string kind = type && !type.IsNull() ? text(type, file, where + ".shape_type") : "polygon";
  if (kind != "rectangle" && kind != "polygon")
    fail(file, where + ": a " + kind + "; a sign is a rectangle (or a polygon, by its bounding box)");
  const YAML::Node points = need(shape, "points", file, where);
  if (!points.IsSequence() || points.size() < 2) fail(file, where + ".points: not a list of at least two [x, y]");
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& p : points) {
    if (!p.IsSequence() || p.size() != 2) fail(file, where + ".points: not a list of [x, y]");
    const double x = number(p[0], file, where + ".points"), y = number(p[1], file, where + ".points");
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  return signOf(x0, y0, x1, y1, label);
}

}  // namespace

void readLabelme(const YAML::Node& root, const std::string& file, Truth& t) {
  const YAML::Node path = root["imagePath"];  // else the file is named after its image
  const std::string image =
      path && !path.IsNull() ? text(path, file, "imagePath") : std::filesystem::path(file).filename().string();
  auto& signs = newFrame(t, stampOfImage(image, file, "imagePath"), file, "imagePath");
  const YAML::Node shapes = need(root, "shapes", file, "the file");
  if (!shapes.IsSequence() && !shapes.IsNull()) fail(file, "'shapes' is not a list");
  for (std::size_t i = 0; i < shapes.size(); ++i)
    signs.push_back(shapeSign(shapes[i], file, "shapes[" + std::to_string(i) + "]"));
}

}  // namespace truth_formats
}  // namespace apex_nodes
