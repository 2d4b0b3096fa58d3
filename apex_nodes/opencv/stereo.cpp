// StereoMatcher: the disparity of a rectified stereo pair (cv::StereoSGBM or cv::StereoBM), in
// pixels: OpenCV's fixed-point result (16ths of a pixel) divided by 16, as a float image. A pixel
// without a match (OpenCV's min_disparity - 1) is NaN, or with invalid = opencv, min_disparity - 1 as OpenCV has it.
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

std::string sizeText(const cv::Mat& m) { return std::to_string(m.cols) + "x" + std::to_string(m.rows); }

/** An 8-bit image as gray (the matchers compare intensities); throws naming `side` otherwise. */
cv::Mat grayOf(const Image& in, const std::string& side) {
  if (in.mat.empty()) throw std::invalid_argument("the " + side + " image is empty");
  const int channels = in.mat.channels();
  if (in.mat.depth() != CV_8U || (channels != 1 && channels != 3 && channels != 4))
    throw std::invalid_argument("the " + side + " image '" + in.encoding + "' (" + std::to_string(channels) +
                                " channels) is not 8-bit gray or colour: mono8, bgr8, rgb8, bgra8 or rgba8");
  if (channels == 1) return in.mat;
  const bool rgb = in.encoding.rfind("rgb", 0) == 0;
  cv::Mat gray;
  cv::cvtColor(
      in.mat, gray,
      channels == 3 ? (rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY) : (rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY));
  return gray;
}

}  // namespace

class StereoMatcher : public apex::Node {
 public:
  enum class Algorithm { kSgbm, kBm };
  enum class Invalid { kNan, kOpencv };
  static inline const apex::InputPort<Image> kLeft{"left", "the rectified left image: 8-bit gray or colour (matched as gray)"};
  static inline const apex::InputPort<Image> kRight{"right", "the rectified right image, of the same size"};
  static inline const apex::OutputPort<Image> kDisparity{
      "disparity", "32FC1, pixels, per pixel of the left image (its header); NaN where no match (see 'invalid')"};
  static inline const apex::ChoiceDecl<Algorithm> kAlgorithm =
      param::choice<Algorithm>("algorithm", {{"sgbm", Algorithm::kSgbm, "semi-global block matching (cv::StereoSGBM)"},
                                             {"bm", Algorithm::kBm, "block matching (cv::StereoBM)"}});
  static inline const apex::ParamDecl<int> kMinDisparity =
      param::integer("min_disparity").range(-256, 256).step(1).init(0).describe("the smallest disparity searched, pixels");
  static inline const apex::ParamDecl<int> kNumDisparities = param::integer("num_disparities")
                                                                 .range(16, 512)
                                                                 .step(16)
                                                                 .init(64)
                                                                 .describe("how many disparities are searched (16, 32...)");
  static inline const apex::ParamDecl<int> kBlockSize =
      param::integer("block_size").range(1, 51).step(2).init(5).describe("the matched block's side, pixels (odd; bm: 5 or more)");
  static inline const apex::ParamDecl<int> kP1 = param::integer("p1").range(0, 100000).step(1).describe(
      "sgbm: penalty of a disparity step of 1 between neighbours; 0: 8 x block_size² (OpenCV's sample)");
  static inline const apex::ParamDecl<int> kP2 = param::integer("p2").range(0, 400000).step(1).describe(
      "sgbm: penalty of a larger step; 0: 32 x block_size² (OpenCV's sample)");
  static inline const apex::ParamDecl<int> kUniqueness =
      param::integer("uniqueness_ratio")
          .range(0, 100)
          .step(1)
          .init(10)
          .describe("percent by which the best match's cost must beat the second best's");
  static inline const apex::ParamDecl<int> kSpeckleWindow =
      param::integer("speckle_window_size")
          .range(0, 1000)
          .step(1)
          .init(100)
          .describe("patches of consistent disparity smaller than this many pixels are dropped; 0: none are");
  static inline const apex::ParamDecl<int> kSpeckleRange =
      param::integer("speckle_range")
          .range(0, 64)
          .step(1)
          .init(32)
          .describe(
              "largest disparity change within a patch: pixels with sgbm (OpenCV multiplies it by 16), 16ths of a pixel with bm");
  static inline const apex::ParamDecl<int> kDisp12MaxDiff =
      param::integer("disp12_max_diff")
          .range(-1, 256)
          .step(1)
          .init(1)
          .describe("largest left-right check difference, pixels; -1: no check");
  static inline const apex::ParamDecl<int> kPreFilterCap =
      param::integer("pre_filter_cap")
          .range(0, 63)
          .step(1)
          .describe("clips the prefiltered image's values; 0: OpenCV's sample's (sgbm 63, bm 31)");
  static inline const apex::ParamDecl<int> kTextureThreshold =
      param::integer("texture_threshold")
          .range(0, 10000)
          .step(1)
          .init(10)
          .describe("bm: blocks with less texture than this get no match");
  static inline const apex::ChoiceDecl<int> kMode =
      param::choice<int>("mode", {{"sgbm", cv::StereoSGBM::MODE_SGBM, "5 directions"},
                                  {"hh", cv::StereoSGBM::MODE_HH, "full 8"},
                                  {"sgbm_3way", cv::StereoSGBM::MODE_SGBM_3WAY, "faster 3-way"},
                                  {"hh4", cv::StereoSGBM::MODE_HH4, "4 directions"}})
          .describe("sgbm's directions searched");
  static inline const apex::ChoiceDecl<Invalid> kInvalid =
      param::choice<Invalid>(
          "invalid", {{"nan", Invalid::kNan, "NaN"}, {"opencv", Invalid::kOpencv, "min_disparity - 1, as OpenCV marks it"}})
          .describe("a pixel without a match");

