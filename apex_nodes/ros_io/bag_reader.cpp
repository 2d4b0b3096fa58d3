// BagReader: a bag player. One output per played topic, typed by the topic's
// message type (an interface per instance): a type the library has a port type for
// (images, clouds, scans, camera models, poses, numbers, regions: ros_message.hpp's
// conversions) arrives converted, any other as the ROS message itself (RosMessage);
// the messages of one frame leave in
// one firing. Plays at the bag's pace times `rate` (0: as fast as the graph
// takes them) and never drops: the next frame waits until the graph has read
// the last one. Seeks in O(log n) (bag_frames.hpp). While paused it holds its
// frame and sends it again after any change downstream, so a parameter's
// effect shows on that frame at once; so does a player at the end of a pass that
// does not loop (as `rosbag play`, it does not loop unless asked). After the last frame of a pass it sends the
// end-of-sequence token, so nodes downstream (SequenceMean) know the pass is over.
#include <algorithm>
#include <chrono>
#include <memory>

#include "apex/core/registry.hpp"
#include "apex_nodes/ros_message.hpp"
#include "apex_nodes/types.hpp"
#include "bag_frames.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** The topics a node plays and their outputs: `topics`, one output each; or, when that is
 *  empty, as graphs made before it: `image_topic` on output image, `cloud_topic` on cloud. */
std::vector<std::pair<std::string, std::string>> playedTopics(const std::vector<std::string>& topics,
                                                              const std::string& image_topic, const std::string& cloud_topic) {
  std::vector<std::pair<std::string, std::string>> out;  // (output, topic)
  for (const auto& topic : topics) out.emplace_back(portForTopic(topic), topic);
  if (!out.empty()) return out;
  if (!image_topic.empty()) out.emplace_back("image", image_topic);
  if (!cloud_topic.empty()) out.emplace_back("cloud", cloud_topic);
  return out;
}

/** The outputs for the played topics, typed from the bag (`any` while the bag cannot be
 *  read), and the ranges of `frame` and `time`: the bag's frames. */
apex::Status shapeOutputs(const apex::ParamValues& p, apex::Manifest& m) {
  using Texts = std::vector<std::string>;
  const auto played = playedTopics(p.get<Texts>("topics"), p.get<std::string>("image_topic"), p.get<std::string>("cloud_topic"));
  const bool legacy = p.get<Texts>("topics").empty();
  std::map<std::string, std::string> types;
  std::vector<BagFrame> frames;
  if (!p.get<std::string>("file").empty()) {
    try {
      auto bag = openBag(p.get<std::string>("file"));
      types = topicTypes(*bag);
      Texts topics;
      for (const auto& [port, topic] : played) topics.push_back(topic);
      frames = indexFrames(*bag, topics, p.get<double>("sync_window"));
      closeBag(bag);
    } catch (const std::invalid_argument&) {
      // the node reports why; its outputs carry anything until the bag can be read
    }
  }
  std::vector<apex::PortSpec> outputs;
  for (const auto& [port, topic] : played) {
    const apex::TypeInfo* type = apex::typeOf<apex::Any>();
    std::string desc = "messages of " + topic;
    if (legacy) {
      type = port == "image" ? apex::typeOf<Image>() : apex::typeOf<Cloud>();
    } else if (auto it = types.find(topic); it != types.end()) {
      type = portType(it->second);
      desc += " (" + it->second + ")";
    }
    outputs.push_back({port, type, false, desc});
  }
  m.outputs.insert(m.outputs.begin(), outputs.begin(), outputs.end());
  if (!frames.empty())
    for (auto& spec : m.params) {  // the panel's sliders span the bag
      if (spec.name == "frame") spec.max = static_cast<double>(frames.size() - 1);
      if (spec.name == "time") spec.max = std::max(0.001, (frames.back().start - frames.front().start).toSec());
    }
  return apex::Status::ok();
}

}  // namespace

