// DigitClassifier: the digit on each region (a sign), by a model apex_train_mlp wrote. The model
// is read when first needed, and again when the parameter is set or the file changes; a missing
// or damaged file is an error on the node (the regions still go out, unlabelled).
// With reject_label, a model trained with a "not a sign" class (SampleExport's negatives) is
// the detector's last stage: the regions it gives that class are dropped.
// A preset for the number signs (its own digit features and MLP file); Classifier is the general
// form: FeatureExtract's features of the regions, labelled by any cv::ml model (apex_train's).

#include <memory>

#include "apex/core/registry.hpp"
#include "apex_nodes/digits.hpp"
#include "apex_nodes/model_file.hpp"
#include "apex_nodes/image_check.hpp"

namespace apex_nodes {
namespace param = apex::param;

class DigitClassifier : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "the image the regions were found in"};
  static inline const apex::InputPort<Regions> kRegions{"regions", "e.g. BlobDetection's: one sign each"};
  static inline const apex::OutputPort<Regions> kLabelled{
      "regions", "the regions with label (the digit, -1 if unsure) and confidence; without those of reject_label"};
  static inline const apex::ParamDecl<std::string> kModel = param::path("model").describe("apex_train_mlp's model file");
  static inline const apex::ParamDecl<double> kMinConfidence =
      param::number("min_confidence")
          .range(0.0, 1.0)
          .step(0.01)
          .init(0.5)
          .describe("a region whose best digit is less certain gets label -1 (shown as '?')");
  static inline const apex::ParamDecl<int> kRejectLabel =
      param::integer("reject_label")
          .range(-1, 1000000)
          .step(1)
          .init(-1)
          .describe("the model's class for 'not a sign' (SampleExport's negatives): regions classified so are dropped; -1: none");
  static apex::Manifest manifest() {
    return apex::Manifest("Classifies the digit in each region with a trained MLP (apex_train_mlp's model file)")
        .inCategory("learning")
        .input(kImage)
        .input(kRegions)
        .output(kLabelled)
        .param(kModel)
        .param(kMinConfidence)
        .param(kRejectLabel);
  }
  void parameterChanged(const std::string& name) override {
    if (name == kModel.name()) model_.forget();
  }
  void process() override {
    const Image& image = *image_.get();
    const auto in = regions_.get();
    requireImage(image);
    const DigitModel* model = nullptr;
    try {
      model = &load();
    } catch (const std::invalid_argument& e) {
      reportError(e.what());
      regions_out_.publish(in);  // the pipeline goes on, unlabelled
      return;
    }
    auto out = std::make_shared<Regions>(*in);
    out->regions.clear();
    const cv::Rect frame(0, 0, image.mat.cols, image.mat.rows);
    for (Region r : in->regions) {
      const cv::Rect box = r.box & frame;
      if (!box.empty()) {
        const DigitPrediction p = model->classify(image.mat(box));
        if (p.label == reject_label_.get()) continue;  // not a sign
        r.confidence = p.confidence;
        r.label = p.confidence >= min_confidence_.get() ? p.label : -1;
      }
      out->regions.push_back(std::move(r));
    }
    regions_out_.publish(std::move(out));
  }

 private:
  const DigitModel& load() {
    const std::string& path = model_path_.get();
    if (path.empty()) throw std::invalid_argument("no model: set 'model' to a file apex_train_mlp wrote");
    bool fresh = false;
    const DigitModel& model = model_.get(
        path, [](const std::string& p) { return DigitModel::load(p); }, fresh);
    if (fresh)
      log(apex::LogLevel::Info, "loaded the model '" + path + "': " + std::to_string(model.classes().size()) +
                                    " classes, validation accuracy " + std::to_string(model.validationAccuracy()));
    return model;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Regions> regions_out_{this, kLabelled};
  apex::Param<std::string> model_path_{this, kModel};
  apex::Param<double> min_confidence_{this, kMinConfidence};
  apex::Param<int> reject_label_{this, kRejectLabel};
  ModelFile<DigitModel> model_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DigitClassifier, "apex_nodes/DigitClassifier");
