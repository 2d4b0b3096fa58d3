// Keypoints (ORB, AKAZE, BRISK, SIFT, FAST, GFTT, with descriptors where the method has them) and DrawKeypoints.
#include <opencv2/features2d.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/features.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class KeypointDetector : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour (detected on its gray)"};
  static inline const apex::OutputPort<Keypoints> kKeypoints{"keypoints", "with descriptors, except fast and gftt"};
  enum class Method { kOrb, kAkaze, kBrisk, kSift, kFast, kGftt };
  static inline const apex::ChoiceDecl<Method> kMethod =
      param::choice<Method>("method", {{"orb", Method::kOrb},
                                       {"akaze", Method::kAkaze},
                                       {"brisk", Method::kBrisk},
                                       {"sift", Method::kSift},
                                       {"fast", Method::kFast},
                                       {"gftt", Method::kGftt}})
          .describe("orb, akaze, brisk: binary descriptors (Hamming); sift: float (L2); fast, gftt: keypoints only");
  static inline const apex::ParamDecl<int> kMaxFeatures =
      param::integer("max_features")
          .range(0, 100000)
          .step(1)
          .init(500)
          .describe("orb, sift: nfeatures; gftt: maxCorners (sift, gftt: 0 for no limit); akaze, brisk, fast keep all");
  static inline const apex::ParamDecl<double> kThreshold =
      param::number("threshold")
          .range(0.0, 255.0)
          .step(0.001)
          .describe(
              "0: OpenCV's default. fast: threshold (10), orb: fastThreshold (20), brisk: thresh (30), in gray "
              "levels; akaze: threshold (0.001); sift: contrastThreshold (0.04); gftt: qualityLevel (0.01)");
  static apex::Manifest manifest() {
    return apex::Manifest("Detects keypoints and computes their descriptors (features2d)")
        .inCategory("features")
        .input(kImage)
        .output(kKeypoints)
        .param(kMethod)
        .param(kMaxFeatures)
        .param(kThreshold);
  }
  void parameterChanged(const std::string&) override { detector_.release(); }

  void process() override {
    const Image& in = *image_.get();
    const cv::Mat gray = gray8(in, gray_);
    if (!detector_) detector_ = create();
    auto out = std::make_shared<Keypoints>();
    out->header = in.header;
    out->image_size = in.mat.size();
    out->method = method_.text();
    if (method_.get() == Method::kFast || method_.get() == Method::kGftt) {
      detector_->detect(gray, out->keypoints);
      out->norm_type = 0;  // no descriptors to match
    } else {
      detector_->detectAndCompute(gray, cv::noArray(), out->keypoints, out->descriptors);  // a new matrix each frame
      out->norm_type = detector_->defaultNorm();
    }
    keypoints_.publish(out);
  }

 private:
  /** The detector for the parameters, as OpenCV's create() with its defaults but for these two. */
  cv::Ptr<cv::Feature2D> create() const {
    const int n = max_features_.get();
    const double t = threshold_.get();
    auto or_default = [t](double d) { return t > 0 ? t : d; };
    switch (method_.get()) {
      case Method::kOrb:
        if (n < 1) throw std::invalid_argument("orb needs max_features of at least 1 (its nfeatures), got 0");
        return cv::ORB::create(n, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, cvRound(or_default(20)));
      case Method::kAkaze:
        return cv::AKAZE::create(cv::AKAZE::DESCRIPTOR_MLDB, 0, 3, static_cast<float>(or_default(0.001)));
      case Method::kBrisk:
        return cv::BRISK::create(cvRound(or_default(30)));
      case Method::kSift:
        return cv::SIFT::create(n, 3, or_default(0.04));
      case Method::kFast:
        return cv::FastFeatureDetector::create(cvRound(or_default(10)));
      case Method::kGftt:
        break;  // below: after the switch, so that every path returns
    }
    if (t > 1) throw std::invalid_argument("gftt's threshold is its qualityLevel, 0..1: got " + std::to_string(t));
    return cv::GFTTDetector::create(n, or_default(0.01));
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<Keypoints> keypoints_{this, kKeypoints};
  apex::Choice<Method> method_{this, kMethod};
  apex::Param<int> max_features_{this, kMaxFeatures};
  apex::Param<double> threshold_{this, kThreshold};
  cv::Ptr<cv::Feature2D> detector_;  // rebuilt after a parameter change
  cv::Mat gray_;  // a colour frame's gray, reused
};

class DrawKeypoints : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit, the keypoints' image"};
  static inline const apex::InputPort<Keypoints> kKeypoints{"keypoints"};
  static inline const apex::OutputPort<Image> kDrawn{"image", "bgr8 with the keypoints drawn"};
  static inline const apex::ParamDecl<apex::Color> kColor = param::color("color").init({0, 255, 0});
  static inline const apex::ParamDecl<bool> kRich =
      param::flag("rich_keypoints").describe("circles of the keypoints' size with their orientation (DRAW_RICH_KEYPOINTS)");
  static apex::Manifest manifest() {
    return apex::Manifest("Draws keypoints over their image (cv::drawKeypoints)")
        .inCategory("features")
        .input(kImage)
        .input(kKeypoints)
        .output(kDrawn)
        .param(kColor)
        .param(kRich);
  }
  void process() override {
    const Image& in = *image_in_.get();
    const Keypoints& k = *keypoints_.get();
    requireImage(in, "134");
    if (k.image_size != in.mat.size())
      throw std::invalid_argument("the keypoints are of a " + std::to_string(k.image_size.width) + "x" +
                                  std::to_string(k.image_size.height) + " image, the image is " + std::to_string(in.mat.cols) +
                                  "x" + std::to_string(in.mat.rows));
    auto out = buffer_.next(in);
    bgr8(in, out->mat);
    const apex::Color& c = color_.get();
    auto flags = cv::DrawMatchesFlags::DRAW_OVER_OUTIMG;
    if (rich_.get()) flags = flags | cv::DrawMatchesFlags::DRAW_RICH_KEYPOINTS;
    cv::drawKeypoints(out->mat, k.keypoints, out->mat, cv::Scalar(c.b, c.g, c.r), flags);
    out->encoding = "bgr8";
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, kImage};
  apex::Input<Keypoints> keypoints_{this, kKeypoints};
  apex::Output<Image> image_out_{this, kDrawn};
  apex::Param<apex::Color> color_{this, kColor};
  apex::Param<bool> rich_{this, kRich};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::KeypointDetector, "apex_nodes/Keypoints");
APEX_REGISTER_NODE(apex_nodes::DrawKeypoints, "apex_nodes/DrawKeypoints");
