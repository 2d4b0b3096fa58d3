// The Optimizer's study file (study_file.hpp).
#include "study_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "apex/core/graph_file.hpp"

namespace apex_nodes {
namespace tuning {

namespace {

const char* const kMagic = "# apex optimizer study: ";

std::string exact(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

StudyFile::StudyFile(std::string path, std::string settings, std::vector<std::string> columns, bool with_cost)
    : path_(std::move(path)), settings_(std::move(settings)), columns_(std::move(columns)), with_cost_(with_cost) {}

std::string StudyFile::header() const {
  std::string out = kMagic + settings_ + "\nevaluation,fitness" + (with_cost_ ? ",ms_per_frame" : "");
  for (const auto& c : columns_) out += "," + c;
  return out + "\n";
}

std::vector<Evaluation> StudyFile::read() {
  lines_.clear();
  std::ifstream in(path_);
  if (!in) return {};
  const std::string want = header();
  std::string line, head;
  for (int i = 0; i < 2 && std::getline(in, line); ++i) head += line + "\n";
  if (head != want)
    throw std::invalid_argument("the study '" + path_ + "' was made by another run (" +
                                (head.rfind(kMagic, 0) == 0
                                     ? head.substr(std::string(kMagic).size(), head.find('\n') - std::string(kMagic).size())
                                     : std::string("not a study file")) +
                                "); this run is " + settings_ + ": name another file, or move it away to start anew");
  std::vector<Evaluation> out;
  for (int n = 3; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string field;
    std::vector<double> values;
    while (std::getline(fields, field, ',')) {
      char* end = nullptr;
      const double v = std::strtod(field.c_str(), &end);
      if (field.empty() || *end)
        throw std::invalid_argument("the study '" + path_ + "' line " + std::to_string(n) + ": '" + field + "' is not a number");
      values.push_back(v);
    }
    const std::size_t first = with_cost_ ? 3 : 2;  // of the point's values
    if (values.size() != columns_.size() + first || values[0] != static_cast<double>(out.size() + 1))
      throw std::invalid_argument("the study '" + path_ + "' line " + std::to_string(n) + ": not evaluation " +
                                  std::to_string(out.size() + 1) + " with a fitness" + (with_cost_ ? ", a cost" : "") + " and " +
                                  std::to_string(columns_.size()) + " values");
    out.push_back({std::vector<double>(values.begin() + first, values.end()), values[1], with_cost_ ? values[2] : 0.0});
    lines_ += line + "\n";
  }
  return out;
}

void StudyFile::append(const Evaluation& e) {
  std::string line = std::to_string(std::count(lines_.begin(), lines_.end(), '\n') + 1) + "," + exact(e.fitness);
  if (with_cost_) line += "," + exact(e.cost_ms);
  for (double v : e.point) line += "," + exact(v);
  lines_ += line + "\n";
  const apex::Status st = apex::writeFileAtomically(path_, header() + lines_);
  if (!st) throw std::runtime_error("cannot write the study: " + st.message());
}

std::unique_ptr<StudyFile> openStudy(const std::string& path, const std::string& settings,
                                     const std::vector<search::Dimension>& coordinates, bool with_cost) {
  if (path.empty()) return nullptr;
  std::vector<std::string> columns;
  for (const auto& c : coordinates) columns.push_back(c.name);
  return std::make_unique<StudyFile>(path, settings, columns, with_cost);
}

bool samePoint(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i])) return false;
  return true;
}

std::vector<Scored> replay(StudyFile& study, search::Search& search, bool minimize) {
  std::vector<Scored> told;
  for (const auto& e : study.read()) {
    if (search.done()) break;
    if (!samePoint(search.ask(), e.point))
      throw std::invalid_argument("the study '" + study.path() + "': evaluation " + std::to_string(told.size() + 1) +
                                  " is not this run's candidate (the search was changed?): name another file, or move it away");
    search.tell(minimize ? -e.fitness : e.fitness);
    told.push_back({static_cast<int>(told.size()) + 1, e.fitness, e.cost_ms, e.point});
  }
  return told;
}

}  // namespace tuning
}  // namespace apex_nodes
