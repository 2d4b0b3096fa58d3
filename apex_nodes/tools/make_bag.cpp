// apex_make_bag's work: its command line read into options; frames from their sources
// (make_bag_sources.hpp), stamped, in the encoding asked for, written with their camera info into a
// bag that gets its name only when whole.
#include "make_bag.hpp"

#include <cv_bridge/cv_bridge.h>
#include <ros/names.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "apex_nodes/camera_model.hpp"
#include "cli.hpp"
#include "make_bag_sources.hpp"

namespace apex_tools {

std::atomic<bool> make_bag_interrupted{false};

namespace {

namespace fs = std::filesystem;

/** A camera of the bag: where its frames come from, where they go. */
struct Camera {
  std::string label;  // how the command line named it: "INPUT", "--left", "--right"
  std::unique_ptr<FrameSource> source;
  std::string topic, info_topic, frame_id, calibration;  // calibration: the file `info` comes from
  std::optional<sensor_msgs::CameraInfo> info;
};

/** `topic`'s namespace and camera_info, as image_transport pairs them (/a/image → /a/camera_info). */
std::string infoTopic(const std::string& topic) { return topic.substr(0, topic.rfind('/')) + "/camera_info"; }

Camera openCamera(const std::string& label, const std::vector<std::string>& specs, const std::string& topic,
                  const std::string& frame_id, const std::string& calibration, int flags) {
  Camera c{label, openFrameSource(specs, flags), topic, infoTopic(topic), frame_id, calibration, std::nullopt};
  if (!calibration.empty()) c.info = apex_nodes::readCameraFile(calibration);  // its errors name the file
  return c;
}

std::vector<Camera> openCameras(const MakeBagOptions& o) {
  const int flags = readFlags(o.encoding);
  std::vector<Camera> cameras;
  if (!o.stereo()) {
    cameras.push_back(openCamera("INPUT", o.inputs, o.topic, o.frame_id, o.camera_info, flags));
    return cameras;
  }
  cameras.push_back(openCamera("--left", {o.left}, o.left_topic, o.frame_id, o.left_info, flags));
  const std::string right_frame = o.right_frame_id.empty() ? o.frame_id : o.right_frame_id;
  cameras.push_back(openCamera("--right", {o.right}, o.right_topic, right_frame, o.right_info, flags));
  return cameras;
}

[[noreturn]] void lengthMismatch(const std::vector<Camera>& cameras, const std::vector<long long>& counts) {
  throw std::runtime_error(cameras[0].label + " '" + cameras[0].source->name() + "' has " + std::to_string(counts[0]) +
                           " frames but " + cameras[1].label + " '" + cameras[1].source->name() + "' has " +
                           std::to_string(counts[1]) + ": a pair needs as many of each");
}

/** One frame per camera; none at the end of all; throws when one camera ends before another. */
std::vector<cv::Mat> nextFrames(std::vector<Camera>& cameras, std::size_t read) {
  std::vector<cv::Mat> frames(cameras.size());
  std::vector<bool> got(cameras.size());
  for (std::size_t k = 0; k < cameras.size(); ++k) got[k] = cameras[k].source->next(frames[k]);
  if (std::all_of(got.begin(), got.end(), [](bool g) { return g; })) return frames;
  if (std::none_of(got.begin(), got.end(), [](bool g) { return g; })) return {};
  std::vector<long long> counts;
  for (std::size_t k = 0; k < cameras.size(); ++k)
    counts.push_back(static_cast<long long>(read + (got[k] ? 1 + cameras[k].source->rest() : 0)));
  lengthMismatch(cameras, counts);
}

/** The bag, written as <path>.active and renamed by commit(); removed if never committed. */
class ActiveBag {
 public:
  ActiveBag(const std::string& path, const std::string& compression) : path_(path), active_(path + ".active") {
    try {
      bag_.open(active_, rosbag::bagmode::Write);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("cannot write '" + active_ + "': " + e.what());
    }
    if (compression == "lz4") bag_.setCompression(rosbag::compression::LZ4);
    if (compression == "bz2") bag_.setCompression(rosbag::compression::BZ2);
  }
  ~ActiveBag() {
    if (committed_) return;
    try {
      bag_.close();
    } catch (const std::exception&) {  // the failure that brought us here is the one to report
    }
    std::error_code ec;
    fs::remove(active_, ec);
  }
  template <class M>
  void write(const std::string& topic, const ros::Time& time, const M& message) {
    try {
      bag_.write(topic, time, message);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("cannot write to '" + active_ + "': " + e.what());
    }
  }
  void commit() {
    bag_.close();
    std::error_code ec;
    fs::rename(active_, path_, ec);
    if (ec) throw std::runtime_error("cannot rename '" + active_ + "' to '" + path_ + "': " + ec.message());
    committed_ = true;
  }

