#include "apex_rviz_plugin/frame_labels.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>

#include "apex/core/graph_file.hpp"  // writeFileAtomically

namespace apex_rviz_plugin {
namespace {

std::string trimmed(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  return begin == std::string::npos ? "" : s.substr(begin, s.find_last_not_of(" \t\r\n") - begin + 1);
}

/** `text` as a JSON string, quotes and all. */
std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (static_cast<unsigned char>(c) < 0x20) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(c));
      out += code;
    } else out += c;  // UTF-8 passes as it is
  }
  return out + "\"";
}

std::string sizeText(int width, int height) { return std::to_string(width) + "×" + std::to_string(height); }

}  // namespace

apex::Status FrameLabels::mark(std::uint64_t stamp, int width, int height) {
  if (stamp == 0)
    return apex::Status::error(
        "this frame has no stamp (0): boxes on it would match no regions; "
        "label the frames of a bag or of a camera that stamps its images");
  if (width <= 0 || height <= 0) return apex::Status::error("this frame's image is empty (" + sizeText(width, height) + ")");
  LabelledFrame& f = frames_[stamp];
  f.stamp = stamp, f.width = width, f.height = height;
  return apex::Status::ok();
}

apex::Status FrameLabels::add(std::uint64_t stamp, int width, int height, LabelBox box) {
  box.label = trimmed(box.label);
  if (box.label.empty()) return apex::Status::error("a box needs a class: type one in the class field");
  // cut to the image: a drag that ends outside it ends at its edge
  const int x0 = std::clamp(box.x, 0, std::max(width, 0)), y0 = std::clamp(box.y, 0, std::max(height, 0));
  const int x1 = std::clamp(box.x + box.width, 0, std::max(width, 0)),
            y1 = std::clamp(box.y + box.height, 0, std::max(height, 0));
  if (x1 <= x0 || y1 <= y0)
    return apex::Status::error("a box of " + sizeText(std::max(x1 - x0, 0), std::max(y1 - y0, 0)) +
                               " pixels in the image ignored: drag from one corner of the object to the opposite one");
  if (const apex::Status st = mark(stamp, width, height); !st) return st;
  box.x = x0, box.y = y0, box.width = x1 - x0, box.height = y1 - y0;
  frames_[stamp].boxes.push_back(std::move(box));
  return apex::Status::ok();
}

bool FrameLabels::remove(std::uint64_t stamp, std::size_t index) {
  auto it = frames_.find(stamp);
  if (it == frames_.end() || index >= it->second.boxes.size()) return false;
  it->second.boxes.erase(it->second.boxes.begin() + static_cast<std::ptrdiff_t>(index));
  return true;
}

bool FrameLabels::relabel(std::uint64_t stamp, std::size_t index, const std::string& label) {
  auto it = frames_.find(stamp);
  if (it == frames_.end() || index >= it->second.boxes.size() || trimmed(label).empty()) return false;
  it->second.boxes[index].label = trimmed(label);
  return true;
}

const LabelledFrame* FrameLabels::frame(std::uint64_t stamp) const {
  auto it = frames_.find(stamp);
  return it == frames_.end() ? nullptr : &it->second;
}

std::size_t FrameLabels::boxCount() const {
  std::size_t n = 0;
  for (const auto& [stamp, f] : frames_) n += f.boxes.size();
  return n;
}

std::vector<std::string> FrameLabels::labels() const {
  std::set<std::string> names;
  for (const auto& [stamp, f] : frames_)
    for (const auto& b : f.boxes) names.insert(b.label);
  return {names.begin(), names.end()};
}

std::string frameImageName(std::uint64_t stamp) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%llu.%09llu.png", static_cast<unsigned long long>(stamp / 1000000000ULL),
                static_cast<unsigned long long>(stamp % 1000000000ULL));
  return name;
}

std::string cocoJson(const FrameLabels& labels) {
  const std::vector<std::string> names = labels.labels();
  auto category = [&names](const std::string& label) {
    return std::lower_bound(names.begin(), names.end(), label) - names.begin() + 1;
  };
  std::string images, annotations, categories;
  int image_id = 0, annotation_id = 0;
  for (const auto& [stamp, f] : labels.frames()) {
    ++image_id;
    images += std::string(images.empty() ? "" : ",\n") + "    {\"id\": " + std::to_string(image_id) +
              ", \"file_name\": " + jsonString(frameImageName(stamp)) + ", \"width\": " + std::to_string(f.width) +
              ", \"height\": " + std::to_string(f.height) + "}";
    for (const auto& b : f.boxes)
      annotations += std::string(annotations.empty() ? "" : ",\n") + "    {\"id\": " + std::to_string(++annotation_id) +
                     ", \"image_id\": " + std::to_string(image_id) + ", \"category_id\": " + std::to_string(category(b.label)) +
                     ", \"bbox\": [" + std::to_string(b.x) + ", " + std::to_string(b.y) + ", " + std::to_string(b.width) + ", " +
                     std::to_string(b.height) + "], \"area\": " + std::to_string(b.width * b.height) + ", \"iscrowd\": 0}";
  }
  for (std::size_t i = 0; i < names.size(); ++i)
    categories +=
        std::string(i ? ",\n" : "") + "    {\"id\": " + std::to_string(i + 1) + ", \"name\": " + jsonString(names[i]) + "}";
  auto list = [](const std::string& items) { return items.empty() ? std::string("[]") : "[\n" + items + "\n  ]"; };
  return "{\n  \"info\": {\"description\": \"frames labelled in the APEX panel\"},\n  \"images\": " + list(images) +
         ",\n  \"annotations\": " + list(annotations) + ",\n  \"categories\": " + list(categories) + "\n}\n";
}

apex::Status saveCoco(const FrameLabels& labels, const std::string& path) {
  if (labels.frames().empty())
    return apex::Status::error("nothing to save to '" + path +
                               "': no frame is labelled yet (draw a box, or mark a frame labelled)");
  if (path.empty()) return apex::Status::error("no file to save the labels to: give a path ending in .json");
  std::string ending = path.size() >= 5 ? path.substr(path.size() - 5) : "";
  std::transform(ending.begin(), ending.end(), ending.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ending != ".json")  // loadTruth tells a COCO file by its extension
    return apex::Status::error("cannot save the labels to '" + path +
                               "': a COCO file's name ends in .json (RegionScore reads it so)");
  if (const apex::Status st = apex::writeFileAtomically(path, cocoJson(labels)); !st)
    return apex::Status::error("cannot save the labels: " + st.message());
  return apex::Status::ok();
}

}  // namespace apex_rviz_plugin
