// SampleExport: training samples from a running pipeline. Each region that matches a sign of
// the ground truth is cut out of the image and written as DIGIT/STAMP_REGION.png under
// `directory`, and listed in DIRECTORY/index.csv (file,label,stamp_ns,x,y,width,height), which
// apex_train_mlp reads. With `negatives` set, each region that overlaps no sign at all (a window,
// a shadow: what the detector wrongly found) is written too, under that label: a classifier
// trained on them learns to reject such regions (DigitClassifier's reject_label). The index is replaced whole after every frame
// (never half-written); a second pass over the same bag rewrites the same samples, and other bags add theirs.
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "apex/core/graph_file.hpp"
#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/truth.hpp"

namespace apex_nodes {
namespace fs = std::filesystem;
namespace param = apex::param;

class SampleExport : public apex::Node {
 public:
  static constexpr const char* kIndexHeader = "file,label,stamp_ns,x,y,width,height";

  static inline const apex::InputPort<Image> kImage{"image", "the image the regions were found in"};
  static inline const apex::InputPort<Regions> kRegions{"regions", "e.g. BlobDetection's"};
  static inline const apex::OutputPort<int> kWritten{"written", "samples this frame gave"};
  static inline const apex::OutputPort<int> kSamples{
      "samples", "at the end of a sequence (e.g. a pass of the bag): samples in the directory's index"};
  static inline const apex::ParamDecl<std::string> kDirectory =
      param::path("directory")
          .describe("where the samples go (made if missing): DIGIT/STAMP_REGION.png and index.csv")
          .mode(apex::PathMode::Directory);
  static inline const apex::ParamDecl<std::string> kTruth =
      param::path("truth").mode(apex::PathMode::ReadFileOrFolder).describe("the ground truth with each sign's digit");
  static inline const apex::ParamDecl<double> kIou =
      param::number("iou").range(0.05, 1.0).step(0.05).init(0.5).describe("overlap a region needs to match a sign");
  static inline const apex::ParamDecl<int> kNegatives =
      param::integer("negatives")
          .range(-1, 1000000)
          .step(1)
          .init(-1)
          .describe("label of the regions that overlap no sign (hard negatives), written as the signs are; -1: not written");
  static inline const apex::ParamDecl<bool> kOverwrite =
      param::flag("overwrite").describe("replace files at a sample's name that index.csv does not list (not samples)");

  static apex::Manifest manifest() {
    return apex::Manifest("Writes the crop of each region that matches a labelled sign of the ground truth, with an index file")
        .inCategory("learning")
        .keepsState("the files it writes: a re-run writes the held frame's samples again")
        .input(kImage)
        .input(kRegions)
        .output(kWritten)
        .output(kSamples)
        .param(kDirectory)
        .param(kTruth)
        .param(kIou)
        .param(kNegatives)
        .param(kOverwrite);
  }
  void parameterChanged(const std::string& name) override {
    if (name == kTruth.name()) truth_file_.reset();
    if (name == kDirectory.name()) index_dir_.clear();  // read the new folder's index first
  }
  void process() override {
    const Image& image = *image_.get();
    const Regions& in = *regions_.get();
    requireImage(image);
    const std::string& dir = directory_.get();
    if (dir.empty()) throw std::invalid_argument("no directory: set 'directory' to the folder for the samples");
    const Truth& truth = truth_file_.get(truth_.get());
    truth.requireDigits(truth_.get());
    const std::vector<TruthSign> signs = truth.signsFor(in, truth_.get());
    openIndex(dir);
    const cv::Rect frame(0, 0, image.mat.cols, image.mat.rows);
    int written = 0;
    const auto save = [&](int label, int r) {
      const cv::Rect box = in.regions[r].box & frame;
      if (box.empty() || label < 0) return;
      write(dir, label, in.header.stamp.toNSec(), r, box, image.mat(box));
      ++written;
    };
    for (const auto& [s, r] : matchSigns(signs, in.regions, iou_.get())) save(signs[s].digit, r);
    if (negatives_.get() >= 0)
      for (std::size_t r = 0; r < in.regions.size(); ++r)
        if (overlapsNone(in.regions[r].box, signs)) save(negatives_.get(), static_cast<int>(r));
    if (written) saveIndex(dir);
    written_.publish(written);
  }
  void endOfSequence() override { samples_.publish(static_cast<int>(index_.size())); }  // in the token's place

 private:
  static bool overlapsNone(const cv::Rect& box, const std::vector<TruthSign>& signs) {
    for (const auto& s : signs)
      if ((s.box & box).area() > 0) return false;
    return true;
  }
  void write(const std::string& dir, int digit, std::uint64_t stamp, int region, const cv::Rect& box, const cv::Mat& crop) {
    const std::string folder = std::to_string(digit);
    std::error_code ec;
    fs::create_directories(fs::path(dir) / folder, ec);
    if (ec) throw std::runtime_error("cannot make the folder '" + dir + "/" + folder + "': " + ec.message());
    const std::string file = folder + "/" + std::to_string(stamp) + "_" + std::to_string(region) + ".png";
    // A sample of an earlier export (in the index) is written anew; any other file is the user's
    if (!index_.count(file) && !overwrite_.get() && fs::exists(fs::symlink_status(fs::path(dir) / file)))
      throw std::runtime_error("'" + dir + "/" + file + "' exists and is not a sample of index.csv: left as it is; " +
                               "set 'overwrite' to replace it, or choose another directory");
    if (!cv::imwrite(dir + "/" + file, crop)) throw std::runtime_error("cannot write '" + dir + "/" + file + "'");
    index_[file] = file + "," + folder + "," + std::to_string(stamp) + "," + std::to_string(box.x) + "," + std::to_string(box.y) +
                   "," + std::to_string(box.width) + "," + std::to_string(box.height);
  }
  /** The index already in `dir` (from an earlier run), read once per folder. */
  void openIndex(const std::string& dir) {
    if (index_dir_ == dir) return;
    index_.clear();
    std::ifstream in(dir + "/index.csv");
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (n == 1 && line == kIndexHeader) continue;
      const auto comma = line.find(',');
      if (comma == std::string::npos || comma == 0)
        throw std::invalid_argument("'" + dir + "/index.csv' line " + std::to_string(n) +
                                    " is not 'file,label,...': move the file away");
      index_[line.substr(0, comma)] = line;
    }
    index_dir_ = dir;
  }
  void saveIndex(const std::string& dir) const {
    std::string text = std::string(kIndexHeader) + "\n";
    for (const auto& [file, line] : index_) text += line + "\n";
    const apex::Status st = apex::writeFileAtomically(dir + "/index.csv", text);
    if (!st) throw std::runtime_error(st.message());
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<int> written_{this, kWritten};
  apex::Output<int> samples_{this, kSamples};
  apex::Param<std::string> directory_{this, kDirectory};
  apex::Param<std::string> truth_{this, kTruth};
  apex::Param<double> iou_{this, kIou};
  apex::Param<int> negatives_{this, kNegatives};
  apex::Param<bool> overwrite_{this, kOverwrite};
  TruthFile truth_file_;
  std::map<std::string, std::string> index_;  // file → its line
  std::string index_dir_;  // the folder index_ belongs to
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::SampleExport, "apex_nodes/SampleExport");
