// RegionScore: how well a frame's regions (BlobDetection's) match the ground truth (the one that
// apex_make_demo_bag writes, or a labelling tool's: truth.hpp): frames found by stamp, truth boxes
// matched one-to-one to regions whose overlap (intersection over union) reaches `iou`, best overlaps first.
#include "apex/core/registry.hpp"
#include "apex_nodes/truth.hpp"

namespace apex_nodes {
namespace param = apex::param;

class RegionScore : public apex::Node {
 public:
  static inline const apex::InputPort<Regions> kRegions{"regions", "e.g. BlobDetection's"};
  static inline const apex::OutputPort<double> kPrecision{"precision", "matched regions / regions (1 if none were found)"};
  static inline const apex::OutputPort<double> kRecall{"recall", "matched truth boxes / truth boxes (1 if the frame has none)"};
  static inline const apex::OutputPort<double> kF1{"f1", "2 precision recall / (precision + recall); 0 if both are 0"};
  static inline const apex::ParamDecl<std::string> kTruth =
      param::path("truth")
          .mode(apex::PathMode::ReadFileOrFolder)
          .describe(
              "the ground truth: apex_make_demo_bag's, or a labelling tool's (COCO, Pascal VOC, YOLO, labelme; images named by "
              "stamp)");
  static inline const apex::ParamDecl<double> kIou =
      param::number("iou").range(0.05, 1.0).step(0.05).init(0.5).describe("overlap a region needs to match a truth box");
  static inline const apex::ParamDecl<bool> kOnlyLabelled =
      param::flag("only_labelled")
          .describe(
              "frames the truth does not list send Nothing (scores over the labelled frames of a bag); off: they are an error");
  static apex::Manifest manifest() {
    return apex::Manifest("Scores a frame's regions against the ground truth (apex_make_demo_bag's, or a labelling tool's)")
        .inCategory("evaluation")
        .input(kRegions)
        .output(kPrecision)
        .output(kRecall)
        .output(kF1)
        .param(kTruth)
        .param(kIou)
        .param(kOnlyLabelled);
  }
  void parameterChanged(const std::string& name) override {
    if (name == kTruth.name()) truth_file_.reset();  // read on the next frame, where an error shows
  }
  void process() override {
    const Regions& in = *regions_.get();
    const Truth& truth = truth_file_.get(truth_.get());
    if (only_labelled_.get() && !truth.frameAt(in.header.stamp.toNSec())) return;  // not labelled: Nothing, no score
    const std::vector<TruthSign> signs = truth.signsFor(in, truth_.get());
    const auto n = static_cast<double>(matchSigns(signs, in.regions, iou_.get()).size());
    const double precision = in.regions.empty() ? 1.0 : n / in.regions.size();
    const double recall = signs.empty() ? 1.0 : n / signs.size();
    precision_.publish(precision);
    recall_.publish(recall);
    f1_.publish(precision + recall > 0 ? 2 * precision * recall / (precision + recall) : 0.0);
  }

 private:
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<double> precision_{this, kPrecision};
  apex::Output<double> recall_{this, kRecall};
  apex::Output<double> f1_{this, kF1};
  apex::Param<std::string> truth_{this, kTruth};
  apex::Param<double> iou_{this, kIou};
  apex::Param<bool> only_labelled_{this, kOnlyLabelled};
  TruthFile truth_file_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::RegionScore, "apex_nodes/RegionScore");
