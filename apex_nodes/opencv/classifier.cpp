// Classifier: labels each region of some Features (FeatureExtract's) with a trained cv::ml model
// of any type OpenCV saves (apex_train writes them; LearnedModel in apex_nodes/learning.hpp says
// how each type's confidence is found). The model is read when first needed, and again when the
// parameter is set or the file changes; a missing or damaged file, or features of another length
// than the model takes, is an error on the node (the regions still go out, unlabelled).
// DigitClassifier is the preset for the number signs (its own features and MLP file).

#include <memory>

#include "apex/core/registry.hpp"
#include "apex_nodes/learning.hpp"
#include "apex_nodes/model_file.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Classifier : public apex::Node {
 public:
  static inline const apex::InputPort<Features> kFeatures{"features", "FeatureExtract's: a row per region, with the regions"};
  static inline const apex::OutputPort<Regions> kLabelled{
      "regions", "the features' regions with label (-1 if rejected or outside the image) and confidence"};
  static inline const apex::ParamDecl<std::string> kModel = param::path("model").describe(
      "a cv::ml model file (apex_train's, or any OpenCV saved: svm, rtrees, knn, ann_mlp, boost, dtrees, lr, nbayes)");
  static inline const apex::ParamDecl<double> kMinConfidence =
      param::number("min_confidence")
          .range(0.0, 1.0)
          .step(0.01)
          .init(0.0)
          .describe(
              "a region whose label is less certain gets label -1 (svm: 1 unless two classes; rtrees: the trees' vote share; "
              "knn: the neighbours' share)");
  static apex::Manifest manifest() {
    return apex::Manifest("Labels each region by its features with a trained OpenCV ml model (SVM, random trees, k-NN, MLP...)")
        .inCategory("learning")
        .input(kFeatures)
        .output(kLabelled)
        .param(kModel)
        .param(kMinConfidence);
  }
  void parameterChanged(const std::string& name) override {
    if (name == kModel.name()) model_.forget();
  }
  void process() override {
    const Features& in = *features_.get();
    if (!in.regions) throw std::invalid_argument("the features carry no regions to label");
    const std::size_t n = in.regions->regions.size();
    if (static_cast<std::size_t>(in.rows.rows) != n || (n && (in.rows.type() != CV_32F || in.rows.cols != in.length)))
      throw std::invalid_argument("the features have " + std::to_string(in.rows.rows) + " rows of " +
                                  std::to_string(in.rows.cols) + " (not float, or not their length " + std::to_string(in.length) +
                                  ") for " + std::to_string(n) + " regions");
    const LearnedModel* model = nullptr;
    try {
      model = &load();
      check(*model, in);
    } catch (const std::invalid_argument& e) {
      reportError(e.what());
      regions_out_.publish(in.regions);  // the pipeline goes on, unlabelled
      return;
    }
    auto out = std::make_shared<Regions>(*in.regions);
    const std::vector<Prediction> predicted = model->predict(in.rows);
    for (std::size_t i = 0; i < n; ++i) {
      Region& r = out->regions[i];
      if (i < in.valid.size() && !in.valid[i]) {
        r.label = -1, r.confidence = 0;
        continue;
      }
      r.confidence = predicted[i].confidence;
      r.label = predicted[i].confidence >= min_confidence_.get() ? predicted[i].label : -1;
    }
    regions_out_.publish(std::move(out));
  }

 private:
  /** The features are what the model takes: their length, and their settings if it recorded its own. */
  void check(const LearnedModel& model, const Features& in) const {
    const std::string& path = model_path_.get();
    if (in.length != model.varCount())
      throw std::invalid_argument("the model '" + path + "' (" + model.kind() + ") takes " + std::to_string(model.varCount()) +
                                  " features per region, but these have " + std::to_string(in.length) +
                                  (in.settings.empty() ? "" : " (" + in.settings + ")"));
    if (!model.features().empty() && !in.settings.empty() && model.features() != in.settings)
      throw std::invalid_argument("the model '" + path + "' was trained on the features '" + model.features() + "', these are '" +
                                  in.settings + "'");
  }
  const LearnedModel& load() {
    const std::string& path = model_path_.get();
    if (path.empty()) throw std::invalid_argument("no model: set 'model' to a model file (apex_train writes them)");
    bool fresh = false;
    const LearnedModel& model = model_.get(
        path, [](const std::string& p) { return LearnedModel::load(p); }, fresh);
    if (fresh)
      log(apex::LogLevel::Info, "loaded the model '" + path + "': " + model.kind() + ", " + std::to_string(model.varCount()) +
                                    " features per region" + (model.features().empty() ? "" : " (" + model.features() + ")"));
    return model;
  }

  apex::Input<Features> features_{this, kFeatures};
  apex::Output<Regions> regions_out_{this, kLabelled};
  apex::Param<std::string> model_path_{this, kModel};
  apex::Param<double> min_confidence_{this, kMinConfidence};
  ModelFile<LearnedModel> model_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Classifier, "apex_nodes/Classifier");
