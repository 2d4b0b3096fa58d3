// Watershed: grows labelled seed regions over a colour image until they meet (cv::watershed). The
// markers are a label image: a positive label per seed, 0 where the region is not known; each
// unknown pixel gets a seed's label, and -1 marks the boundaries between regions. Touching objects
// that a threshold joins (coins, candies) come apart, seeded from ConnectedComponents' labels.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class Watershed : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit, 3 channels (bgr8 or rgb8)"};
  static inline const apex::InputPort<Image> kMarkersIn{
      "markers", "32SC1 of the image's size: a positive label per seed region, 0 where the region is not known"};
  static inline const apex::OutputPort<Image> kMarkersOut{
      "markers", "32SC1: each pixel the label of its region, -1 on the boundaries between regions"};
  static apex::Manifest manifest() {
    return apex::Manifest("Grows labelled seeds over an image until they meet (cv::watershed): regions, -1 on their boundaries")
        .inCategory("segmentation")
        .input(kImage)
        .input(kMarkersIn)
        .output(kMarkersOut);
  }
  void process() override {
    const Image& in = *image_.get();
    const Image& markers = *markers_in_.get();
    requireImage(in, "3");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit pixels");
    if (markers.mat.type() != CV_32SC1)
      throw std::invalid_argument("the markers are " + imageWords(markers) +
                                  "; they need a 32SC1 label image (e.g. ConnectedComponents' labels)");
    if (markers.mat.size() != in.mat.size())
      throw std::invalid_argument("the image is " + imageWords(in) + ", the markers " + imageWords(markers) +
                                  ": they need the same size");
    auto out = buffer_.next(in);
    markers.mat.copyTo(out->mat);  // cv::watershed writes into its markers: the input stays as it came
    out->encoding = "32SC1";
    cv::watershed(in.mat, out->mat);
    markers_out_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<Image> markers_in_{this, kMarkersIn};
  apex::Output<Image> markers_out_{this, kMarkersOut};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Watershed, "apex_nodes/Watershed");
