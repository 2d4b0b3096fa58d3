// Colour: ColorRange (a mask of the pixels within a colour range), SplitChannels, MergeChannels, Debayer.
#include <sensor_msgs/image_encodings.h>

#include <array>
#include <map>
#include <utility>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ColorRange : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "bgr8 or rgb8"};
  static inline const apex::OutputPort<Image> kMask{"mask", "mono8: 255 where the pixel is within the range, else 0"};
  enum class Space { kBgr, kHsv, kLab };
  static inline const apex::ChoiceDecl<Space> kColorSpace =
      param::choice<Space>("color_space", {{"bgr", Space::kBgr}, {"hsv", Space::kHsv}, {"lab", Space::kLab}})
          .describe("the space lower and upper are in (rgb8 images are converted)");
  static inline const apex::ParamDecl<std::vector<double>> kLower = param::list("lower").init({0, 0, 0}).describe(
      "the range's low end, three numbers in the space's channel order: b, g, r; h (0..179), s, v; or L, a, b (0..255)");
  static inline const apex::ParamDecl<std::vector<double>> kUpper =
      param::list("upper").init({255, 255, 255}).describe("the range's high end, inclusive, in the same order");
  static apex::Manifest manifest() {
    return filterManifest("Marks the pixels whose colour is within a range in BGR, HSV or Lab (cv::inRange)", kImage, kMask)
        .inCategory("colour")
        .param(kColorSpace)
        .param(kLower)
        .param(kUpper);
  }
  ColorRange() : ImageFilter("3", true, kImage, kMask) {}

 private:
  static cv::Scalar threeNumbers(const std::vector<double>& v, const char* name) {
    if (v.size() != 3)
      throw std::invalid_argument(std::string("'") + name + "' takes three numbers, one per channel, not " +
                                  std::to_string(v.size()));
    return cv::Scalar(v[0], v[1], v[2]);
  }
  void filter(const Image& in, Image& out) override {
    const bool rgb = in.encoding == "rgb8";
    if (!rgb && in.encoding != "bgr8")
      throw std::invalid_argument("needs a bgr8 or rgb8 image, got '" + in.encoding + "': its colours' order is unknown");
    cv::Scalar lower = threeNumbers(lower_.get(), "lower"), upper = threeNumbers(upper_.get(), "upper");
    const Space space = color_space_.get();
    const cv::Mat* pixels = &in.mat;
    if (space == Space::kHsv) cv::cvtColor(in.mat, converted_, rgb ? cv::COLOR_RGB2HSV : cv::COLOR_BGR2HSV);
    else if (space == Space::kLab) cv::cvtColor(in.mat, converted_, rgb ? cv::COLOR_RGB2Lab : cv::COLOR_BGR2Lab);
    if (space != Space::kBgr) pixels = &converted_;
    else if (rgb) std::swap(lower[0], lower[2]), std::swap(upper[0], upper[2]);  // the bounds in r, g, b order: no copy
    cv::inRange(*pixels, lower, upper, out.mat);
    out.encoding = "mono8";
  }
  apex::Choice<Space> color_space_{this, kColorSpace};
  apex::Param<std::vector<double>> lower_{this, kLower};
  apex::Param<std::vector<double>> upper_{this, kUpper};
  cv::Mat converted_;  // the image in hsv or lab, reused
};

