// VideoSource: a player of a video file (cv::VideoCapture), a folder of images (cv::glob, in name
// order) or a V4L2 camera, one bgr8 frame per firing, as BagReader plays a bag: at `rate` frames
// per second (0: as fast as the graph takes them; it never drops one), seeking where the source
// allows (`frame`), holding its frame while paused or at the end of a pass (sent again after a
// change downstream), and sending the end-of-sequence token after the last frame of each pass, so
// SequenceMean and the Optimizer's tuning loop know a pass is over. A camera never ends, nor seeks.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <opencv2/videoio/registry.hpp>
#include <optional>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

// A file's frames are stamped from here on, as apex_make_bag stamps them: far from 0, which a
// header reads as "no stamp".
constexpr std::int64_t kFirstStampNs = 1700000000LL * 1000000000LL;

/** Opens `path` with the first of OpenCV's file backends that reads it (as cv::VideoCapture(path)
 *  does), but gphoto2's: it is for USB cameras, and leaks libusb's device list on a file. */
bool openVideo(cv::VideoCapture& video, const std::string& path) {
  for (const auto backend : cv::videoio_registry::getStreamBackends())
    if (backend != cv::CAP_GPHOTO2 && video.open(path, backend)) return true;
  return false;
}

}  // namespace

class VideoSource : public apex::Node {
 public:
  static inline const apex::OutputPort<Image> kImage{"image", "each frame, bgr8, stamped with its time in the sequence"};
  static inline const apex::OutputPort<double> kStamp{
      "stamp", "the frame's time, seconds: into the video (CAP_PROP_POS_MSEC), k / fps for image k; a camera's: now"};
  static inline const apex::TriggerPort kFinished{
      "finished", "fires after the last frame of each pass, with the end-of-sequence token that follows that frame"};
  static inline const apex::ParamDecl<std::string> kFile = param::path("file")
                                                               .describe("a video file, or a folder of images (see pattern)")
                                                               .mode(apex::PathMode::ReadFileOrFolder)
                                                               .files({"*.avi", "*.mp4", "*.mkv", "*.mov", "*.webm"});
  static inline const apex::ParamDecl<std::string> kPattern =
      param::text("pattern")
          .init("*.jpg")
          .describe("with a folder: the images whose names match this (cv::glob: * and ?), in name order, e.g. left*.jpg")
          .fileName();
  static inline const apex::ParamDecl<int> kDevice = param::integer("device").range(-1, 63).step(1).init(-1).describe(
      "0 or more: the camera /dev/video<device> (V4L2) instead of the file; -1: the file");
  static inline const apex::ParamDecl<std::string> kFrameId =
      param::text("frame_id").init("camera").describe("the images' header frame");
  static inline const apex::ParamDecl<bool> kPlaying = param::flag("playing").init(true);
  static inline const apex::ParamDecl<double> kRate =
      param::number("rate").range(0.0, 1000.0).step(0.1).describe("frames per second; 0: as fast as the graph takes them");
  static inline const apex::ParamDecl<double> kFps =
      param::number("fps")
          .range(0.01, 1000.0)
          .step(0.01)
          .init(25.0)
          .describe("a folder's images: their frame rate, for their stamps (image k at k / fps seconds)");
  static inline const apex::ParamDecl<bool> kLoop =
      param::flag("loop").describe("after the last frame, play again from the first");
  static inline const apex::ParamDecl<int> kFrame =
      param::integer("frame")
          .range(0, 10000000)
          .step(1)
          .describe("the current frame (its output sends each frame's index); setting it seeks there and sends that frame")
          .interactive()
          .everySet();
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Plays a video file, a folder of images or a V4L2 camera: one bgr8 frame per firing; seeks, holds a frame")
        .inCategory("ROS I/O")
        .output(kImage)
        .output(kStamp)
        .trigger(kFinished)
        .slot("restart", &VideoSource::restart, "back to the first frame (and send it)")
        .slot("end_pass", &VideoSource::endPass,
              "ends a pass in progress now: its end of the sequence follows the frames already sent")
        .param(kFile)
        .param(kPattern)
        .param(kDevice)
        .param(kFrameId)
        .param(kPlaying)
        .param(kRate)
        .param(kFps)
        .param(kLoop)
        .param(kFrame)
        .driven();
  }

  void setup() override { open(); }
  void parameterChanged(const std::string& name) override {
    if (name == "file" || name == "pattern" || name == "device") {
      if (opened_) open();  // before setup(): it opens once with every value
    } else if (name == "frame") {
      if (opened_) seek(frame_.get());
      else seek_on_open_ = true;  // set with the node: open() goes there
    } else if ((name == "playing" && playing_.get()) || name == "rate") {
      if (name == "playing" && at_end_) at_end_ = false, next_ = 0;  // play at the end starts again
      wake();
    }
  }
  void downstreamChanged() override {
    if (!held_.image || (playing_.get() && !at_end_)) return;  // playing: the next frame shows the change
    resend_ = true;  // the frame held is sent once more; it ends no pass
    notifyNewData();
  }

  void process() override {
    if (!open_error_.empty()) return reportError(open_error_);  // stays in error until a source opens
    if (kind_ == Kind::kNone) return;
    if (std::exchange(end_now_, false)) return finishPass(false);
    const bool requested = request_ >= 0, resend = std::exchange(resend_, false);
    if (!requested && resend) return send(held_);
    int k = std::exchange(request_, -1);
    if (!requested) {
      if (!playing_.get() || at_end_ || std::chrono::steady_clock::now() < due_) return;  // the timer for the next is set
      k = next_;
    }
    std::optional<Held> frame = read(k);
    if (!frame) {
      if (requested) throw std::invalid_argument("frame " + std::to_string(k) + " is past the end of " + name_);
      return finishPass(loop_.get());
    }
    next_ = k + 1;
    held_ = *frame;
    updateParam(kFrame.name(), k);
    if (playing_.get()) schedule();
    send(held_);
  }

  void restart() {
    if (kind_ == Kind::kNone || kind_ == Kind::kDevice) return;  // a camera has no first frame to go back to
    end_now_ = false;
    seek(0);
  }
  void endPass() {
    if (kind_ == Kind::kNone || at_end_ || !held_.image) return;  // no pass in progress
    request_ = -1;
    end_now_ = true;
    notifyNewData();
  }

 private:
  enum class Kind { kNone, kVideo, kImages, kDevice };
  struct Held {
    std::shared_ptr<const Image> image;
    double seconds = 0;
  };

  void open() {
    opened_ = true;
    video_.release();
    files_.clear();
    kind_ = Kind::kNone;
    held_ = {};
    request_ = -1, next_ = 0, position_ = -1, count_ = -1;
    at_end_ = end_now_ = resend_ = false;
    open_error_.clear();
    try {
      openSource();
    } catch (const std::exception& e) {
      open_error_ = e.what();  // also for the firings to come: "playing" must not make it look fine
      throw;
    }
    // A frame set with the node is shown (and played from); one saved at the end of a pass starts over.
    if (std::exchange(seek_on_open_, false) && kind_ != Kind::kNone && kind_ != Kind::kDevice &&
        (count_ < 0 || frame_.get() < count_ - 1))
      seek(frame_.get());
    wake();
  }
  void openSource() {
    if (device_.get() >= 0) {
      name_ = "the camera /dev/video" + std::to_string(device_.get());
      if (!std::filesystem::exists("/dev/video" + std::to_string(device_.get())))
        throw std::invalid_argument("no " + name_.substr(4) + ": this machine has no such V4L2 device (device " +
                                    std::to_string(device_.get()) + "; -1 plays the file)");
      if (!video_.open(device_.get(), cv::CAP_V4L2)) throw std::invalid_argument("cannot open " + name_ + " (V4L2)");
      kind_ = Kind::kDevice;
      position_ = 0;
      return;
    }
    const std::string file = file_.get();
    if (file.empty()) return;  // nothing to play yet
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) {
      name_ = "the images '" + pattern_.get() + "' in '" + file + "'";
      cv::glob(file + "/" + pattern_.get(), files_, false);  // sorted by name
      if (files_.empty()) throw std::invalid_argument("no files in the folder '" + file + "' match '" + pattern_.get() + "'");
      kind_ = Kind::kImages;
      count_ = static_cast<int>(files_.size());
      return;
    }
    name_ = "the video '" + file + "'";
    if (!std::filesystem::exists(file, ec)) throw std::invalid_argument("cannot open the video '" + file + "': no such file");
    if (!openVideo(video_, file)) throw std::invalid_argument("OpenCV cannot read '" + file + "' as a video");
    const double n = video_.get(cv::CAP_PROP_FRAME_COUNT);  // the container's count: the end is where reading stops
    count_ = n >= 1 ? static_cast<int>(std::llround(n)) : -1;
    kind_ = Kind::kVideo;
    position_ = 0;
  }

  /** Frame k, or nothing past the last one: reads on from where the source is, seeks otherwise. */
  std::optional<Held> read(int k) {
    auto out = std::make_shared<Image>();
    out->encoding = "bgr8";
    out->header.frame_id = frame_id_.get();
    Held held;
    if (kind_ == Kind::kImages) {
      if (k >= static_cast<int>(files_.size())) return std::nullopt;
      out->mat = cv::imread(files_[k], cv::IMREAD_COLOR);
      if (out->mat.empty()) throw std::invalid_argument("cannot read '" + files_[k] + "' as an image");
      held.seconds = k / fps_.get();
    } else {
      if (kind_ == Kind::kVideo && k != position_ && !video_.set(cv::CAP_PROP_POS_FRAMES, k))
        throw std::invalid_argument("cannot seek to frame " + std::to_string(k) + " of " + name_);
      position_ = -1;  // unknown until the read succeeds: the next read seeks
      if (!video_.read(out->mat)) {
        if (kind_ == Kind::kDevice) throw std::invalid_argument(name_ + " sent no frame");
        return std::nullopt;
      }
      position_ = k + 1;
      held.seconds = video_.get(cv::CAP_PROP_POS_MSEC) / 1000.0;
    }
    if (kind_ == Kind::kDevice) {  // stamped as a live sensor's: when it was read
      const ros::WallTime now = ros::WallTime::now();
      out->header.stamp = ros::Time(now.sec, now.nsec);
      held.seconds = out->header.stamp.toSec();
    } else {
      out->header.stamp.fromNSec(static_cast<std::uint64_t>(kFirstStampNs + std::llround(held.seconds * 1e9)));
    }
    held.image = std::move(out);
    return held;
  }
  void send(const Held& frame) {
    image_.publish(frame.image);
    stamp_.publish(frame.seconds);
  }
  /** The end of a pass: the token on every output and `finished`; then the next pass, or the last frame held. */
  void finishPass(bool again) {
    endSequence();
    finished_.fire();
    next_ = 0;
    at_end_ = !again;
    if (again) schedule();
  }
  void seek(int k) {
    if (kind_ == Kind::kNone) return;
    if (kind_ == Kind::kDevice) throw std::invalid_argument(name_ + " cannot seek: it sends its frames as they come");
    if (count_ >= 0 && k >= count_)
      throw std::invalid_argument("frame " + std::to_string(k) + " is past the last frame, " + std::to_string(count_ - 1) +
                                  ", of " + name_);
    next_ = k;
    at_end_ = false;
    request_ = k;
    notifyNewData();
  }
  void schedule() {
    const double rate = rate_.get();
    due_ = std::chrono::steady_clock::now();
    if (rate <= 0) return notifyNewData();
    due_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / rate));
    notifyAfter(1.0 / rate);
  }
  void wake() {
    due_ = std::chrono::steady_clock::now();
    if (playing_.get()) notifyNewData();
  }

  apex::Output<Image> image_{this, kImage};
  apex::Output<double> stamp_{this, kStamp};
  apex::Trigger finished_{this, kFinished};
  apex::Param<std::string> file_{this, kFile};
  apex::Param<std::string> pattern_{this, kPattern};
  apex::Param<int> device_{this, kDevice};
  apex::Param<std::string> frame_id_{this, kFrameId};
  apex::Param<bool> playing_{this, kPlaying};
  apex::Param<double> rate_{this, kRate};
  apex::Param<double> fps_{this, kFps};
  apex::Param<bool> loop_{this, kLoop};
  apex::Param<int> frame_{this, kFrame};

  Kind kind_ = Kind::kNone;
  cv::VideoCapture video_;  // a video or a camera
  std::vector<std::string> files_;  // a folder's images, in name order
  std::string name_;  // the source, for messages: "the video '/data/a.avi'"
  int count_ = -1;  // frames in the source; -1: unknown (a camera)
  int position_ = -1;  // the frame video_ reads next; -1: unknown
  int next_ = 0;  // the frame playing sends next
  int request_ = -1;  // a frame asked for by a seek or restart
  bool resend_ = false;  // the held frame goes again (a change downstream)
  bool at_end_ = false;  // a pass ended and no loop: the last frame is held
  bool end_now_ = false;  // end_pass: the end of the sequence goes next
  bool opened_ = false;
  bool seek_on_open_ = false;
  std::string open_error_;  // why the source did not open ("" if it did, or there is none)
  Held held_;  // the frame sent last
  std::chrono::steady_clock::time_point due_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::VideoSource, "apex_nodes/VideoSource");
