// DrawRegions: the regions' boxes over the image, for visual feedback.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class DrawRegions : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Draws regions' bounding boxes over an image")
        .input<Image>("image")
        .input<Regions>("regions")
        .output<Image>("image", "bgr8 with the boxes drawn")
        .param(apex::param::color("color", 0, 255, 0))
        .param(apex::param::range("thickness", 1, 20, 1, 2));
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
    for (const auto& r : regions.regions)
      cv::rectangle(out->mat, r.box, cv::Scalar(c.b, c.g, c.r), thickness_.get());
    out->encoding = "bgr8";
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Input<Regions> regions_{this, "regions"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<apex::Color> color_{this, "color"};
  apex::Param<int> thickness_{this, "thickness"};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DrawRegions, "apex_nodes/DrawRegions");