class SplitChannels : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "1 to 4 channels"};
  static inline const apex::OutputPort<Image> kChannel0{"channel_0", "the first channel (blue of bgr8), single-channel"};
  static inline const apex::OutputPort<Image> kChannel1{"channel_1", "the second channel; Nothing if the image has one"};
  static inline const apex::OutputPort<Image> kChannel2{"channel_2", "the third channel; Nothing if the image has fewer"};
  static inline const apex::OutputPort<Image> kChannel3{"channel_3",
                                                        "the fourth channel (alpha of bgra8); Nothing if the image has fewer"};
  static apex::Manifest manifest() {
    return apex::Manifest("Splits an image into its channels, each a single-channel image (mono8, mono16, 32FC1...)")
        .inCategory("colour")
        .input(kImage)
        .output(kChannel0)
        .output(kChannel1)
        .output(kChannel2)
        .output(kChannel3);
  }
  void process() override {
    const Image& in = *in_.get();
    requireImage(in, "1234");
    if (in.mat.channels() == 1) {  // channel_0 is the image itself: its message as it came, no copy
      outs_[0].publishMessage(in_.take());
      return;
    }
    // One cv::split into the reused buffers (extractChannel per channel was 8x the split call:
    // docs/benchmarks.md); split keeps a plane's pixels when its size and type fit.
    const int n = in.mat.channels();
    std::array<std::shared_ptr<Image>, 4> out;
    std::array<cv::Mat, 4> planes;
    for (int c = 0; c < n; ++c) planes[c] = (out[c] = buffers_[c].next(in))->mat;
    cv::split(in.mat, planes.data());
    for (int c = 0; c < n; ++c) {  // the outputs of channels it lacks send Nothing
      out[c]->mat = planes[c];
      out[c]->encoding = encodingOf(in, 1, in.mat.depth());
      outs_[c].publish(out[c]);
    }
  }

 private:
  apex::Input<Image> in_{this, kImage};
  std::array<apex::Output<Image>, 4> outs_{{{this, kChannel0}, {this, kChannel1}, {this, kChannel2}, {this, kChannel3}}};
  std::array<OutputBuffer, 4> buffers_;
};

class MergeChannels : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kChannel0{"channel_0", "single-channel: the first (blue)"};
  static inline const apex::InputPort<Image> kChannel1{"channel_1", "single-channel, of channel_0's size and depth"};
  static inline const apex::InputPort<Image> kChannel2{"channel_2", "single-channel, of channel_0's size and depth"};
  static inline const apex::InputPort<Image> kChannel3{"channel_3", "optional: a fourth (alpha)", true};
  static inline const apex::OutputPort<Image> kImage{
      "image", "bgr8 or bgra8 (bgr16, bgra16 of 16-bit channels; 32FC3... of others), with channel_0's header"};
  static apex::Manifest manifest() {
    return apex::Manifest("Merges three or four single-channel images into one image")
        .inCategory("colour")
        .input(kChannel0)
        .input(kChannel1)
        .input(kChannel2)
        .input(kChannel3)
        .output(kImage);
  }
  void process() override {
    std::vector<std::shared_ptr<const Image>> parts{ins_[0].get(), ins_[1].get(), ins_[2].get()};
    if (ins_[3].has()) parts.push_back(ins_[3].get());
    std::vector<cv::Mat> mats;
    for (std::size_t c = 0; c < parts.size(); ++c) {
      const Image& part = *parts[c];
      const std::string name = "channel_" + std::to_string(c);
      if (part.mat.empty()) throw std::invalid_argument(name + " is an empty image");
      if (part.mat.channels() != 1)
        throw std::invalid_argument(name + " is " + imageWords(part) + "; each input needs a single-channel image");
      if (part.mat.size() != parts[0]->mat.size() || part.mat.depth() != parts[0]->mat.depth())
        throw std::invalid_argument(name + " is " + imageWords(part) + ", channel_0 " + imageWords(*parts[0]) +
                                    ": the channels need the same size and depth");
      mats.push_back(part.mat);
    }
    const int depth = mats[0].depth(), channels = static_cast<int>(mats.size());
    auto out = buffer_.next(*parts[0]);
    cv::merge(mats, out->mat);
    if (depth == CV_8U || depth == CV_16U)
      out->encoding = std::string(channels == 3 ? "bgr" : "bgra") + (depth == CV_8U ? "8" : "16");
    else out->encoding = depthName(depth) + "C" + std::to_string(channels);
    out_.publish(out);
  }

 private:
  std::array<apex::Input<Image>, 4> ins_{{{this, kChannel0}, {this, kChannel1}, {this, kChannel2}, {this, kChannel3}}};
  apex::Output<Image> out_{this, kImage};
  OutputBuffer buffer_;
};

