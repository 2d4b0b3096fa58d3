// Optical flow from the previous frame to this one: OpticalFlowLK (sparse, tracked corners) and OpticalFlowFarneback (dense).
#include <opencv2/video/tracking.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/features.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
/** A frame's gray pixels, kept for the next frame. A colour frame's are converted into one of two
 *  scratch images, taking turns, so that converting a frame never writes the kept gray of the one
 *  before; a gray frame's are its own, and the frame is held with them, so that its sender cannot
 *  reuse them (OutputBuffer). */
class KeptGray {
 public:
  /** `frame` in gray (gray8): its own pixels, or a scratch image the kept gray is not in. */
  cv::Mat of(const Image& frame) { return gray8(frame, scratch_[next_]); }
  /** Keeps `gray`, of(frame)'s result, as the previous frame's. */
  void keep(const std::shared_ptr<const Image>& frame, const cv::Mat& gray) {
    gray_ = gray;
    if (gray.data == frame->mat.data) {
      frame_ = frame;
    } else {  // converted: scratch_[next_] is kept, the next frame is converted into the other
      frame_.reset();
      next_ ^= 1;
    }
  }
  const cv::Mat& get() const { return gray_; }
  void reset() {
    gray_.release();
    frame_.reset();
  }

 private:
  cv::Mat scratch_[2];
  int next_ = 0;  // the scratch image the next colour frame is converted into
  cv::Mat gray_;  // the last frame's gray (perhaps the frame's own pixels: shared, never written)
  std::shared_ptr<const Image> frame_;  // the last frame, if gray_ is its pixels
};
}  // namespace

class OpticalFlowLK : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour (tracked on its gray)"};
  static inline const apex::OutputPort<Tracks> kTracks{"tracks",
                                                       "points of the previous frame and where they went; none on the first"};
  static inline const apex::ParamDecl<int> kMaxCorners =
      param::integer("max_corners").range(1, 100000).step(1).init(200).describe("goodFeaturesToTrack: the most points to track");
  static inline const apex::ParamDecl<double> kQuality =
      param::number("quality_level")
          .range(0.001, 1.0)
          .step(0.001)
          .init(0.01)
          .describe("goodFeaturesToTrack: a corner's least response, as a fraction of the best's");
  static inline const apex::ParamDecl<double> kMinDistance = param::number("min_distance")
                                                                 .range(0.0, 1000.0)
                                                                 .step(1.0)
                                                                 .init(10.0)
                                                                 .describe("goodFeaturesToTrack: pixels between corners");
  enum class Redetect { kEveryFrame, kWhenHalfLost };
  static inline const apex::ChoiceDecl<Redetect> kRedetect =
      param::choice<Redetect>("redetect", {{"every_frame", Redetect::kEveryFrame, "corners of each previous frame"},
                                           {"when_half_lost", Redetect::kWhenHalfLost,
                                            "the points found again are tracked on, until fewer than half of the last "
                                            "detection remain"}});
  static inline const apex::ParamDecl<int> kWinSize =
      param::integer("win_size").range(3, 101).step(2).init(21).describe("calcOpticalFlowPyrLK: search window, pixels a side");
  static inline const apex::ParamDecl<int> kMaxLevel =
      param::integer("max_level").range(0, 10).step(1).init(3).describe("calcOpticalFlowPyrLK: pyramid levels above the image");
  static apex::Manifest manifest() {
    return apex::Manifest("Tracks corners from the previous frame to this one (goodFeaturesToTrack, calcOpticalFlowPyrLK)")
        .inCategory("motion")
        .keepsState("the previous frame: a re-run compares the held frame with itself")
        .input(kImage)
        .output(kTracks)
        .param(kMaxCorners)
        .param(kQuality)
        .param(kMinDistance)
        .param(kRedetect)
        .param(kWinSize)
        .param(kMaxLevel)
        .slot("reset", &OpticalFlowLK::reset, "forgets the previous frame: the next one starts again");
  }
  void parameterChanged(const std::string&) override { points_.clear(); }  // detected again with the new values
  void endOfSequence() override {
    reset();  // the next pass starts afresh, not from this pass's last frame
    endSequence();
  }
  void reset() {
    previous_.reset();
    points_.clear();
  }

  void process() override {
    const auto frame = image_.get();
    const Image& in = *frame;
    const cv::Mat gray = previous_.of(in);  // the input's own pixels if gray: never written
    auto out = std::make_shared<Tracks>();
    out->header = in.header;
    out->image_size = gray.size();
    if (previous_.get().size() != gray.size()) reset();  // the first frame, or one of another size
    if (!previous_.get().empty()) {
      if (redetect_.get() == Redetect::kEveryFrame || points_.empty() || 2 * points_.size() < detected_) {
        cv::goodFeaturesToTrack(previous_.get(), points_, max_corners_.get(), quality_.get(), min_distance_.get());
        detected_ = points_.size();
      }
      if (!points_.empty()) {
        std::vector<float> err;
        cv::calcOpticalFlowPyrLK(previous_.get(), gray, points_, out->current, out->status, err,
                                 cv::Size(win_size_.get(), win_size_.get()), max_level_.get());
        out->previous = points_;
      }
      points_.clear();  // those found again go on from here
      for (std::size_t i = 0; i < out->current.size(); ++i)
        if (out->status[i]) points_.push_back(out->current[i]);
    }
    previous_.keep(frame, gray);
    tracks_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Tracks> tracks_{this, kTracks};
  apex::Param<int> max_corners_{this, kMaxCorners};
  apex::Param<double> quality_{this, kQuality};
  apex::Param<double> min_distance_{this, kMinDistance};
  apex::Choice<Redetect> redetect_{this, kRedetect};
  apex::Param<int> win_size_{this, kWinSize};
  apex::Param<int> max_level_{this, kMaxLevel};
  KeptGray previous_;  // the last frame's gray
  std::vector<cv::Point2f> points_;  // to track from previous_
  std::size_t detected_ = 0;  // points the last detection found
};

