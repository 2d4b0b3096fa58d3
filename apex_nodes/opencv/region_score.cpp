// RegionScore: how well a frame's regions (BlobDetection's) match the ground truth that
// apex_make_demo_bag writes: frames found by stamp, truth boxes matched one-to-one to regions
// whose overlap (intersection over union) reaches `iou`, best overlaps first.
#include "apex/core/registry.hpp"
#include "apex_nodes/truth.hpp"

namespace apex_nodes {

class RegionScore : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Scores a frame's regions against the ground truth (apex_make_demo_bag's truth file)")
        .input<Regions>("regions", "e.g. BlobDetection's")
        .output<double>("precision", "matched regions / regions (1 if none were found)")
        .output<double>("recall", "matched truth boxes / truth boxes (1 if the frame has none)")
        .output<double>("f1", "2 precision recall / (precision + recall); 0 if both are 0")
        .param(apex::param::path("truth", "", apex::PathMode::Read)
                   .describe("the ground truth: frames by stamp, boxes in the upright scene and the camera's rotation"))
        .param(apex::param::range("iou", 0.05, 1.0, 0.05, 0.5).describe("overlap a region needs to match a truth box"));
  }
  void parameterChanged(const std::string& name) override {
    if (name == "truth") truth_file_.reset();  // read on the next frame, where an error shows
  }
  void process() override {
    const Regions& in = *regions_.get();
    const std::vector<TruthSign> signs = truth_file_.get(truth_.get()).signsFor(in, truth_.get());
    const auto n = static_cast<double>(matchSigns(signs, in.regions, iou_.get()).size());
    const double precision = in.regions.empty() ? 1.0 : n / in.regions.size();
    const double recall = signs.empty() ? 1.0 : n / signs.size();
    precision_.publish(precision);
    recall_.publish(recall);
    f1_.publish(precision + recall > 0 ? 2 * precision * recall / (precision + recall) : 0.0);
  }

 private:
  apex::Input<Regions> regions_{this, "regions"};
  apex::Output<double> precision_{this, "precision"};
  apex::Output<double> recall_{this, "recall"};
  apex::Output<double> f1_{this, "f1"};
  apex::Param<std::string> truth_{this, "truth"};
  apex::Param<double> iou_{this, "iou"};
  TruthFile truth_file_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::RegionScore, "apex_nodes/RegionScore");
