// Ground truth from Pascal VOC files (one per image: <filename>, <object> with <name> and <bndbox>
// xmin ymin xmax ymax), read with tinyxml2 (pluginlib's XML parser).
#include <tinyxml2.h>

#include <cstdlib>
#include <filesystem>

#include "truth_formats.hpp"

namespace apex_nodes {
namespace truth_formats {
namespace {

std::string line(const tinyxml2::XMLElement* e) { return "line " + std::to_string(e->GetLineNum()); }

/** The text of `parent`'s element `name`; throws naming the file and the line if there is none. */
std::string child(const tinyxml2::XMLElement* parent, const char* name, const std::string& file) {
  const tinyxml2::XMLElement* e = parent->FirstChildElement(name);
  if (!e || !e->GetText()) fail(file, line(parent) + ": <" + parent->Name() + "> has no <" + name + ">");
  return e->GetText();
}

double coordinate(const tinyxml2::XMLElement* box, const char* name, const std::string& file) {
  const std::string s = child(box, name, file);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || s.find_first_not_of(" \t\r\n", end - s.c_str()) != std::string::npos)
    fail(file, line(box->FirstChildElement(name)) + ": <" + name + "> '" + s + "' is not a number");
  return v;
}

TruthSign objectSign(const tinyxml2::XMLElement* object, const std::string& file) {
  const std::string label = child(object, "name", file);
  const tinyxml2::XMLElement* box = object->FirstChildElement("bndbox");
  if (!box) fail(file, line(object) + ": <object> has no <bndbox>");
  // xmax - xmin is the width, as labelImg and CVAT write them (the VOC devkit's 1-based inclusive
  // corners make a box a pixel larger, which moves its overlap with a region by a few percent)
  return signOf(coordinate(box, "xmin", file), coordinate(box, "ymin", file), coordinate(box, "xmax", file),
                coordinate(box, "ymax", file), label);
}

}  // namespace

void readVoc(const std::string& file, Truth& t) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLError e = doc.LoadFile(file.c_str());
  if (e == tinyxml2::XML_ERROR_FILE_NOT_FOUND || e == tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED) fail(file, "cannot be read");
  if (e != tinyxml2::XML_SUCCESS)
    fail(file, "line " + std::to_string(doc.ErrorLineNum()) + ": not well-formed XML (" + doc.ErrorName() + ")");
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "annotation") fail(file, "not a Pascal VOC file: no <annotation>");
  const tinyxml2::XMLElement* name = root->FirstChildElement("filename");  // else the file is named after its image
  const std::string image = name && name->GetText() ? name->GetText() : std::filesystem::path(file).filename().string();
  const std::string where = name ? line(name) + ": <filename>" : "its name";
  auto& signs = newFrame(t, stampOfImage(image, file, where), file, where);
  for (auto* o = root->FirstChildElement("object"); o; o = o->NextSiblingElement("object")) signs.push_back(objectSign(o, file));
}

}  // namespace truth_formats
}  // namespace apex_nodes
