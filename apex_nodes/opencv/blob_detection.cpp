// BlobDetection: connected components of a binary image, filtered by area.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class BlobDetection : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "binary, single-channel 8-bit"};
  static inline const apex::OutputPort<Regions> kRegions{"regions"};
  static inline const apex::OutputPort<int> kCount{"count", "how many regions passed the area filter"};
  static inline const apex::ParamDecl<int> kMinArea =
      param::integer("min_area").range(0, 10000000).step(1).init(50).describe("pixels; smaller regions are dropped");
  static inline const apex::ParamDecl<int> kMaxArea =
      param::integer("max_area").range(0, 10000000).step(1).init(1000000).describe("pixels; larger regions are dropped");
  static inline const apex::ChoiceDecl<int> kConnectivity = param::choice<int>("connectivity", {{"4", 4}, {"8", 8}}).init("8");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds connected regions of non-zero pixels (bounding box, area, centroid)")
        .inCategory("detection")
        .input(kImage)
        .output(kRegions)
        .output(kCount)
        .param(kMinArea)
        .param(kMaxArea)
        .param(kConnectivity);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "1");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit binary image ('" + in.encoding + "')");
    const int n =
        cv::connectedComponentsWithStats(in.mat, labels_, stats_, centroids_, connectivity_.get(), CV_32S, cv::CCL_DEFAULT);
    auto out = regions_buf_.next();  // the last one when nobody holds it: its vector keeps its memory
    out->header = in.header;
    out->image_size = in.mat.size();
    out->regions.clear();
    const int lo = min_area_.get(), hi = max_area_.get();
    for (int i = 1; i < n; ++i) {  // 0 is the background
      const int area = stats_.at<int>(i, cv::CC_STAT_AREA);
      if (area < lo || area > hi) continue;
      Region r;
      r.box = cv::Rect(stats_.at<int>(i, cv::CC_STAT_LEFT), stats_.at<int>(i, cv::CC_STAT_TOP),
                       stats_.at<int>(i, cv::CC_STAT_WIDTH), stats_.at<int>(i, cv::CC_STAT_HEIGHT));
      r.area = area;
      r.centroid = cv::Point2d(centroids_.at<double>(i, 0), centroids_.at<double>(i, 1));
      out->regions.push_back(r);
    }
    count_.publish(static_cast<int>(out->regions.size()));
    regions_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Output<int> count_{this, kCount};
  apex::Param<int> min_area_{this, kMinArea};
  apex::Param<int> max_area_{this, kMaxArea};
  apex::Choice<int> connectivity_{this, kConnectivity};
  cv::Mat labels_, stats_, centroids_;  // reused between frames
  Reused<Regions> regions_buf_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::BlobDetection, "apex_nodes/BlobDetection");
