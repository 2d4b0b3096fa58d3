// apex_make_bag: a video, a folder or glob of images, or a left/right pair of them, into a bag
// (make_bag.hpp does the work). A progress bar on stderr when it is a terminal; a summary line on
// stdout; Ctrl-C stops before the next frame and leaves no bag.
#include <ros/time.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "make_bag.hpp"

namespace {

const char* kSynopsis =
    "usage: apex_make_bag INPUT... -o OUT.bag [options]\n"
    "       apex_make_bag --left LEFT --right RIGHT -o OUT.bag [options]\n";

const char* kUsage = R"(
Writes a video, images, or a stereo pair of them into a bag of sensor_msgs/Image frames, with a
sensor_msgs/CameraInfo beside each frame when given a calibration. The bag is written as
OUT.bag.active and gets its name only when complete: a failure or Ctrl-C leaves no bag.

  INPUT        a video file (what OpenCV's VideoCapture opens), a folder of images, a glob of
               images in quotes ('frames/*.png'), or image files; images are taken in the
               natural order of their names (img2 before img10)
  LEFT, RIGHT  the same for each camera of a pair: as many frames each, paired in order, each
               pair with one stamp

  -o, --output OUT.bag  the bag to write
  --topic T             the image topic (/camera/image_raw); camera info goes to T's namespace
                        + /camera_info (/camera/camera_info)
  --left-topic T, --right-topic T
                        a pair's image topics (/stereo/left/image_raw, /stereo/right/image_raw)
  --frame-id F          the images' frame id (camera); --right-frame-id F: the right camera's (F)
  --encoding E          bgr8 (default), rgb8, bgra8, rgba8, mono8, or mono16 / 16UC1 (for 16-bit
                        gray images, such as depth)
  --rate HZ             frames per second (default: the video's own frame rate, else 10)
  --timestamps FILE     the stamps instead: a time in seconds first on each line (further fields,
                        blank lines and # comments ignored), one line per frame (per pair)
  --start S             the first stamp, in seconds (default 1700000000); with --timestamps, the
                        file's stamps shifted to start there (default: the file's as they are)
  --camera-info FILE    a calibration: camera_calibration_parsers' YAML or INI (what ROS's
                        camera_calibration writes) or OpenCV's calibration output
  --left-info FILE, --right-info FILE
                        a pair's calibrations
  --max-frames N        at most N frames (pairs)
  --compression C       lz4 (default), bz2 or none
  --overwrite           replace OUT.bag if it exists
  -h, --help            this help

examples:
  apex_make_bag video.avi -o video.bag
  apex_make_bag 'frames/*.png' --camera-info camera.yaml --rate 30 -o frames.bag
  apex_make_bag --left 'left/*.png' --right 'right/*.png' \
                --left-info left.yaml --right-info right.yaml -o stereo.bag
)";

void interrupt(int) { apex_tools::make_bag_interrupted = true; }

/** A bar redrawn in place on stderr when the share done changes (or every 25 frames of an
 *  unknown number). */
class ProgressBar {
 public:
  void operator()(std::size_t done, long long total) {
    const long long percent = total > 0 ? std::min<long long>(100, static_cast<long long>(done) * 100 / total) : -1;
    if (total > 0 ? percent == last_ : done % 25 != 0) return;
    last_ = percent;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(std::max<long long>(percent, 0) * kWidth / 100);
    if (total > 0)
      std::fprintf(stderr, "\r[%s%s] %3lld%% %zu/%lld frames", std::string(filled, '#').c_str(),
                   std::string(kWidth - filled, '.').c_str(), percent, done, total);
    else std::fprintf(stderr, "\r%zu frames", done);
    std::fflush(stderr);
    drawn_ = true;
  }
  /** Ends the bar's line, if one was drawn. */
  void end() const {
    if (drawn_) std::fputc('\n', stderr);
  }

 private:
  long long last_ = -2;
  bool drawn_ = false;
};

std::string summary(const apex_tools::MakeBagSummary& s, const apex_tools::MakeBagOptions& o) {
  std::ostringstream out;
  out << "apex_make_bag: wrote " << s.frames << (o.stereo() ? " pair" : " frame") << (s.frames == 1 ? "" : "s") << " of "
      << s.width << "x" << s.height << " " << o.encoding << " on ";
  for (std::size_t i = 0; i < s.topics.size(); ++i) out << (i ? ", " : "") << s.topics[i];
  out << ", stamped " << ros::Time().fromNSec(s.first_ns) << " to " << ros::Time().fromNSec(s.last_ns);
  if (s.rate > 0) out << " (" << s.rate << " Hz)";
  else out << " (from " << o.timestamps << ")";
  out << ", to " << o.output;
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (std::find_if(args.begin(), args.end(), [](const std::string& a) { return a == "-h" || a == "--help"; }) != args.end()) {
    std::cout << kSynopsis << kUsage;
    return 0;
  }
  apex_tools::MakeBagOptions options;
  try {
    options = apex_tools::parseMakeBagArgs(args);
  } catch (const std::exception& e) {
    std::cerr << "apex_make_bag: error: " << e.what() << "\n" << kSynopsis << "(--help for more)\n";
    return 2;
  }
  std::signal(SIGINT, interrupt);
  std::signal(SIGTERM, interrupt);
  ProgressBar bar;
  const bool terminal = isatty(STDERR_FILENO);
  try {
    const auto done = apex_tools::makeBag(options, terminal ? apex_tools::MakeBagProgress(std::ref(bar)) : nullptr);
    bar.end();
    std::cout << summary(done, options) << "\n";
  } catch (const std::exception& e) {
    bar.end();
    std::cerr << "apex_make_bag: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