class BagReader : public apex::Node {
 public:
  static inline const apex::OutputPort<double> kStamp{"stamp", "record time of the frame's first message, seconds"};
  static inline const apex::TriggerPort kFinished{"finished",
                                                  "fires after the last frame of each pass, with the end-of-sequence token that "
                                                  "follows that frame on every output"};
  static inline const apex::ParamDecl<std::string> kFile =
      param::path("file").files({"*.bag"}).describe("the bag").shapesInterface();
  static inline const apex::ParamDecl<std::vector<std::string>> kTopics =
      param::textList("topics")
          .describe(
              "topics to play, one output each (/camera/image_raw: output camera_image_raw); "
              "empty: image_topic and cloud_topic, on outputs image and cloud")
          .shapesInterface();
  static inline const apex::ParamDecl<std::string> kImageTopic =
      param::text("image_topic").init("/camera/image_raw").describe("used when topics is empty").shapesInterface().legacy();
  static inline const apex::ParamDecl<std::string> kCloudTopic =
      param::text("cloud_topic").init("/camera/points").describe("used when topics is empty").shapesInterface().legacy();
  static inline const apex::ParamDecl<double> kSyncWindow =
      param::number("sync_window")
          .range(0.0, 10.0)
          .step(0.001)
          .init(0.02)
          .describe("messages within this many seconds of a frame's first one belong to it")
          .shapesInterface();
  static inline const apex::ParamDecl<bool> kPlaying = param::flag("playing").init(true);
  static inline const apex::ParamDecl<double> kRate =
      param::number("rate").range(0.0, 100.0).step(0.1).init(1.0).describe("times the recorded pace; 0: as fast as possible");
  static inline const apex::ParamDecl<bool> kLoop = param::flag("loop");
  static inline const apex::ParamDecl<bool> kRestamp = param::flag("restamp").describe(
      "stamp each frame's messages (their headers) with the time it is sent, as a live sensor would: latencies "
      "are then live (the panel shows them); off: the recorded stamps");
  static inline const apex::ParamDecl<double> kStart =
      param::number("start").range(0.0, 1e6).step(0.1).describe("play from this many seconds into the bag");
  static inline const apex::ParamDecl<double> kEnd =
      param::number("end").range(0.0, 1e6).step(0.1).describe("play up to this many seconds into the bag; 0: its end");
  static inline const apex::ParamDecl<int> kFrame =
      param::integer("frame")
          .range(0, 10000000)
          .step(1)
          .describe(
              "the current frame (its output sends each frame's index); setting it seeks there "
              "and sends that frame")
          .interactive()
          .everySet();
  static inline const apex::ParamDecl<double> kTime =
      param::number("time")
          .range(0.0, 1e6)
          .step(0.01)
          .describe("seconds into the bag of the current frame; setting it seeks to the frame at that time")
          .everySet();
  static apex::Manifest manifest() {
    return apex::Manifest("Plays a bag: one output per topic, one firing per frame; seeks, holds a frame")
        .inCategory("ROS I/O")
        .output(kStamp)
        .trigger(kFinished)
        .slot("restart", &BagReader::restart, "back to the first frame (and send it)")
        .slot("next", &BagReader::next, "send the next frame")
        .slot("previous", &BagReader::previous, "send the previous frame")
        .slot("end_pass", &BagReader::endPass,
              "ends a pass in progress now: its end of the sequence follows the frames already sent (the "
              "Optimizer's racing cuts a poor candidate's pass so)")
        .param(kFile)
        .param(kTopics)
        .param(kImageTopic)
        .param(kCloudTopic)
        .param(kSyncWindow)
        .param(kPlaying)
        .param(kRate)
        .param(kLoop)
        .param(kRestamp)
        .param(kStart)
        .param(kEnd)
        .param(kFrame)
        .param(kTime)
        .shapedBy(shapeOutputs)
        .driven();
  }
  ~BagReader() override {
    try {
      closeBag(bag_);
    } catch (...) {  // read only: nothing was lost
    }
  }
  void setup() override { open(); }
  void parameterChanged(const std::string& name) override {
    if (name == "file" || name == "topics" || name == "image_topic" || name == "cloud_topic" || name == "sync_window") {
      if (opened_) open();  // before setup(): it opens once with every value
    } else if (name == "start" || name == "end") {
      playRange();
    } else if (name == "frame") {
      if (opened_) seek(frame_.get());
      else seek_on_open_ = true;  // set with the node: open() goes there
    } else if (name == "time" && opened_ && !frames_.empty()) {
      seek(frameAt(time_.get()));
    } else if (name == "playing" && playing_.get()) {
      if (next_ > last_) next_ = first_;  // play at the end starts again
      wake();
    }
  }
  void downstreamChanged() override {
    // Paused, or at the end of a pass that does not loop: the frame shown is held, and sent once
    // more, so a node added or tuned after the pass sees it (it ends no pass: no second `finished`).
    const bool held = !playing_.get() || (next_ > last_ && !loop_.get());
    if (!held || current_ < 0) return;
    request(current_);
    again_ = true;
  }

