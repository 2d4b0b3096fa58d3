// BackgroundSubtraction: a foreground mask from a background model learnt over the frames (MOG2 or KNN).
#include <opencv2/video/background_segm.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class BackgroundSubtraction : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour, one frame of a fixed camera"};
  static inline const apex::OutputPort<Image> kMask{"mask", "mono8: 255 foreground, 127 shadow, 0 background"};
  enum class Method { kMog2, kKnn };
  static inline const apex::ChoiceDecl<Method> kMethod =
      param::choice<Method>("method", {{"mog2", Method::kMog2}, {"knn", Method::kKnn}});
  static inline const apex::ParamDecl<int> kHistory =
      param::integer("history").range(1, 100000).step(1).init(500).describe("frames the model remembers");
  static inline const apex::ParamDecl<double> kVarThreshold =
      param::number("var_threshold")
          .range(0.0, 1000.0)
          .step(0.5)
          .init(16.0)
          .describe("mog2: squared Mahalanobis distance under which a pixel is background");
  static inline const apex::ParamDecl<double> kDist2Threshold =
      param::number("dist2_threshold")
          .range(0.0, 100000.0)
          .step(1.0)
          .init(400.0)
          .describe("knn: squared distance under which a pixel is near a sample of the background");
  static inline const apex::ParamDecl<bool> kShadows =
      param::flag("detect_shadows").init(true).describe("mark shadows 127 in the mask (a little slower)");
  static inline const apex::ParamDecl<double> kLearningRate =
      param::number("learning_rate")
          .range(-1.0, 1.0)
          .step(0.001)
          .init(-1.0)
          .describe("-1: automatic (from history); 0: the model stays as it is; 1: relearnt from this frame alone");
  static apex::Manifest manifest() {
    return apex::Manifest("Foreground mask of each frame against a background model learnt over the frames (MOG2 or KNN)")
        .inCategory("motion")
        .keepsState("its background model: every frame it sees teaches it, a re-run of the held frame too")
        .input(kImage)
        .output(kMask)
        .param(kMethod)
        .param(kHistory)
        .param(kVarThreshold)
        .param(kDist2Threshold)
        .param(kShadows)
        .param(kLearningRate)
        .slot("reset", &BackgroundSubtraction::reset, "forgets the model: the next frame starts a new one");
  }
  /** A change of the model's parameters starts a new model; the learning rate is read per frame. */
  void parameterChanged(const std::string& name) override {
    if (name != kLearningRate.name()) reset();
  }
  /** A new pass of a sequence starts a new model: each pass gives the same masks. */
  void endOfSequence() override {
    reset();
    endSequence();
  }
  void reset() { model_.release(); }

  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "13");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
    if (!model_) {
      if (method_.get() == Method::kMog2)
        model_ = cv::createBackgroundSubtractorMOG2(history_.get(), var_threshold_.get(), shadows_.get());
      else model_ = cv::createBackgroundSubtractorKNN(history_.get(), dist2_threshold_.get(), shadows_.get());
    }
    auto out = buffer_.next(in);
    model_->apply(in.mat, out->mat, learning_rate_.get());  // a new frame size starts the model again
    out->encoding = "mono8";
    mask_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Image> mask_{this, kMask};
  apex::Choice<Method> method_{this, kMethod};
  apex::Param<int> history_{this, kHistory};
  apex::Param<double> var_threshold_{this, kVarThreshold};
  apex::Param<double> dist2_threshold_{this, kDist2Threshold};
  apex::Param<bool> shadows_{this, kShadows};
  apex::Param<double> learning_rate_{this, kLearningRate};
  cv::Ptr<cv::BackgroundSubtractor> model_;  // made by the first frame after a reset
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::BackgroundSubtraction, "apex_nodes/BackgroundSubtraction");
