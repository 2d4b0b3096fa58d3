// Ground truth from a COCO file (images[], annotations[] with bbox [x, y, w, h], categories[]),
// read through yaml-cpp: JSON is YAML's flow style.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>

#include "truth_formats.hpp"

namespace apex_nodes {
namespace truth_formats {
namespace {

long long integer(const YAML::Node& node, const std::string& file, const std::string& where) {
  const double v = number(node, file, where);
  if (v != std::floor(v)) fail(file, where + ": " + node.Scalar() + " is not a whole number");
  return static_cast<long long>(v);
}

/** `root[key]` as a list, empty if it is missing; throws naming `file` if it is not a list. */
YAML::Node list(const YAML::Node& root, const char* key, const std::string& file) {
  const YAML::Node n = root[key];
  if (n && !n.IsSequence() && !n.IsNull()) fail(file, std::string("'") + key + "' is not a list");
  return n && n.IsSequence() ? n : YAML::Node(YAML::NodeType::Sequence);
}

std::string entry(const char* key, std::size_t i) { return std::string(key) + "[" + std::to_string(i) + "]"; }

/** Category names by id. */
std::map<long long, std::string> categories(const YAML::Node& root, const std::string& file) {
  std::map<long long, std::string> names;
  const YAML::Node cats = list(root, "categories", file);
  for (std::size_t i = 0; i < cats.size(); ++i) {
    const std::string where = entry("categories", i);
    names[integer(need(cats[i], "id", file, where), file, where + ".id")] =
        text(need(cats[i], "name", file, where), file, where + ".name");
  }
  return names;
}

}  // namespace

Truth readCoco(const YAML::Node& root, const std::string& file) {
  Truth t;
  const auto names = categories(root, file);
  std::map<long long, std::vector<TruthSign>*> frames;  // by image id
  const YAML::Node images = list(root, "images", file);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string where = entry("images", i);
    const long long id = integer(need(images[i], "id", file, where), file, where + ".id");
    const std::string name = text(need(images[i], "file_name", file, where), file, where + ".file_name");
    if (frames.count(id)) fail(file, where + ": a second image with id " + std::to_string(id));
    frames[id] = &newFrame(t, stampOfImage(name, file, where), file, where);
  }
  const YAML::Node annotations = list(root, "annotations", file);
  for (std::size_t i = 0; i < annotations.size(); ++i) {
    const std::string where = entry("annotations", i);
    const YAML::Node a = annotations[i];
    const long long image = integer(need(a, "image_id", file, where), file, where + ".image_id");
    const long long category = integer(need(a, "category_id", file, where), file, where + ".category_id");
    const YAML::Node bbox = need(a, "bbox", file, where);
    if (!frames.count(image)) fail(file, where + ": image_id " + std::to_string(image) + " is not among the images");
    if (!names.count(category)) fail(file, where + ": category_id " + std::to_string(category) + " is not among the categories");
    if (!bbox.IsSequence() || bbox.size() != 4) fail(file, where + ".bbox: not [x, y, width, height]");
    double b[4];
    for (std::size_t k = 0; k < 4; ++k) b[k] = number(bbox[k], file, where + ".bbox");
    frames[image]->push_back(signOf(b[0], b[1], b[0] + b[2], b[1] + b[3], names.at(category)));
  }
  finishLabelled(t, file);
  return t;
}

}  // namespace truth_formats
}  // namespace apex_nodes