class OpticalFlowFarneback : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour (on its gray)"};
  static inline const apex::OutputPort<Image> kFlow{
      "flow", "32FC2: each pixel's (dx, dy) from the previous frame to this one; zeros on the first frame"};
  static inline const apex::ParamDecl<double> kPyrScale =
      param::number("pyr_scale").range(0.1, 0.9).step(0.05).init(0.5).describe("each pyramid level's scale of the one below");
  static inline const apex::ParamDecl<int> kLevels =
      param::integer("levels").range(1, 10).step(1).init(3).describe("pyramid levels, the image included");
  static inline const apex::ParamDecl<int> kWinsize =
      param::integer("winsize").range(3, 101).step(1).init(15).describe("averaging window, pixels a side");
  static inline const apex::ParamDecl<int> kIterations =
      param::integer("iterations").range(1, 20).step(1).init(3).describe("per level");
  static inline const apex::ChoiceDecl<int> kPolyN =
      param::choice<int>("poly_n", {{"5", 5}, {"7", 7}}).describe("pixels a side of the neighbourhood fitted with a polynomial");
  static inline const apex::ParamDecl<double> kPolySigma = param::number("poly_sigma")
                                                               .range(0.5, 3.0)
                                                               .step(0.05)
                                                               .init(1.2)
                                                               .describe("the fit's Gaussian: 1.1 suits poly_n 5, 1.5 poly_n 7");
  static apex::Manifest manifest() {
    return apex::Manifest("Dense optical flow from the previous frame to this one (calcOpticalFlowFarneback)")
        .inCategory("motion")
        .keepsState("the previous frame: a re-run compares the held frame with itself")
        .input(kImage)
        .output(kFlow)
        .param(kPyrScale)
        .param(kLevels)
        .param(kWinsize)
        .param(kIterations)
        .param(kPolyN)
        .param(kPolySigma)
        .slot("reset", &OpticalFlowFarneback::reset, "forgets the previous frame: the next one gets zeros");
  }
  void endOfSequence() override {
    reset();
    endSequence();
  }
  void reset() { previous_.reset(); }

  void process() override {
    const auto frame = image_.get();
    const Image& in = *frame;
    const cv::Mat gray = previous_.of(in);
    auto out = buffer_.next(in);
    out->encoding = "32FC2";
    if (previous_.get().size() != gray.size()) {  // the first frame, or one of another size
      out->mat.create(gray.size(), CV_32FC2);
      out->mat.setTo(cv::Scalar::all(0));
    } else {
      cv::calcOpticalFlowFarneback(previous_.get(), gray, out->mat, pyr_scale_.get(), levels_.get(), winsize_.get(),
                                   iterations_.get(), poly_n_.get(), poly_sigma_.get(), 0);
    }
    previous_.keep(frame, gray);
    flow_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Image> flow_{this, kFlow};
  apex::Param<double> pyr_scale_{this, kPyrScale};
  apex::Param<int> levels_{this, kLevels};
  apex::Param<int> winsize_{this, kWinsize};
  apex::Param<int> iterations_{this, kIterations};
  apex::Choice<int> poly_n_{this, kPolyN};
  apex::Param<double> poly_sigma_{this, kPolySigma};
  KeptGray previous_;  // the last frame's gray
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::OpticalFlowLK, "apex_nodes/OpticalFlowLK");
APEX_REGISTER_NODE(apex_nodes::OpticalFlowFarneback, "apex_nodes/OpticalFlowFarneback");
