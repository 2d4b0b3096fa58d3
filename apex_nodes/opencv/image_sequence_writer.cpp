// ImageSequenceWriter: writes each image as one file of a numbered sequence, frame_000000.png,
// frame_000001.png, ..., that VideoSource (a folder and a pattern), apex_make_bag and other tools
// read back in order. Where ImageExport writes PNGs named <prefix>_<count> (or region crops), this
// names its files by a pattern whose %d is the frame's number in its pass or its stamp, writes the
// format the name's extension says (.png, .jpg, .tiff, .webp, ...) at a set quality, and writes the
// same files again on each pass of a sequence (the count starts over at its end).
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** The name `pattern` gives number n: its one %d (or %0<width>d, zero-padded) replaced by n, each %%
 *  by a %. Throws std::invalid_argument naming the pattern if it has no %d, several, or another %. */
std::string nameFor(const std::string& pattern, std::int64_t n) {
  std::string out;
  int conversions = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      out += pattern[i];
    } else if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      out += '%', ++i;
    } else {
      std::size_t j = i + 1;
      while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && j - i <= 2) ++j;
      if (j == pattern.size() || pattern[j] != 'd' || (j > i + 1 && pattern[i + 1] != '0'))
        throw std::invalid_argument("pattern '" + pattern + "': a % is followed by %d, %0<width>d (e.g. %06d) or %%");
      const std::size_t width = j > i + 1 ? std::stoul(pattern.substr(i + 1, j - i - 1)) : 0;
      const std::string digits = std::to_string(n);
      out += std::string(width > digits.size() ? width - digits.size() : 0, '0') + digits;
      ++conversions, i = j;
    }
  }
  if (conversions != 1)
    throw std::invalid_argument("pattern '" + pattern + "' has " + std::to_string(conversions) +
                                " %d: it needs one, for each file's number (e.g. frame_%06d.png)");
  return out;
}

}  // namespace

class ImageSequenceWriter : public apex::Node {
 public:
  enum class Number { kCount, kStamp };
  static inline const apex::InputPort<Image> kImage{"image", "8 or 16 bits, gray or colour (rgb8 is written as colour)"};
  static inline const apex::OutputPort<std::string> kPath{"path", "the file written"};
  static inline const apex::ParamDecl<std::string> kDirectory =
      param::path("directory").init("/tmp/apex_sequence").describe("made if it is not there").mode(apex::PathMode::Directory);
  static inline const apex::ParamDecl<std::string> kPattern =
      param::text("pattern")
          .init("frame_%06d.png")
          .describe("each file's name: %d (%06d: 6 digits, zero-padded) is its number; the extension its format")
          .fileName();
  static inline const apex::ChoiceDecl<Number> kNumber =
      param::choice<Number>("number", {{"count", Number::kCount, "start_number, then one more per frame; again at each pass"},
                                       {"stamp", Number::kStamp, "the image's stamp, nanoseconds"}})
          .describe("what %d is");
  static inline const apex::ParamDecl<int> kStartNumber =
      param::integer("start_number").range(0, 1000000000).step(1).describe("the first frame's number (count)");
  static inline const apex::ParamDecl<int> kJpegQuality =
      param::integer("jpeg_quality").range(0, 100).step(1).init(95).describe(".jpg: IMWRITE_JPEG_QUALITY");
  static inline const apex::ParamDecl<int> kPngCompression =
      param::integer("png_compression")
          .range(-1, 9)
          .step(1)
          .init(-1)
          .describe(
              ".png: IMWRITE_PNG_COMPRESSION, 0 (none) to 9 (most); -1: cv::imwrite's own choice (level 1, filtered for speed)");
  static inline const apex::ParamDecl<bool> kOverwrite =
      param::flag("overwrite").describe("replace files this node did not write (another run's)");
  static apex::Manifest manifest() {
    return apex::Manifest("Writes each image as a numbered file (cv::imwrite), e.g. frame_000000.png: a sequence in name order")
        .inCategory("ROS I/O")
        .keepsState("the files it writes and its count: a frame held by a paused player is written once")
        .input(kImage)
        .output(kPath)
        .param(kDirectory)
        .param(kPattern)
        .param(kNumber)
        .param(kStartNumber)
        .param(kJpegQuality)
        .param(kPngCompression)
        .param(kOverwrite);
  }

  void parameterChanged(const std::string& name) override {
    if (name == "directory" || name == "pattern" || name == "number" || name == "start_number") startOver();
  }
  void endOfSequence() override {
    startOver();  // the next pass writes the same names
    endSequence();
  }

  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "134");
    if (in.mat.depth() != CV_8U && in.mat.depth() != CV_16U)
      throw std::invalid_argument("needs an 8- or 16-bit image, got '" + in.encoding + "'");
    if (!in.header.stamp.isZero() && in.header.stamp == last_stamp_) return;  // the held frame, sent again
    const std::int64_t number =
        number_.get() == Number::kStamp ? static_cast<std::int64_t>(in.header.stamp.toNSec()) : start_number_.get() + count_;
    const std::string path = (std::filesystem::path(directory_.get()) / nameFor(pattern_.get(), number)).string();
    if (!cv::haveImageWriter(path))
      throw std::invalid_argument("OpenCV writes no files named as '" + pattern_.get() + "': give it the extension of a " +
                                  "format (.png, .jpg, .tiff, .webp, .bmp, ...)");
    std::filesystem::create_directories(directory_.get());
    if (!written_.count(path) && !overwrite_.get() && std::filesystem::exists(std::filesystem::symlink_status(path)))
      throw std::invalid_argument("'" + path + "' exists (not written by this node): left as it is; set 'overwrite' to " +
                                  "replace such files, or choose another pattern or directory");
    const bool rgb = in.encoding.rfind("rgb", 0) == 0;  // imwrite takes BGR
    if (rgb && in.mat.channels() == 3) cv::cvtColor(in.mat, bgr_, cv::COLOR_RGB2BGR);
    if (rgb && in.mat.channels() == 4) cv::cvtColor(in.mat, bgr_, cv::COLOR_RGBA2BGRA);
    std::vector<int> options{cv::IMWRITE_JPEG_QUALITY, jpeg_quality_.get()};  // 95 is imwrite's own: the same file
    if (png_compression_.get() >= 0) options.insert(options.end(), {cv::IMWRITE_PNG_COMPRESSION, png_compression_.get()});
    if (!cv::imwrite(path, rgb ? bgr_ : in.mat, options)) throw std::invalid_argument("cannot write '" + path + "'");
    written_.insert(path);
    last_stamp_ = in.header.stamp;
    ++count_;
    path_.publish(path);
  }

 private:
  void startOver() {
    count_ = 0;
    last_stamp_ = ros::Time();
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<std::string> path_{this, kPath};
  apex::Param<std::string> directory_{this, kDirectory};
  apex::Param<std::string> pattern_{this, kPattern};
  apex::Choice<Number> number_{this, kNumber};
  apex::Param<int> start_number_{this, kStartNumber};
  apex::Param<int> jpeg_quality_{this, kJpegQuality};
  apex::Param<int> png_compression_{this, kPngCompression};
  apex::Param<bool> overwrite_{this, kOverwrite};

  std::int64_t count_ = 0;  // frames written in this pass
  ros::Time last_stamp_;  // of the frame written last
  std::set<std::string> written_;  // files this node wrote: a later pass may replace them
  cv::Mat bgr_;  // an rgb frame as BGR, reused
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ImageSequenceWriter, "apex_nodes/ImageSequenceWriter");
