// SampleExport's samples as the training tools read them (apex_train_mlp, apex_train): the crops
// DIR/index.csv lists (file,label,stamp_ns,x,y,width,height), with their labels.
#pragma once

#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"

namespace apex_tools {

/** @brief Appends the crops of DIR/index.csv, read with `flags` (cv::IMREAD_GRAYSCALE, ...), and
 *  their labels. Throws std::invalid_argument naming the index and the line of what is wrong. */
inline void readSamples(const std::string& dir, int flags, std::vector<cv::Mat>& crops, std::vector<int>& labels) {
  const std::string index = dir + "/index.csv";
  std::ifstream in(index);
  if (!in) throw std::invalid_argument("cannot read '" + index + "' (SampleExport writes it)");
  const std::size_t before = labels.size();
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n == 1 && line.rfind("file,", 0) == 0) continue;
    std::stringstream fields(line);
    std::string file, label;
    if (!std::getline(fields, file, ',') || !std::getline(fields, label, ','))
      throw std::invalid_argument(index + " line " + std::to_string(n) + ": needs 'file,label,...'");
    const cv::Mat crop = cv::imread(dir + "/" + file, flags);
    if (crop.empty()) throw std::invalid_argument(index + " line " + std::to_string(n) + ": cannot read '" + file + "'");
    crops.push_back(crop);
    labels.push_back(static_cast<int>(number(index + " line " + std::to_string(n) + ": the label", label, 0, 1 << 20)));
  }
  if (labels.size() == before) throw std::invalid_argument(index + " lists no samples");
}

}  // namespace apex_tools
