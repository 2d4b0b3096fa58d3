// DigitScore: how well regions' labels (DigitClassifier's) match the digits of the ground truth
// over a sequence (e.g. one pass of a bag): at its end (the player's end-of-sequence token, or the
// `finish` slot) it sends the accuracy, the counts and the confusion matrix, then starts the next.
#include <array>
#include <cstdio>

#include "apex/core/registry.hpp"
#include "apex_nodes/truth.hpp"

namespace apex_nodes {
namespace param = apex::param;

class DigitScore : public apex::Node {
 public:
  static constexpr int kDigits = 10;

  static inline const apex::InputPort<Regions> kRegions{"regions", "labelled, e.g. DigitClassifier's"};
  static inline const apex::OutputPort<double> kAccuracy{
      "accuracy", "at the end of a sequence: right labels / regions matched to a sign (1 if none)"};
  static inline const apex::OutputPort<int> kMatched{
      "matched", "at the end of a sequence: regions matched to a sign, the accuracy's denominator"};
  static inline const apex::OutputPort<int> kRegionsSeen{"regions", "at the end of a sequence: regions seen"};
  static inline const apex::OutputPort<std::string> kConfusion{
      "confusion", "at the end of a sequence: the confusion matrix, a row per true digit, a column per label ('?': rejected)"};
  static inline const apex::ParamDecl<std::string> kTruth =
      param::path("truth").mode(apex::PathMode::ReadFileOrFolder).describe("the ground truth with each sign's digit");
  static inline const apex::ParamDecl<double> kIou =
      param::number("iou").range(0.05, 1.0).step(0.05).init(0.5).describe("overlap a region needs to match a sign");
  static apex::Manifest manifest() {
    return apex::Manifest("Scores regions' digit labels against the ground truth over a sequence (accuracy, confusion matrix)")
        .inCategory("evaluation")
        .input(kRegions)
        .output(kAccuracy)
        .output(kMatched)
        .output(kRegionsSeen)
        .output(kConfusion)
        .param(kTruth)
        .param(kIou)
        .slot("reset", &DigitScore::reset, "forgets the counts: a new sequence starts")
        .slot("finish", &DigitScore::finish, "ends the sequence now, as its end-of-sequence token does");
  }
  void parameterChanged(const std::string& name) override {
    if (name == kTruth.name()) truth_file_.reset();
  }
  void process() override {
    const Regions& in = *regions_.get();
    const Truth& truth = truth_file_.get(truth_.get());
    truth.requireDigits(truth_.get());
    const std::vector<TruthSign> signs = truth.signsFor(in, truth_.get());
    for (const auto& [s, r] : matchSigns(signs, in.regions, iou_.get())) {
      const int digit = signs[s].digit, label = in.regions[r].label;
      if (digit < 0 || digit >= kDigits) continue;
      ++counts_[digit][label >= 0 && label < kDigits ? label : kDigits];
      ++matched_;
      right_ += label == digit;
    }
    regions_seen_ += static_cast<int>(in.regions.size());
  }
  void endOfSequence() override { finish(); }  // the result goes out in the token's place
  void finish() {
    accuracy_.publish(matched_ ? static_cast<double>(right_) / matched_ : 1.0);
    matched_out_.publish(matched_);
    regions_out_.publish(regions_seen_);
    confusion_.publish(table());
    reset();
  }
  void reset() {
    counts_ = {};
    matched_ = right_ = regions_seen_ = 0;
  }

 private:
  std::string table() const {
    std::string out = "true\\label";
    char cell[16];
    for (int c = 0; c < kDigits; ++c) {
      std::snprintf(cell, sizeof cell, "%5d", c);
      out += cell;
    }
    out += "    ?";
    for (int d = 0; d < kDigits; ++d) {
      std::snprintf(cell, sizeof cell, "\n%10d", d);
      out += cell;
      for (int c = 0; c <= kDigits; ++c) {
        std::snprintf(cell, sizeof cell, "%5d", counts_[d][c]);
        out += cell;
      }
    }
    return out;
  }

  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<double> accuracy_{this, kAccuracy};
  apex::Output<int> matched_out_{this, kMatched};
  apex::Output<int> regions_out_{this, kRegionsSeen};
  apex::Output<std::string> confusion_{this, kConfusion};
  apex::Param<std::string> truth_{this, kTruth};
  apex::Param<double> iou_{this, kIou};
  TruthFile truth_file_;
  std::array<std::array<int, kDigits + 1>, kDigits> counts_{};
  int matched_ = 0, right_ = 0, regions_seen_ = 0;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DigitScore, "apex_nodes/DigitScore");