class Debayer : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kRaw{"image",
                                                  "a Bayer mosaic: bayer_rggb8, bayer_bggr8, bayer_gbrg8, bayer_grbg8 or 16-bit"};
  static inline const apex::OutputPort<Image> kColour{"image", "bgr8 (bgr16 from a 16-bit mosaic)"};
  /** A method's value is its column in the codes of a pattern (filter()). */
  enum class Method { kBilinear, kVng, kEa };
  static inline const apex::ChoiceDecl<Method> kMethod =
      param::choice<Method>("method", {{"bilinear", Method::kBilinear}, {"vng", Method::kVng}, {"ea", Method::kEa}})
          .describe("bilinear; vng: variable number of gradients (8-bit only); ea: edge-aware");
  static apex::Manifest manifest() {
    return filterManifest("Makes a colour image of a camera's raw Bayer mosaic (demosaicing)", kRaw, kColour)
        .inCategory("colour")
        .param(kMethod);
  }
  Debayer() : ImageFilter("1234", false, kRaw, kColour) {}  // the encoding is checked: an error naming the mosaics

 private:
  void filter(const Image& in, Image& out) override {
    namespace enc = sensor_msgs::image_encodings;
    // OpenCV's codes per pattern, in Method's order: bilinear, VNG, edge-aware.
    static const std::map<std::string, std::array<int, 3>> kCodes{
        {enc::BAYER_RGGB8, {cv::COLOR_BayerRGGB2BGR, cv::COLOR_BayerRGGB2BGR_VNG, cv::COLOR_BayerRGGB2BGR_EA}},
        {enc::BAYER_BGGR8, {cv::COLOR_BayerBGGR2BGR, cv::COLOR_BayerBGGR2BGR_VNG, cv::COLOR_BayerBGGR2BGR_EA}},
        {enc::BAYER_GBRG8, {cv::COLOR_BayerGBRG2BGR, cv::COLOR_BayerGBRG2BGR_VNG, cv::COLOR_BayerGBRG2BGR_EA}},
        {enc::BAYER_GRBG8, {cv::COLOR_BayerGRBG2BGR, cv::COLOR_BayerGRBG2BGR_VNG, cv::COLOR_BayerGRBG2BGR_EA}}};
    const bool wide = in.encoding.size() > 2 && in.encoding.compare(in.encoding.size() - 2, 2, "16") == 0;
    const std::string pattern = wide ? in.encoding.substr(0, in.encoding.size() - 2) + "8" : in.encoding;
    const auto codes = kCodes.find(pattern);
    if (codes == kCodes.end())
      throw std::invalid_argument("cannot debayer '" + in.encoding +
                                  "'; needs bayer_rggb8, bayer_bggr8, bayer_gbrg8 or bayer_grbg8, or their 16-bit forms");
    if (in.mat.channels() != 1 || in.mat.depth() != (wide ? CV_16U : CV_8U))
      throw std::invalid_argument("the encoding '" + in.encoding + "' does not fit the image's pixels, " +
                                  std::to_string(in.mat.channels()) + "-channel " + depthName(in.mat.depth()));
    const Method method = method_.get();
    if (method == Method::kVng && wide)
      throw std::invalid_argument("vng demosaics 8-bit mosaics only, not '" + in.encoding + "': choose bilinear or ea");
    cv::cvtColor(in.mat, out.mat, codes->second[static_cast<std::size_t>(method)]);
    out.encoding = wide ? "bgr16" : "bgr8";
  }
  apex::Choice<Method> method_{this, kMethod};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ColorRange, "apex_nodes/ColorRange");
APEX_REGISTER_NODE(apex_nodes::SplitChannels, "apex_nodes/SplitChannels");
APEX_REGISTER_NODE(apex_nodes::MergeChannels, "apex_nodes/MergeChannels");
APEX_REGISTER_NODE(apex_nodes::Debayer, "apex_nodes/Debayer");
