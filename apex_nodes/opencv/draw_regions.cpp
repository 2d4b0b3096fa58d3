// DrawRegions: the regions' boxes over the image, for visual feedback.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class DrawRegions : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image"};
  static inline const apex::InputPort<Regions> kRegions{"regions"};
  static inline const apex::OutputPort<Image> kDrawn{"image", "bgr8 with the boxes drawn"};
  static inline const apex::ParamDecl<apex::Color> kColor = param::color("color").init({0, 255, 0});
  static inline const apex::ParamDecl<int> kThickness = param::integer("thickness").range(1, 20).step(1).init(2);
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Draws regions' bounding boxes over an image, with their labels if a classifier gave them (a tracker's ids as "
               "#id)")
        .inCategory("drawing")
        .input(kImage)
        .input(kRegions)
        .output(kDrawn)
        .param(kColor)
        .param(kThickness);
  }
  void process() override {
    const Image& in = *image_in_.get();
    const Regions& regions = *regions_.get();
    requireImage(in, "134");
    auto out = buffer_.next(in);
    if (in.mat.channels() == 1) cv::cvtColor(in.mat, out->mat, cv::COLOR_GRAY2BGR);
    else if (in.mat.channels() == 4) cv::cvtColor(in.mat, out->mat, cv::COLOR_BGRA2BGR);
    else if (in.encoding == "rgb8") cv::cvtColor(in.mat, out->mat, cv::COLOR_RGB2BGR);
    else in.mat.copyTo(out->mat);
    const apex::Color& c = color_.get();
    for (const auto& r : regions.regions) {
      cv::rectangle(out->mat, r.box, cv::Scalar(c.b, c.g, c.r), thickness_.get());
      drawLabel(out->mat, r, cv::Scalar(c.b, c.g, c.r));
    }
    out->encoding = "bgr8";
    image_out_.publish(out);
  }

 private:
  /** A classified region's label and confidence above its box ('?' if the classifier rejected it);
   *  a label without a confidence is an id (MultiObjectTracker's), drawn as #id. */
  static void drawLabel(cv::Mat& img, const Region& r, const cv::Scalar& colour) {
    if (r.label < 0 && r.confidence <= 0) return;  // not classified
    const std::string text = r.confidence <= 0 ? "#" + std::to_string(r.label)
                                               : (r.label >= 0 ? std::to_string(r.label) : std::string("?")) + " " +
                                                     std::to_string(cvRound(100 * r.confidence)) + "%";
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.6, 2, &baseline);
    const cv::Point at(r.box.x, r.box.y > size.height + 6 ? r.box.y - 6 : r.box.br().y + size.height + 4);
    cv::rectangle(img, cv::Rect(at.x, at.y - size.height - 2, size.width + 2, size.height + baseline + 2), cv::Scalar::all(0),
                  cv::FILLED);
    cv::putText(img, text, at + cv::Point(1, 0), cv::FONT_HERSHEY_SIMPLEX, 0.6, colour, 2, cv::LINE_AA);
  }

  apex::Input<Image> image_in_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Image> image_out_{this, kDrawn};
  apex::Param<apex::Color> color_{this, kColor};
  apex::Param<int> thickness_{this, kThickness};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DrawRegions, "apex_nodes/DrawRegions");