  static apex::Manifest manifest() {
    return apex::Manifest("Disparity of a rectified stereo pair, in pixels (cv::StereoSGBM or cv::StereoBM)")
        .inCategory("cameras and stereo")
        .input(kLeft)
        .input(kRight)
        .output(kDisparity)
        .param(kAlgorithm)
        .param(kMinDisparity)
        .param(kNumDisparities)
        .param(kBlockSize)
        .param(kP1)
        .param(kP2)
        .param(kUniqueness)
        .param(kSpeckleWindow)
        .param(kSpeckleRange)
        .param(kDisp12MaxDiff)
        .param(kPreFilterCap)
        .param(kTextureThreshold)
        .param(kMode)
        .param(kInvalid);
  }
  void parameterChanged(const std::string&) override { matcher_.reset(); }
  void process() override {
    const Image& left = *left_.get();
    const Image& right = *right_.get();
    const cv::Mat l = grayOf(left, "left"), r = grayOf(right, "right");
    if (l.size() != r.size())
      throw std::invalid_argument("the left image is " + sizeText(l) + ", the right image " + sizeText(r) +
                                  ": a rectified pair has one size");
    if (!matcher_) matcher_ = make();
    cv::Mat fixed;  // 16ths of a pixel; (min_disparity - 1) x 16 where no match
    matcher_->compute(l, r, fixed);
    auto out = buffer_.next(left);
    out->encoding = "32FC1";
    fixed.convertTo(out->mat, CV_32F, 1.0 / 16);
    if (invalid_.get() == Invalid::kNan) {
      const int lowest = min_disparity_.get() * 16;
      for (int y = 0; y < fixed.rows; ++y) {
        const short* in = fixed.ptr<short>(y);
        float* d = out->mat.ptr<float>(y);
        for (int x = 0; x < fixed.cols; ++x)
          if (in[x] < lowest) d[x] = std::numeric_limits<float>::quiet_NaN();
      }
    }
    disparity_.publish(out);
  }

 private:
  cv::Ptr<cv::StereoMatcher> make() const {
    const int block = block_size_.get(), cap = pre_filter_cap_.get();
    if (algorithm_.get() == Algorithm::kBm) {
      if (block < 5)
        throw std::invalid_argument("bm needs a block_size of at least 5, got " + std::to_string(block) + " (sgbm takes any)");
      auto bm = cv::StereoBM::create(num_disparities_.get(), block);
      bm->setMinDisparity(min_disparity_.get());
      bm->setPreFilterCap(cap > 0 ? cap : 31);
      bm->setTextureThreshold(texture_threshold_.get());
      bm->setUniquenessRatio(uniqueness_.get());
      bm->setSpeckleWindowSize(speckle_window_.get());
      bm->setSpeckleRange(speckle_range_.get());
      bm->setDisp12MaxDiff(disp12_max_diff_.get());
      return bm;
    }
    const int area = block * block;  // one channel: the images are matched as gray
    return cv::StereoSGBM::create(min_disparity_.get(), num_disparities_.get(), block, p1_.get() > 0 ? p1_.get() : 8 * area,
                                  p2_.get() > 0 ? p2_.get() : 32 * area, disp12_max_diff_.get(), cap > 0 ? cap : 63,
                                  uniqueness_.get(), speckle_window_.get(), speckle_range_.get(), mode_.get());
  }

  apex::Input<Image> left_{this, kLeft};
  apex::Input<Image> right_{this, kRight};
  apex::Output<Image> disparity_{this, kDisparity};
  apex::Choice<Algorithm> algorithm_{this, kAlgorithm};
  apex::Param<int> min_disparity_{this, kMinDisparity};
  apex::Param<int> num_disparities_{this, kNumDisparities};
  apex::Param<int> block_size_{this, kBlockSize};
  apex::Param<int> p1_{this, kP1};
  apex::Param<int> p2_{this, kP2};
  apex::Param<int> uniqueness_{this, kUniqueness};
  apex::Param<int> speckle_window_{this, kSpeckleWindow};
  apex::Param<int> speckle_range_{this, kSpeckleRange};
  apex::Param<int> disp12_max_diff_{this, kDisp12MaxDiff};
  apex::Param<int> pre_filter_cap_{this, kPreFilterCap};
  apex::Param<int> texture_threshold_{this, kTextureThreshold};
  apex::Choice<int> mode_{this, kMode};
  apex::Choice<Invalid> invalid_{this, kInvalid};
  cv::Ptr<cv::StereoMatcher> matcher_;  // made anew after a parameter changes; keeps its buffers between frames
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::StereoMatcher, "apex_nodes/StereoMatcher");
