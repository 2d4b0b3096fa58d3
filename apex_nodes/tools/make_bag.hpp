// apex_make_bag's work (make_bag_main.cpp is its command line): a video, a folder or glob of
// images, or a left/right pair of them, written into a bag as sensor_msgs/Image frames (and
// sensor_msgs/CameraInfo beside each, when given a calibration), as <out>.active renamed to <out>
// only when complete.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace apex_tools {

/** What to write: one camera (`inputs`) or a stereo pair (`left` and `right`). */
struct MakeBagOptions {
  std::vector<std::string> inputs;  // a video; or folders, globs and image files (all images)
  std::string left, right;  // a stereo pair: each a video, a folder, a glob or an image
  std::string output;
  std::string topic = "/camera/image_raw";
  std::string left_topic = "/stereo/left/image_raw", right_topic = "/stereo/right/image_raw";
  std::string frame_id = "camera", right_frame_id;  // empty: frame_id
  std::string encoding = "bgr8";
  double rate = 0;  // Hz; 0: the video's own frame rate, else kDefaultRate
  std::string timestamps;  // a file of one stamp (seconds) per frame, instead of a rate
  std::int64_t start_ns = -1;  // the first stamp; -1: kDefaultStart (with timestamps: the file's)
  std::string camera_info, left_info, right_info;  // calibration files
  std::uint64_t max_frames = 0;  // 0: all
  std::string compression = "lz4";  // lz4 (a video in a tenth of its raw size, read as fast), bz2, none
  bool overwrite = false;

  bool stereo() const { return !left.empty() || !right.empty(); }
};

constexpr double kDefaultRate = 10;  // Hz, for images and for videos that give no frame rate
constexpr std::int64_t kDefaultStart = 1700000000LL * 1000000000LL;  // ns: as apex_make_demo_bag's, far from 0

/** @brief The options of a command line (without the program's name): INPUT... or --left and
 *  --right, -o OUT, and the options of MakeBagOptions as --name VALUE or --name=VALUE. Throws
 *  std::invalid_argument naming the option that is wrong, missing or out of place. `--help` is
 *  not one: the caller answers it. */
MakeBagOptions parseMakeBagArgs(const std::vector<std::string>& args);

/** What was written. */
struct MakeBagSummary {
  std::size_t frames = 0;  // per camera
  std::vector<std::string> topics;
  double rate = 0;  // Hz; 0 with timestamps from a file
  std::int64_t first_ns = 0, last_ns = 0;
  int width = 0, height = 0;  // the first frame's (the left one's)
};

/** Called after each frame with the frames written and the frames expected (-1: not known). */
using MakeBagProgress = std::function<void(std::size_t done, long long total)>;

/** @brief Writes the bag. Throws std::runtime_error naming the file (and line) that cannot be
 *  read or that does not fit (a frame that does not decode, a calibration for another size, a
 *  timestamps file of another length, left and right of different lengths; a calibration file
 *  that is not one: std::invalid_argument), and refuses an existing output unless `overwrite`;
 *  on any failure no file is left under the output's name and <output>.active is removed. */
MakeBagSummary makeBag(const MakeBagOptions& options, const MakeBagProgress& progress = nullptr);

/** @brief Set from a signal handler to stop before the next frame: makeBag then throws and
 *  removes <output>.active. */
extern std::atomic<bool> make_bag_interrupted;

}  // namespace apex_tools