  void process() override {
    if (!open_error_.empty()) return reportError(open_error_);  // stays in error until a file opens
    if (!bag_ || frames_.empty()) return;
    if (end_pending_) {  // the pass's end, one firing behind its last frame: in step with it
      end_pending_ = false;
      endSequence();
      finished_.fire();
      // What comes next fires again: a frame asked for, or the next pass now (a later one has its timer).
      const bool due = playing_.get() && next_ <= last_ && std::chrono::steady_clock::now() >= due_;
      if (request_ >= 0 || due) notifyNewData();
      return;
    }
    int k;
    const bool requested = request_ >= 0, again = requested && again_;
    again_ = false;
    if (requested) {
      k = request_;
      request_ = -1;
    } else if (playing_.get() && next_ <= last_ && std::chrono::steady_clock::now() >= due_) {
      k = next_;
    } else {
      return;  // paused, past the end, or an early wake-up: the timer for the next frame is set
    }
    next_ = k + 1;
    const bool pass_ends = k == last_ && !again && (!requested || playing_.get());  // stepping by hand ends nothing
    if (pass_ends && loop_.get()) next_ = first_;
    if (playing_.get() && next_ <= last_) schedule(k);
    if (pass_ends) {
      end_pending_ = true;
      notifyNewData();
    }
    send(k);  // last: a malformed message fails this frame only, the next one is on its way
  }

  void restart() {
    next_ = first_;
    request(first_);
  }
  // From a frame asked for but not sent yet, if any: quick presses add up, and coalesce.
  void next() {
    const int at = request_ >= 0 ? request_ : current_;
    request(at < 0 ? next_ : std::min(at + 1, static_cast<int>(frames_.size()) - 1));
  }
  void endPass() {
    if (!bag_ || frames_.empty() || end_pending_ || next_ > last_ || current_ < 0) return;  // no pass in progress
    next_ = last_ + 1;
    request_ = -1;
    end_pending_ = true;
    // At the end of the pass, as if played through: the frame held (sent again after an edit) is
    // the last, and a bag opened next plays from its start, not from where this pass was cut
    // (open() keeps a position inside the bag).
    current_ = last_;
    updateParam(kFrame.name(), last_);
    updateParam(kTime.name(), (frames_[last_].start - frames_.front().start).toSec());
    notifyNewData();
  }
  void previous() { request(std::max((request_ >= 0 ? request_ : current_) - 1, 0)); }

