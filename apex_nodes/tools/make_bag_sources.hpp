// apex_make_bag's inputs: frames from a video or from image files (a folder, a glob, a list), in
// the encoding asked for, and their stamps (a rate, or a timestamps file). Errors name the file.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace apex_tools {

/** The frames of one camera, in order. */
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  /** @brief The next frame in `frame` (BGR, gray or as decoded for the encoding: readFlags);
   *  false at the end. Throws std::runtime_error naming an image file that cannot be read or
   *  does not decode. */
  virtual bool next(cv::Mat& frame) = 0;
  /** @brief How many frames there are in all, -1 if not known before reading them (a video). */
  virtual long long total() const = 0;
  /** @brief total(), or a video's own (approximate) frame count; -1 if it gives none. */
  virtual long long estimate() const { return total(); }
  /** @brief The frame rate the source records (a video's), 0 if none. */
  virtual double fps() const { return 0; }
  /** @brief How many frames are left; reads through them. */
  virtual std::size_t rest() = 0;
  /** @brief The frame read last, for messages: 'left03.jpg', or 'vtest.avi' frame 7. */
  virtual std::string where() const = 0;
  /** @brief What the source reads, as given (a video, a folder, a glob, a list of files). */
  const std::string& name() const { return name_; }

 protected:
  explicit FrameSource(std::string name) : name_(std::move(name)) {}

 private:
  std::string name_;
};

/** @brief The frames `specs` name: one video file (what is not a folder, a glob or a file named
 *  as an image is opened as a video), or the images of folders (their files named as images,
 *  hidden ones aside), globs and image files, all sorted by naturalLess, read with `flags`.
 *  Throws std::runtime_error naming a path that does not exist, a glob that matches nothing, a
 *  folder without images, a video OpenCV cannot open. */
std::unique_ptr<FrameSource> openFrameSource(const std::vector<std::string>& specs, int flags);

/** @brief `a` before `b` in natural order: runs of digits compare as numbers (img2 < img10). */
bool naturalLess(const std::string& a, const std::string& b);

/** @brief The encodings frames can be written in: bgr8, rgb8, bgra8, rgba8, mono8, mono16, 16UC1. */
const std::vector<std::string>& frameEncodings();
/** @brief cv::imread's flags for an image that will be written as `encoding`: gray for mono8,
 *  16 bits kept for mono16 and 16UC1, an alpha channel kept for bgra8 and rgba8; else colour. */
int readFlags(const std::string& encoding);
/** @brief `frame` (gray, BGR or BGRA, as decoded) in `encoding`; throws std::runtime_error naming
 *  `where` when it cannot be (a 16-bit encoding for 8-bit pixels, an 8-bit one for 16-bit). */
cv::Mat toEncoding(const cv::Mat& frame, const std::string& encoding, const std::string& where);

/** @brief Seconds ("1700000000.033333333", "12", "0.5", "1.7e9") as nanoseconds, exact to the
 *  nanosecond for decimal text; -1 for anything else, a negative time or one past 2106 (beyond
 *  ROS's 32-bit seconds). */
std::int64_t nanoseconds(const std::string& seconds);
/** @brief A timestamps file's stamps (ns): a time in seconds as the first field of each line
 *  (split at spaces, tabs or commas: further fields, such as TUM's file names, are ignored),
 *  blank lines and lines starting with '#' skipped, each later than the one before. Throws
 *  std::runtime_error naming the file and the line. */
std::vector<std::int64_t> readTimestamps(const std::string& file);

/** When each frame was taken (ns): at a rate from a start, or a timestamps file's stamps. */
class FrameClock {
 public:
  /** @brief With a `file`, its stamps (readTimestamps), shifted so that the first is `start` when
   *  `start` >= 0; else one every 1/`rate` s from `start`. Throws std::runtime_error naming the
   *  file when a stamp would be 0 or less (ROS's "no stamp"). */
  FrameClock(const std::string& file, std::int64_t start, double rate);
  /** @brief Hz; 0 with a file. */
  double rate() const { return file_.empty() ? rate_ : 0; }
  /** @brief Frame `i`'s stamp; throws std::runtime_error naming the file and `source` when the
   *  file has no i-th stamp. */
  std::int64_t at(std::size_t i, const std::string& source) const;
  /** @brief Throws std::runtime_error unless the file, if any, has a stamp per frame: `frames` of
   *  all (`all`: the source ran out), or at least `frames` (--max-frames stopped it early). */
  void requireLength(std::size_t frames, bool all, const std::string& source) const;

 private:
  [[noreturn]] void mismatch(const std::string& source, const std::string& frames) const;
  std::string file_;
  std::vector<std::int64_t> stamps_;
  std::int64_t start_;
  double rate_;
};

}  // namespace apex_tools
