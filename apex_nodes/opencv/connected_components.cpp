// ConnectedComponents: labels the connected regions of a binary image
// (cv::connectedComponentsWithStats): a label image (0 the background, 1..count the components),
// their count, and each one's box, area and centroid as regions. The labels seed Watershed or mask
// one object; BlobDetection gives the regions alone, filtered by area.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ConnectedComponents : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "binary, single-channel 8-bit: non-zero pixels are the foreground"};
  static inline const apex::OutputPort<Image> kLabels{
      "labels", "32SC1 of the image's size: 0 on the background, 1..count on the components"};
  static inline const apex::OutputPort<int> kCount{"count", "how many components (the background not counted)"};
  static inline const apex::OutputPort<Regions> kRegions{
      "regions", "one per component in the order of their labels (label i: regions[i - 1]): box, area in pixels, centroid"};
  static inline const apex::ChoiceDecl<int> kConnectivity = param::choice<int>(
      "connectivity", {{"8", 8, "pixels touching at a corner are connected"}, {"4", 4, "only pixels sharing a side"}});
  static inline const apex::ChoiceDecl<int> kCclType =
      param::choice<int>("ccltype", {{"default", cv::CCL_DEFAULT, "OpenCV's, Spaghetti"},
                                     {"sauf", cv::CCL_SAUF, "SAUF (Wu et al.)"},
                                     {"bbdt", cv::CCL_BBDT, "BBDT (Grana et al.) for 8-connectivity, SAUF for 4"},
                                     {"spaghetti", cv::CCL_SPAGHETTI, "Spaghetti (Bolelli et al.)"}})
          .describe("the labelling algorithm");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Labels the connected regions of a binary image (cv::connectedComponentsWithStats): labels, count and each "
               "one's box, area and centroid")
        .inCategory("segmentation")
        .input(kImage)
        .output(kLabels)
        .output(kCount)
        .output(kRegions)
        .param(kConnectivity)
        .param(kCclType);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "1");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit binary image, got " + imageWords(in));
    auto labels = buffer_.next(in);
    labels->encoding = "32SC1";
    const int n =
        cv::connectedComponentsWithStats(in.mat, labels->mat, stats_, centroids_, connectivity_.get(), CV_32S, ccltype_.get());
    auto regions = regions_buffer_.next();  // its vector keeps its memory
    regions->header = in.header;
    regions->image_size = in.mat.size();
    regions->regions.clear();
    for (int i = 1; i < n; ++i) {  // 0 is the background
      Region r;
      r.box = cv::Rect(stats_.at<int>(i, cv::CC_STAT_LEFT), stats_.at<int>(i, cv::CC_STAT_TOP),
                       stats_.at<int>(i, cv::CC_STAT_WIDTH), stats_.at<int>(i, cv::CC_STAT_HEIGHT));
      r.area = stats_.at<int>(i, cv::CC_STAT_AREA);
      r.centroid = cv::Point2d(centroids_.at<double>(i, 0), centroids_.at<double>(i, 1));
      regions->regions.push_back(r);
    }
    labels_.publish(labels);
    count_.publish(n - 1);
    regions_.publish(regions);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Image> labels_{this, kLabels};
  apex::Output<int> count_{this, kCount};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Choice<int> connectivity_{this, kConnectivity};
  apex::Choice<int> ccltype_{this, kCclType};
  cv::Mat stats_, centroids_;  // reused between frames
  OutputBuffer buffer_;
  Reused<Regions> regions_buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ConnectedComponents, "apex_nodes/ConnectedComponents");
