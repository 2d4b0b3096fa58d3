// ChessboardCorners: a calibration chessboard's inner corners (cv::findChessboardCorners), refined to subpixels.
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/shapes.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ChessboardCorners : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour"};
  static inline const apex::OutputPort<Corners> kCorners{"corners", "found = false (and no corners) when the board is not seen"};
  static inline const apex::ParamDecl<int> kColumns =
      param::integer("pattern_columns").range(2, 100).step(1).init(9).describe("inner corners per row");
  static inline const apex::ParamDecl<int> kRows =
      param::integer("pattern_rows").range(2, 100).step(1).init(6).describe("inner corners per column");
  static inline const apex::ParamDecl<bool> kRefine =
      param::flag("refine").init(true).describe("refine the corners to subpixels (cv::cornerSubPix: 30 iterations or 0.001 px)");
  static inline const apex::ParamDecl<int> kRefineWindow =
      param::integer("refine_window").range(1, 50).step(1).init(11).describe("cornerSubPix's half window, pixels");
  static inline const apex::ParamDecl<bool> kAdaptive =
      param::flag("adaptive_thresh").init(true).describe("threshold adaptively (not by the mean brightness)");
  static inline const apex::ParamDecl<bool> kNormalize =
      param::flag("normalize_image").init(true).describe("equalise the histogram before thresholding");
  static inline const apex::ParamDecl<bool> kFastCheck =
      param::flag("fast_check").describe("a quick look for a board first: fast on frames without one");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds a chessboard's inner corners, for camera calibration (cv::findChessboardCorners)")
        .inCategory("detection")
        .input(kImage)
        .output(kCorners)
        .param(kColumns)
        .param(kRows)
        .param(kRefine)
        .param(kRefineWindow)
        .param(kAdaptive)
        .param(kNormalize)
        .param(kFastCheck);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "134");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image, got '" + in.encoding + "'");
    // Gray, once, for both calls: findChessboardCorners makes any colour image gray itself with
    // cv::cvtColor's BGR2GRAY, which is what a bgr8 image gets here; rgb8 and rgba8 by their order.
    const bool rgb = in.encoding.rfind("rgb", 0) == 0;
    if (in.mat.channels() == 4) cv::cvtColor(in.mat, gray_, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
    else if (in.mat.channels() == 3) cv::cvtColor(in.mat, gray_, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
    const cv::Mat& gray = in.mat.channels() == 1 ? in.mat : gray_;  // read only (OpenCV copies what it changes)

    auto out = std::make_shared<Corners>();
    out->header = in.header;
    out->image_size = in.mat.size();
    out->pattern_size = cv::Size(columns_.get(), rows_.get());
    const int flags = (adaptive_.get() ? cv::CALIB_CB_ADAPTIVE_THRESH : 0) |
                      (normalize_.get() ? cv::CALIB_CB_NORMALIZE_IMAGE : 0) | (fast_check_.get() ? cv::CALIB_CB_FAST_CHECK : 0);
    out->found = cv::findChessboardCorners(gray, out->pattern_size, out->corners, flags);
    if (!out->found) {
      out->corners.clear();  // what it had of the board: not a result
    } else if (refine_.get()) {
      cv::cornerSubPix(gray, out->corners, cv::Size(refine_window_.get(), refine_window_.get()), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
    }
    corners_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Corners> corners_{this, kCorners};
  apex::Param<int> columns_{this, kColumns};
  apex::Param<int> rows_{this, kRows};
  apex::Param<bool> refine_{this, kRefine};
  apex::Param<int> refine_window_{this, kRefineWindow};
  apex::Param<bool> adaptive_{this, kAdaptive};
  apex::Param<bool> normalize_{this, kNormalize};
  apex::Param<bool> fast_check_{this, kFastCheck};
  cv::Mat gray_;  // a colour frame's gray, reused
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ChessboardCorners, "apex_nodes/ChessboardCorners");