 private:
  void open() {
    opened_ = true;
    end_pending_ = false;
    closeBag(bag_);
    frames_.clear();
    current_ = request_ = -1;
    open_error_.clear();
    const std::string file = file_.get();
    if (file.empty()) return;
    try {
      bag_ = openBag(file);
    } catch (const std::exception& e) {
      open_error_ = e.what();  // also for the firings to come: "playing" must not make it look fine
      throw;
    }
    ports_.clear();
    played_topics_.clear();
    for (const auto& [port, topic] : playedTopics(topics_.get(), image_topic_.get(), cloud_topic_.get())) {
      ports_[topic] = port;
      played_topics_.push_back(topic);
    }
    frames_ = indexFrames(*bag_, played_topics_, sync_window_.get());
    std::string missing;
    const auto types = topicTypes(*bag_);
    for (const auto& t : played_topics_)
      if (!types.count(t)) missing += (missing.empty() ? "" : ", ") + t;
    if (!missing.empty()) log(apex::LogLevel::Warn, "bag '" + file + "' has no topic " + missing);
    playRange();
    const int asked = frame_.get();
    const bool show = seek_on_open_ && !playing_.get();
    seek_on_open_ = false;
    // Playing from a position saved at the end of a pass starts over; paused on a frame shows it.
    next_ = asked > first_ && asked < last_ ? asked : playing_.get() ? first_ : std::min(asked, last_);
    if (show) seek(asked);
    wake();
  }
  /** first_/last_ from `start` and `end`, as frame indices. */
  void playRange() {
    first_ = 0;
    last_ = static_cast<int>(frames_.size()) - 1;
    if (frames_.empty()) return;
    const ros::Time begin = frames_.front().start;
    const double start = start_.get(), end = end_.get();
    while (first_ < last_ && (frames_[first_].start - begin).toSec() < start) ++first_;
    if (end > 0)
      while (last_ > first_ && (frames_[last_].start - begin).toSec() > end) --last_;
  }
  void seek(int k) {
    if (!bag_) return;
    if (k >= static_cast<int>(frames_.size()))
      throw std::invalid_argument("frame " + std::to_string(k) + " is past the bag's last frame " +
                                  std::to_string(frames_.size() - 1));
    next_ = k;
    request(k);
  }
  /** The first frame at or after `seconds` into the bag (binary search), the last if none. */
  int frameAt(double seconds) const {
    const ros::Time t = frames_.front().start + ros::Duration(std::max(0.0, seconds));
    auto it =
        std::lower_bound(frames_.begin(), frames_.end(), t, [](const BagFrame& f, const ros::Time& at) { return f.start < at; });
    return static_cast<int>(std::min<std::ptrdiff_t>(it - frames_.begin(), frames_.size() - 1));
  }
  void request(int k) {
    if (k < 0 || !bag_) return;
    request_ = k;
    again_ = false;
    notifyNewData();
  }
  void wake() {
    due_ = std::chrono::steady_clock::now();
    if (playing_.get()) notifyNewData();
  }
  /** Publishes frame k: every played topic's message in it, the index and the stamp. */
  void send(int k) {
    current_ = k;
    const BagFrame& f = frames_[k];
    updateParam(kFrame.name(), k);
    updateParam(kTime.name(), (f.start - frames_.front().start).toSec());
    const ros::WallTime wall = ros::WallTime::now();
    const ros::Time now(wall.sec, wall.nsec);  // the clock latencies are measured on
    for (const rosbag::MessageInstance& m : rosbag::View(*bag_, rosbag::TopicQuery(played_topics_), f.start, f.end)) {
      auto port = ports_.find(m.getTopic());
      if (port == ports_.end()) continue;
      publishMessage(port->second, toPort(readMessage(m, restamp_.get() ? &now : nullptr)));
    }
    stamp_.publish(f.start.toSec());
  }
  void schedule(int sent) {
    const double rate = rate_.get();
    if (rate <= 0) {
      due_ = std::chrono::steady_clock::now();
      return notifyNewData();
    }
    const double gap = std::max(0.0, (frames_[next_].start - frames_[sent].start).toSec()) / rate;
    due_ = std::chrono::steady_clock::now() +
           std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(gap));
    notifyAfter(gap);
  }

  // The fixed ports and parameters; the outputs of the played topics are read by name (shapeOutputs).
  apex::Output<double> stamp_{this, kStamp};
  apex::Trigger finished_{this, kFinished};
  apex::Param<std::string> file_{this, kFile};
  apex::Param<std::vector<std::string>> topics_{this, kTopics};
  apex::Param<std::string> image_topic_{this, kImageTopic};
  apex::Param<std::string> cloud_topic_{this, kCloudTopic};
  apex::Param<double> sync_window_{this, kSyncWindow};
  apex::Param<bool> playing_{this, kPlaying};
  apex::Param<double> rate_{this, kRate};
  apex::Param<bool> loop_{this, kLoop};
  apex::Param<bool> restamp_{this, kRestamp};
  apex::Param<double> start_{this, kStart};
  apex::Param<double> end_{this, kEnd};
  apex::Param<int> frame_{this, kFrame};
  apex::Param<double> time_{this, kTime};

  std::unique_ptr<rosbag::Bag> bag_;
  std::vector<std::string> played_topics_;
  std::map<std::string, std::string> ports_;  // topic → output
  std::vector<BagFrame> frames_;
  int first_ = 0, last_ = -1;  // the play range
  int current_ = -1;  // the frame sent last (held while paused)
  int next_ = 0;  // the frame playing sends next
  int request_ = -1;  // a frame asked for by a seek, a slot or a change downstream
  bool again_ = false;  // request_ is the held frame sent again after a change downstream
  bool opened_ = false;
  std::string open_error_;  // why the file did not open ("" if it did, or there is none)
  bool seek_on_open_ = false;
  bool end_pending_ = false;  // the last frame of a pass went out: the end-of-sequence token follows
  std::chrono::steady_clock::time_point due_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::BagReader, "apex_nodes/BagReader");
