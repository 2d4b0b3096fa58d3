// VideoWriter: records its images into a video file (cv::VideoWriter, with OpenCV's FFmpeg
// backend), e.g. a pipeline's drawn results. The file opens at the first frame, whose size and
// colour every later frame must have, and is complete once closed: by the stop slot, the end of a
// pass (stop_at_end), a new file name, codec or rate, or the node's removal. As BagWriter, it
// replaces a file it did not write only when told to (overwrite), and writes a frame held by a
// paused player once, however often it is sent again.
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <set>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"

namespace apex_nodes {
namespace param = apex::param;

class VideoWriter : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{
      "image", "8-bit: bgr8, rgb8, bgra8, rgba8 (written as colour) or mono8 (as gray); every frame the first one's size"};
  static inline const apex::OutputPort<int> kFrames{"frames", "how many frames the file holds so far"};
  static inline const apex::ParamDecl<std::string> kFile =
      param::path("file")
          .init("/tmp/apex_video.avi")
          .describe("the video; its extension names the container (.avi, .mp4, .mkv), which must suit the fourcc")
          .mode(apex::PathMode::Write)
          .files({"*.avi", "*.mp4", "*.mkv"});
  // The codecs Debian's OpenCV (4.6, FFmpeg 5.1) encodes, each with a container that takes it.
  static inline const apex::ChoiceDecl<int> kFourcc =
      param::choice<int>(
          "fourcc", {{"MJPG", cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), "Motion JPEG, in .avi: each frame a JPEG (lossy)"},
                     {"XVID", cv::VideoWriter::fourcc('X', 'V', 'I', 'D'), "MPEG-4 part 2, in .avi (lossy, small)"},
                     {"mp4v", cv::VideoWriter::fourcc('m', 'p', '4', 'v'), "MPEG-4 part 2, in .mp4 (lossy, small)"},
                     {"FFV1", cv::VideoWriter::fourcc('F', 'F', 'V', '1'),
                      "FFmpeg's lossless codec, in .avi or .mkv: frames read back exact"}})
          .describe("the codec");
  static inline const apex::ParamDecl<double> kFps =
      param::number("fps").range(0.1, 1000.0).step(0.1).init(25.0).describe("frames per second the video plays at");
  static inline const apex::ParamDecl<bool> kRecording =
      param::flag("recording").init(true).describe("the start and stop slots set it; off closes the file");
  static inline const apex::ParamDecl<bool> kOverwrite =
      param::flag("overwrite").describe("replace a file this node did not write");
  static inline const apex::ParamDecl<bool> kStopAtEnd =
      param::flag("stop_at_end")
          .init(true)
          .describe(
              "the end of a pass (e.g. a VideoSource's last frame) stops recording, so the file is complete when the source has "
              "played once");
  static apex::Manifest manifest() {
    return apex::Manifest("Records its images into a video file (cv::VideoWriter): MJPG, XVID, mp4v or lossless FFV1")
        .inCategory("ROS I/O")
        .keepsState("the file it writes: a frame held by a paused player is written once")
        .input(kImage)
        .output(kFrames)
        .slot("start", &VideoWriter::start, "start recording (a new file: one of that name written before is replaced)")
        .slot("stop", &VideoWriter::stop, "stop recording and close the file")
        .param(kFile)
        .param(kFourcc)
        .param(kFps)
        .param(kRecording)
        .param(kOverwrite)
        .param(kStopAtEnd);
  }

  void parameterChanged(const std::string& name) override {
    if (name == "file" || name == "fourcc" || name == "fps" || (name == "recording" && !recording_.get())) close();
  }
  void endOfSequence() override {
    if (stop_at_end_.get() && recording_.get()) stop();
    endSequence();
  }

  void process() override {
    if (!recording_.get()) return;
    const Image& in = *image_.get();
    requireImage(in, "134");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image, got '" + in.encoding + "'");
    if (!in.header.stamp.isZero() && in.header.stamp == last_stamp_) return;  // the held frame, sent again
    const cv::Mat& frame = bgrOf(in);
    if (!writer_.isOpened()) open(frame);
    if (frame.size() != size_ || frame.channels() != channels_)
      throw std::invalid_argument("a frame of " + sizeText(frame) + " in a video of " + sizeText(size_, channels_) + " ('" +
                                  path_ +
                                  "'): every frame must have the first one's size and colour (stop, then start a new file)");
    writer_.write(frame);
    last_stamp_ = in.header.stamp;
    frames_.publish(++written_);
  }

  void start() {
    close();
    if (!recording_.get()) updateParam(kRecording.name(), true);
  }
  void stop() {
    close();
    if (recording_.get()) updateParam(kRecording.name(), false);
  }

 private:
  static std::string sizeText(const cv::Size& s, int channels) {
    return std::to_string(s.width) + "x" + std::to_string(s.height) + (channels == 1 ? " gray" : " colour");
  }
  static std::string sizeText(const cv::Mat& m) { return sizeText(m.size(), m.channels()); }

  /** The frame as cv::VideoWriter takes it: BGR, or gray. */
  const cv::Mat& bgrOf(const Image& in) {
    const bool rgb = in.encoding.rfind("rgb", 0) == 0;
    if (in.mat.channels() == 4) cv::cvtColor(in.mat, bgr_, rgb ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
    else if (in.mat.channels() == 3 && rgb) cv::cvtColor(in.mat, bgr_, cv::COLOR_RGB2BGR);
    else return in.mat;
    return bgr_;
  }
  void open(const cv::Mat& first) {
    const std::string path = file_.get();
    if (!created_.count(path) && !overwrite_.get() && std::filesystem::exists(std::filesystem::symlink_status(path)))
      throw std::invalid_argument("'" + path + "' exists (not written by this node): left as it is; set 'overwrite' to " +
                                  "replace it, or choose another file");
    if (!writer_.open(path, cv::CAP_FFMPEG, fourcc_.get(), fps_.get(), first.size(), first.channels() != 1))
      throw std::invalid_argument("cannot write '" + path + "' as " + fourcc_.text() +
                                  " video: is its folder writable, and does its extension suit the codec (MJPG, XVID, FFV1: "
                                  ".avi; mp4v: .mp4)?");
    created_.insert(path);
    path_ = path;
    size_ = first.size();
    channels_ = first.channels();
    written_ = 0;
  }
  void close() {
    if (writer_.isOpened()) writer_.release();  // writes the container's index: the file is complete
    last_stamp_ = ros::Time();  // a new file takes the held frame too
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<int> frames_{this, kFrames};
  apex::Param<std::string> file_{this, kFile};
  apex::Choice<int> fourcc_{this, kFourcc};
  apex::Param<double> fps_{this, kFps};
  apex::Param<bool> recording_{this, kRecording};
  apex::Param<bool> overwrite_{this, kOverwrite};
  apex::Param<bool> stop_at_end_{this, kStopAtEnd};

  cv::VideoWriter writer_;
  std::string path_;  // the file writer_ writes
  cv::Size size_;  // its frames' size and channels, from the first
  int channels_ = 3;
  int written_ = 0;
  ros::Time last_stamp_;  // of the frame written last
  std::set<std::string> created_;  // files this node wrote: start replaces them
  cv::Mat bgr_;  // a frame converted to BGR, reused
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::VideoWriter, "apex_nodes/VideoWriter");
