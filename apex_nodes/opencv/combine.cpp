// Two images into one: ImageCombine (arithmetic, bitwise, min/max, weighted sum), ApplyMask.
#include <opencv2/core.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ImageCombine : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kA{"a", "the first image"};
  static inline const apex::InputPort<Image> kB{"b", "the second: of a's size and type"};
  static inline const apex::OutputPort<Image> kOut{"image", "a's size, type, encoding and header"};
  /** One of the per-pixel operations; nullptr: weighted (it takes parameters). */
  using Per = void (*)(const cv::Mat& a, const cv::Mat& b, cv::Mat& out);
  static inline const apex::ChoiceDecl<Per> kOperation =
      param::choice<Per>("operation",
                         {{"add", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::add(a, b, m); }},
                          {"subtract", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::subtract(a, b, m); }},
                          {"absdiff", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::absdiff(a, b, m); }},
                          {"and", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::bitwise_and(a, b, m); }},
                          {"or", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::bitwise_or(a, b, m); }},
                          {"xor", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::bitwise_xor(a, b, m); }},
                          {"min", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::min(a, b, m); }},
                          {"max", [](const cv::Mat& a, const cv::Mat& b, cv::Mat& m) { cv::max(a, b, m); }},
                          {"weighted", nullptr}})
          .describe(
              "per pixel: a + b, a - b, |a - b|, bitwise a & b, a | b, a ^ b, min, max; weighted: alpha a + beta b + gamma "
              "(sums saturate)");
  static inline const apex::ParamDecl<double> kAlpha =
      param::number("alpha").range(-10.0, 10.0).step(0.01).init(0.5).describe("weighted: the factor on a");
  static inline const apex::ParamDecl<double> kBeta =
      param::number("beta").range(-10.0, 10.0).step(0.01).init(0.5).describe("weighted: the factor on b");
  static inline const apex::ParamDecl<double> kGamma =
      param::number("gamma").range(-255.0, 255.0).step(1.0).init(0.0).describe("weighted: added to the sum");
  static apex::Manifest manifest() {
    return apex::Manifest("Combines two images of the same size and type pixel by pixel")
        .inCategory("image filters")
        .input(kA)
        .input(kB)
        .output(kOut)
        .param(kOperation)
        .param(kAlpha)
        .param(kBeta)
        .param(kGamma);
  }
  void process() override {
    const Image& a = *a_.get();
    const Image& b = *b_.get();
    if (a.mat.empty() || b.mat.empty())
      throw std::invalid_argument(std::string("received an empty image on ") + (a.mat.empty() ? "a" : "b"));
    const std::string& op = operation_.text();
    if (a.mat.size() != b.mat.size() || a.mat.type() != b.mat.type())
      throw std::invalid_argument("a is " + imageWords(a) + ", b " + imageWords(b) + ": " + op +
                                  " needs two images of the same size and type");
    auto out = buffer_.next(a);
    cv::Mat& m = out->mat;
    if (const Per per = operation_.get()) per(a.mat, b.mat, m);
    else cv::addWeighted(a.mat, alpha_.get(), b.mat, beta_.get(), gamma_.get(), m);
    out->encoding = a.encoding;
    out_.publish(out);
  }

 private:
  apex::Input<Image> a_{this, kA};
  apex::Input<Image> b_{this, kB};
  apex::Output<Image> out_{this, kOut};
  apex::Choice<Per> operation_{this, kOperation};
  apex::Param<double> alpha_{this, kAlpha};
  apex::Param<double> beta_{this, kBeta};
  apex::Param<double> gamma_{this, kGamma};
  OutputBuffer buffer_;
};

class ApplyMask : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "any image"};
  static inline const apex::InputPort<Image> kMask{"mask", "mono8 of the image's size: non-zero where the image is kept"};
  static inline const apex::OutputPort<Image> kOut{"image", "the image where the mask is non-zero, else 0"};
  static apex::Manifest manifest() {
    return apex::Manifest("Keeps an image's pixels where a mask is non-zero and blacks out the rest")
        .inCategory("image filters")
        .input(kImage)
        .input(kMask)
        .output(kOut);
  }
  void process() override {
    const Image& in = *image_.get();
    const Image& mask = *mask_.get();
    requireImage(in, "1234");
    if (mask.mat.empty()) throw std::invalid_argument("received an empty mask");
    if (mask.mat.type() != CV_8UC1)
      throw std::invalid_argument("the mask is " + imageWords(mask) + "; it needs a single-channel 8-bit image (mono8)");
    if (mask.mat.size() != in.mat.size())
      throw std::invalid_argument("the image is " + imageWords(in) + ", the mask " + imageWords(mask) +
                                  ": they need the same size");
    auto out = buffer_.next(in);
    out->mat.create(in.mat.size(), in.mat.type());
    out->mat.setTo(cv::Scalar::all(0));  // a reused buffer holds the last frame
    in.mat.copyTo(out->mat, mask.mat);
    out->encoding = in.encoding;
    out_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<Image> mask_{this, kMask};
  apex::Output<Image> out_{this, kOut};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ImageCombine, "apex_nodes/ImageCombine");
APEX_REGISTER_NODE(apex_nodes::ApplyMask, "apex_nodes/ApplyMask");
