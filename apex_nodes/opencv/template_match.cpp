// TemplateMatch: where a template image appears in a frame (cv::matchTemplate), best matches first.
#include <algorithm>
#include <cfloat>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class TemplateMatch : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit or 32-bit float, 1 to 4 channels"};
  static inline const apex::InputPort<Image> kTemplate{"template", "the same depth and channels, not larger than the image"};
  static inline const apex::OutputPort<Regions> kRegions{
      "regions", "the template's box at each match (not overlapping), label 0, confidence the normalised score"};
  static inline const apex::OutputPort<Image> kScores{"scores", "32FC1: cv::matchTemplate's result, one per template position"};
  static inline const apex::ChoiceDecl<int> kMethod =
      param::choice<int>("method", {{"sqdiff", cv::TM_SQDIFF},
                                    {"sqdiff_normed", cv::TM_SQDIFF_NORMED},
                                    {"ccorr", cv::TM_CCORR},
                                    {"ccorr_normed", cv::TM_CCORR_NORMED},
                                    {"ccoeff", cv::TM_CCOEFF},
                                    {"ccoeff_normed", cv::TM_CCOEFF_NORMED}})
          .init("ccoeff_normed")
          .describe("*_normed: confidence is the score (1 - it for sqdiff_normed); else the score scaled to 0..1 over the frame");
  static inline const apex::ParamDecl<double> kThreshold =
      param::number("threshold").range(0.0, 1.0).step(0.01).init(0.8).describe("the confidence a match needs");
  static inline const apex::ParamDecl<int> kMaxMatches =
      param::integer("max_matches").range(1, 1000).step(1).init(1).describe("the best ones, not overlapping each other");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds a template image in a frame (cv::matchTemplate): its best, non-overlapping matches")
        .inCategory("detection")
        .input(kImage)
        .input(kTemplate)
        .output(kRegions)
        .output(kScores)
        .param(kMethod)
        .param(kThreshold)
        .param(kMaxMatches);
  }
  void process() override {
    const Image& in = *image_.get();
    const Image& templ = *template_.get();
    requireImage(in, "1234");
    if (templ.mat.empty()) throw std::invalid_argument("received an empty template");
    if (in.mat.depth() != CV_8U && in.mat.depth() != CV_32F)
      throw std::invalid_argument("needs an 8-bit or 32-bit float image, got '" + in.encoding + "'");
    if (templ.mat.type() != in.mat.type())
      throw std::invalid_argument("the template ('" + templ.encoding + "', " + std::to_string(templ.mat.channels()) +
                                  " channels) is not of the image's type ('" + in.encoding + "', " +
                                  std::to_string(in.mat.channels()) + " channels)");
    if (templ.mat.cols > in.mat.cols || templ.mat.rows > in.mat.rows)
      throw std::invalid_argument("the template (" + std::to_string(templ.mat.cols) + "x" + std::to_string(templ.mat.rows) +
                                  ") is larger than the image (" + std::to_string(in.mat.cols) + "x" +
                                  std::to_string(in.mat.rows) + ")");
    const bool swapped =
        (in.encoding == "rgb8" && templ.encoding == "bgr8") || (in.encoding == "bgr8" && templ.encoding == "rgb8");
    if (swapped) cv::cvtColor(templ.mat, swapped_, cv::COLOR_RGB2BGR);  // the image's channel order, in a copy of its own
    const cv::Mat& t = swapped ? swapped_ : templ.mat;  // read only: the message's pixels are never written

    const int method = method_.get();
    auto scores = buffer_.next(in);
    scores->encoding = "32FC1";
    cv::matchTemplate(in.mat, t, scores->mat, method);

    auto out = std::make_shared<Regions>();
    out->header = in.header;
    out->image_size = in.mat.size();
    cv::Mat& conf = confidence(scores->mat, method);
    const cv::Rect all(0, 0, conf.cols, conf.rows);
    for (int k = 0; k < max_matches_.get(); ++k) {
      double best = 0;
      cv::Point at;
      cv::minMaxLoc(conf, nullptr, &best, nullptr, &at);
      if (best < threshold_.get()) break;
      Region r;
      r.box = cv::Rect(at, t.size());
      r.area = r.box.area();
      r.centroid = cv::Point2d(at.x + (t.cols - 1) / 2.0, at.y + (t.rows - 1) / 2.0);
      r.label = 0;  // the template
      r.confidence = std::min(1.0, best);
      out->regions.push_back(r);
      // No later match overlaps this one: every position whose box would is out.
      conf(cv::Rect(at.x - t.cols + 1, at.y - t.rows + 1, 2 * t.cols - 1, 2 * t.rows - 1) & all).setTo(-FLT_MAX);
    }
    regions_.publish(std::move(out));
    scores_.publish(scores);
  }

 private:
  /** The scores as confidences in conf_ (reused), higher is better, 0..1 where the method allows. */
  cv::Mat& confidence(const cv::Mat& scores, int method) {
    cv::Mat& conf = conf_;
    if (method == cv::TM_SQDIFF_NORMED) {
      cv::subtract(cv::Scalar::all(1.0), scores, conf);
    } else if (method == cv::TM_CCORR_NORMED || method == cv::TM_CCOEFF_NORMED) {
      scores.copyTo(conf);
    } else {  // unbounded scores: scaled to 0..1 over this frame
      double lo = 0, hi = 0;
      cv::minMaxLoc(scores, &lo, &hi);
      if (!(hi > lo)) {  // every position alike
        conf.create(scores.size(), CV_32F);
        conf.setTo(cv::Scalar::all(1.0));
        return conf;
      }
      if (method == cv::TM_SQDIFF) scores.convertTo(conf, CV_32F, -1.0 / (hi - lo), hi / (hi - lo));
      else scores.convertTo(conf, CV_32F, 1.0 / (hi - lo), -lo / (hi - lo));
    }
    cv::patchNaNs(conf, -1.0);  // a flat patch under a normed method
    return conf;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Image> template_{this, kTemplate};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Output<Image> scores_{this, kScores};
  apex::Choice<int> method_{this, kMethod};
  apex::Param<double> threshold_{this, kThreshold};
  apex::Param<int> max_matches_{this, kMaxMatches};
  OutputBuffer buffer_;
  cv::Mat swapped_;  // the template in the image's channel order, when they differ; reused
  cv::Mat conf_;  // the confidences, marked off as matches are taken; reused, never sent
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TemplateMatch, "apex_nodes/TemplateMatch");