 private:
  std::string path_, active_;
  rosbag::Bag bag_;
  bool committed_ = false;
};

void refuseExisting(const std::string& path, bool overwrite) {
  if (overwrite) return;
  if (fs::exists(fs::symlink_status(path))) throw std::runtime_error("'" + path + "' exists: give --overwrite to replace it");
  if (fs::exists(fs::symlink_status(path + ".active")))
    throw std::runtime_error("'" + path + ".active' exists: an unfinished bag (rosbag reindex may recover it); " +
                             "move it away or give --overwrite");
}

void writeFrame(ActiveBag& bag, const Camera& c, const cv::Mat& frame, std_msgs::Header header, const std::string& encoding) {
  header.frame_id = c.frame_id;
  const cv::Mat pixels = toEncoding(frame, encoding, c.source->where());
  bag.write(c.topic, header.stamp, *cv_bridge::CvImage(header, encoding, pixels).toImageMsg());
  if (!c.info) return;
  if ((c.info->width || c.info->height) && (int(c.info->width) != pixels.cols || int(c.info->height) != pixels.rows))
    throw std::runtime_error("'" + c.calibration + "' is for " + std::to_string(c.info->width) + "x" +
                             std::to_string(c.info->height) + " images but " + c.source->where() + " is " +
                             std::to_string(pixels.cols) + "x" + std::to_string(pixels.rows));
  sensor_msgs::CameraInfo info = *c.info;
  info.header = header;
  bag.write(c.info_topic, header.stamp, info);
}

/** The frames to expect (for the progress bar), -1 if not known; checks a pair's known lengths. */
long long expectedFrames(const std::vector<Camera>& cameras, std::uint64_t max_frames) {
  std::vector<long long> totals;
  for (const auto& c : cameras) totals.push_back(c.source->total());
  if (totals.size() == 2 && totals[0] >= 0 && totals[1] >= 0 && totals[0] != totals[1]) lengthMismatch(cameras, totals);
  const long long n = cameras[0].source->estimate();
  if (n < 0) return -1;
  return max_frames ? std::min<long long>(n, static_cast<long long>(max_frames)) : n;
}

/** Frames from `cameras` into `bag` until they run out (true) or --max-frames (false). */
bool writeFrames(ActiveBag& bag, std::vector<Camera>& cameras, const FrameClock& clock, const MakeBagOptions& o,
                 const MakeBagProgress& progress, long long expected, MakeBagSummary& s) {
  for (std::size_t i = 0; !o.max_frames || i < o.max_frames; ++i) {
    if (make_bag_interrupted) throw std::runtime_error("interrupted: no bag written");
    const std::vector<cv::Mat> frames = nextFrames(cameras, i);
    if (frames.empty()) return true;
    std_msgs::Header header;
    header.seq = static_cast<std::uint32_t>(i);
    header.stamp.fromNSec(static_cast<std::uint64_t>(clock.at(i, cameras[0].source->name())));
    for (std::size_t k = 0; k < cameras.size(); ++k) writeFrame(bag, cameras[k], frames[k], header, o.encoding);
    if (!i) s.first_ns = clock.at(0, ""), s.width = frames[0].cols, s.height = frames[0].rows;
    s.last_ns = clock.at(i, "");
    s.frames = i + 1;
    if (progress) progress(s.frames, expected);
  }
  return false;
}

const std::vector<std::string> kCompressions = {"none", "lz4", "bz2"};

std::string oneOf(const std::string& what, const std::string& value, const std::vector<std::string>& allowed) {
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return value;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  throw std::invalid_argument(what + " is one of " + list + ", not '" + value + "'");
}

double hertz(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (!text.empty() && !*end && v >= 1e-3 && v <= 1e6) return v;
  throw std::invalid_argument("--rate needs Hz from 0.001 to 1000000, not '" + text + "'");
}

std::int64_t startTime(const std::string& text) {
  const std::int64_t ns = nanoseconds(text);
  if (ns > 0) return ns;
  throw std::invalid_argument("--start needs seconds after 0 (ROS's \"no stamp\") and before 4294967296, not '" + text + "'");
}

/** `topic` as a bag holds it: a valid ROS name, absolute. */
std::string topicName(const std::string& what, const std::string& topic) {
  std::string error;
  if (topic.empty() || topic[0] == '~' || topic.back() == '/' || !ros::names::validate(topic, error))
    throw std::invalid_argument(what + " '" + topic + "' is not a topic name" + (error.empty() ? "" : ": " + error));
  return topic[0] == '/' ? topic : "/" + topic;
}

std::string frameId(const std::string& what, const std::string& id) {
  if (!id.empty() && id[0] != '/') return id;
  throw std::invalid_argument(what + " '" + id + "': a frame id is not empty and (for tf2) does not start with '/'");
}

void requireCombination(const MakeBagOptions& o, const std::set<std::string>& given) {
  const auto refuse = [](const std::string& why) { throw std::invalid_argument(why); };
  if (o.output.empty()) refuse("needs the bag to write: -o OUT.bag");
  if (given.count("--rate") && given.count("--timestamps")) refuse("give --rate or --timestamps, not both");
  if (!o.stereo()) {
    if (o.inputs.empty()) refuse("needs an INPUT (a video, a folder or a glob of images), or --left and --right");
    for (const char* pair : {"--left-topic", "--right-topic", "--right-frame-id", "--left-info", "--right-info"})
      if (given.count(pair)) refuse(std::string(pair) + " is for a stereo pair (--left and --right)");
    return;
  }
  if (o.left.empty() || o.right.empty()) refuse("a stereo pair needs both --left and --right");
  if (!o.inputs.empty()) refuse("give INPUT or --left and --right, not both ('" + o.inputs[0] + "')");
  for (const char* one : {"--topic", "--camera-info"})
    if (given.count(one)) refuse(std::string(one) + " is for one camera: a pair takes --left-topic, --left-info, ...");
  if (o.left_topic == o.right_topic) refuse("--left-topic and --right-topic are both '" + o.left_topic + "'");
  if (!o.left_info.empty() && !o.right_info.empty() && infoTopic(o.left_topic) == infoTopic(o.right_topic))
    refuse("both cameras' info would go to " + infoTopic(o.left_topic) + ": give their topics namespaces of their own");
}

}  // namespace

MakeBagOptions parseMakeBagArgs(const std::vector<std::string>& args) {
  MakeBagOptions o;
  using Set = std::function<void(const std::string&)>;
  const std::map<std::string, Set> options = {
      {"--output", [&](const std::string& v) { o.output = v; }},
      {"--left", [&](const std::string& v) { o.left = v; }},
      {"--right", [&](const std::string& v) { o.right = v; }},
      {"--topic", [&](const std::string& v) { o.topic = topicName("--topic", v); }},
      {"--left-topic", [&](const std::string& v) { o.left_topic = topicName("--left-topic", v); }},
      {"--right-topic", [&](const std::string& v) { o.right_topic = topicName("--right-topic", v); }},
      {"--frame-id", [&](const std::string& v) { o.frame_id = frameId("--frame-id", v); }},
      {"--right-frame-id", [&](const std::string& v) { o.right_frame_id = frameId("--right-frame-id", v); }},
      {"--encoding", [&](const std::string& v) { o.encoding = oneOf("--encoding", v, frameEncodings()); }},
      {"--rate", [&](const std::string& v) { o.rate = hertz(v); }},
      {"--timestamps", [&](const std::string& v) { o.timestamps = v; }},
      {"--start", [&](const std::string& v) { o.start_ns = startTime(v); }},
      {"--camera-info", [&](const std::string& v) { o.camera_info = v; }},
      {"--left-info", [&](const std::string& v) { o.left_info = v; }},
      {"--right-info", [&](const std::string& v) { o.right_info = v; }},
      {"--max-frames", [&](const std::string& v) { o.max_frames = number("--max-frames", v, 1, 1000000000); }},
      {"--compression", [&](const std::string& v) { o.compression = oneOf("--compression", v, kCompressions); }}};
  std::set<std::string> given;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string arg = args[i] == "-o" ? "--output" : args[i], value;
    if (arg == "--overwrite") {
      o.overwrite = true;
    } else if (arg.size() < 2 || arg[0] != '-') {
      o.inputs.push_back(arg);
    } else {
      const std::size_t eq = arg.find('=');  // --rate=30 as well as --rate 30
      if (eq != std::string::npos) value = arg.substr(eq + 1), arg.resize(eq);
      const auto option = options.find(arg);
      if (option == options.end()) throw std::invalid_argument("unknown option '" + arg + "'");
      if (eq == std::string::npos && i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
      option->second(eq == std::string::npos ? args[++i] : value);
      given.insert(arg);
    }
  }
  requireCombination(o, given);
  return o;
}

MakeBagSummary makeBag(const MakeBagOptions& o, const MakeBagProgress& progress) {
  refuseExisting(o.output, o.overwrite);
  std::vector<Camera> cameras = openCameras(o);
  const long long expected = expectedFrames(cameras, o.max_frames);
  const FrameSource& first = *cameras[0].source;
  const double rate = o.rate > 0 ? o.rate : first.fps() > 0 && first.fps() <= 1000 ? first.fps() : kDefaultRate;
  const FrameClock clock(o.timestamps, (o.start_ns >= 0 || !o.timestamps.empty()) ? o.start_ns : kDefaultStart, rate);
  if (first.total() >= 0)  // before any work: the frames are known
    clock.requireLength(expected, !o.max_frames || first.total() <= static_cast<long long>(o.max_frames), first.name());
  MakeBagSummary s;
  s.rate = clock.rate();
  for (const auto& c : cameras) {
    s.topics.push_back(c.topic);
    if (c.info) s.topics.push_back(c.info_topic);
  }
  ActiveBag bag(o.output, o.compression);
  const bool all = writeFrames(bag, cameras, clock, o, progress, expected, s);
  if (!s.frames) throw std::runtime_error("'" + first.name() + "' has no frames");
  clock.requireLength(s.frames, all, first.name());
  bag.commit();
  return s;
}

}  // namespace apex_tools
