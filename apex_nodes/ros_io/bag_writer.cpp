// BagWriter: a bag recorder. One input per recorded topic, of any type that has a
// ROS message (apex/ros/inspect.hpp: images, clouds, scans, transforms, numbers,
// text, and the image library's results as this package's messages: regions, contours,
// keypoints, matches... (ros_results.hpp)); each message is written with its own header stamp as its record time
// (a message without one takes the firing's newest stamp, else the clock), so
// BagReader plays back the frames that were recorded. As `rosbag record` does, the
// file is written as <file>.active and renamed when it is closed (stop, the end of a
// pass, a new file name, the node's removal): a crash never leaves a half-written
// bag under the name. With split_size, files are <stem>_0.bag, <stem>_1.bag, ...
#include <topic_tools/shape_shifter.h>

#include <boost/make_shared.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <memory>

#include "apex/core/registry.hpp"
#include "apex/ros/inspect.hpp"
#include "bag_frames.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** One optional input of any type per topic, named as BagReader names its outputs. */
apex::Status shapeInputs(const apex::ParamValues& p, apex::Manifest& m) {
  std::vector<apex::PortSpec> inputs;
  std::map<std::string, std::string> topic_of;  // input → its topic
  for (const auto& topic : p.get<std::vector<std::string>>("topics")) {
    if (topic.empty()) return apex::Status::error("an empty topic name");
    const std::string port = portForTopic(topic);
    if (auto [it, added] = topic_of.emplace(port, topic); !added)
      return apex::Status::error("topics '" + it->second + "' and '" + topic + "' both make input '" + port + "'");
    inputs.push_back({port, apex::typeOf<apex::Any>(), true, "recorded on " + topic});
  }
  m.inputs.insert(m.inputs.begin(), inputs.begin(), inputs.end());
  return apex::Status::ok();
}

ros::Time clockNow() {
  if (ros::Time::isValid()) return ros::Time::now();
  const ros::WallTime w = ros::WallTime::now();
  return ros::Time(w.sec, w.nsec);
}

}  // namespace

class BagWriter : public apex::Node {
 public:
  static inline const apex::ParamDecl<std::string> kFile = param::path("file")
                                                               .init("/tmp/apex_record.bag")
                                                               .describe("the bag; written as <file>.active until it is closed")
                                                               .mode(apex::PathMode::Write);
  static inline const apex::ParamDecl<std::vector<std::string>> kTopics =
      param::textList("topics")
          .init({"/camera/image_raw"})
          .describe("topics to record, one input each (/camera/image_raw: input camera_image_raw)")
          .shapesInterface();
  static inline const apex::ParamDecl<double> kSplitSize =
      param::number("split_size")
          .range(0.0, 1e6)
          .step(1.0)
          .describe(
              "MB (of 1,048,576 bytes, as rosbag record): when a file grows past this, the next "
              "one starts; files are <stem>_0.bag, <stem>_1.bag, ...; 0: one file");
  static inline const apex::ParamDecl<bool> kRecording =
      param::flag("recording").init(true).describe("the start and stop slots set it; off closes the file");
  static inline const apex::ParamDecl<bool> kOverwrite =
      param::flag("overwrite").describe("replace a bag this node did not record");
  static inline const apex::ParamDecl<bool> kStopAtEnd =
      param::flag("stop_at_end")
          .init(true)
          .describe(
              "the end of a pass (e.g. a BagReader's last frame) stops recording, so the file is "
              "complete when the bag has played once");
  static apex::Manifest manifest() {
    return apex::Manifest("Records its inputs into a bag: one input per topic, each message at its own stamp")
        .inCategory("ROS I/O")
        .keepsState("the bag it records: a re-run records the held frame again")
        .slot("start", &BagWriter::start, "start recording (a new file: an old one of that name is replaced)")
        .slot("stop", &BagWriter::stop, "stop recording and close the file")
        .param(kFile)
        .param(kTopics)
        .param(kSplitSize)
        .param(kRecording)
        .param(kOverwrite)
        .param(kStopAtEnd)
        .shapedBy(shapeInputs);
  }
  ~BagWriter() override {
    try {
      close();
    } catch (...) {  // nothing to report to from here; the .active file stays for rosbag reindex
    }
  }

  void parameterChanged(const std::string& name) override {
    if (name == "file" || name == "split_size" || (name == "recording" && !recording_.get())) close();
    if (name == "file" || (name == "recording" && recording_.get())) part_ = 0;
  }
  void endOfSequence() override {
    if (stop_at_end_.get() && recording_.get()) stop();
  }

  void process() override {
    if (!recording_.get()) return;
    std::vector<std::pair<std::string, apex::SerializedMessage>> messages;  // (topic, message)
    ros::Time newest;
    for (const auto& topic : topics_.get()) {
      const apex::Message& m = inputMessage(portForTopic(topic));
      if (m.isNothing()) continue;
      const apex::Inspector inspector = apex::findInspector(m.type());
      if (!inspector.serialize) {
        std::string types;
        for (const auto& t : apex::inspectedTypes()) types += (types.empty() ? "" : ", ") + t;
        throw std::invalid_argument("input '" + portForTopic(topic) + "' carries " + m.typeName() +
                                    ", which has no ROS message to record (these types have one: " + types + ")");
      }
      messages.emplace_back(topic, inspector.serialize(m));
      newest = std::max(newest, messages.back().second.stamp);
    }
    // A held frame sent again (a paused player, after an edit downstream) is recorded once.
    messages.erase(
        std::remove_if(messages.begin(), messages.end(),
                       [&](const auto& tm) { return !tm.second.stamp.isZero() && last_stamp_[tm.first] == tm.second.stamp; }),
        messages.end());
    if (messages.empty()) return;
    if (newest.isZero()) newest = clockNow();
    if (!bag_) open();
    for (const auto& [topic, m] : messages) {
      write(topic, m, m.stamp.isZero() ? newest : m.stamp);
      last_stamp_[topic] = m.stamp;
    }
    const double split = split_size_.get();
    if (split > 0 && bag_->getSize() > split * 1048576.0) close();  // MB as rosbag record counts them
  }

  void start() {
    close();
    part_ = 0;
    if (!recording_.get()) updateParam(kRecording.name(), true);
  }
  void stop() {
    close();
    if (recording_.get()) updateParam(kRecording.name(), false);
  }

 private:
  /** The file being written now: `file`, or with split_size its part's <stem>_<k>.bag. */
  std::string target() const {
    if (split_size_.get() <= 0) return file_.get();
    const std::filesystem::path file(file_.get());
    return (file.parent_path() / (file.stem().string() + "_" + std::to_string(part_) + ".bag")).string();
  }
  void open() {
    const std::string path = target();
    if (!created_.count(path) && !overwrite_.get()) {  // another recording's, or the user's
      if (std::filesystem::exists(std::filesystem::symlink_status(path)))
        throw std::runtime_error("'" + path + "' exists (not recorded by this node): left as it is; set 'overwrite' " +
                                 "to replace it, or choose another file");
      if (std::filesystem::exists(std::filesystem::symlink_status(path + ".active")))
        throw std::runtime_error("'" + path + ".active' exists: a recording that did not finish (rosbag reindex " +
                                 "recovers it); left as it is: move it away, or set 'overwrite'");
    }
    path_ = path;
    part_open_ = split_size_.get() > 0;
    bag_ = createBag(path_ + ".active");
    created_.insert(path_);
  }
  /** Closes the file and gives it its name; a part moves on to the next part first, so that a
   *  failure here never has the next frame write over this part. */
  void close() {
    if (!bag_) return;
    if (part_open_) ++part_;
    closeBag(bag_);
    std::error_code ec;
    std::filesystem::rename(path_ + ".active", path_, ec);
    if (ec) throw std::runtime_error("cannot rename '" + path_ + ".active' to '" + path_ + "': " + ec.message());
  }
  void write(const std::string& topic, const apex::SerializedMessage& m, const ros::Time& at) {
    topic_tools::ShapeShifter message;
    message.morph(m.md5sum, m.datatype, m.definition, "");
    ros::serialization::IStream stream(const_cast<std::uint8_t*>(m.bytes.data()), static_cast<std::uint32_t>(m.bytes.size()));
    message.read(stream);
    // One connection per topic and type: an input reconnected to another type mid-recording
    // gets a connection of its own, not the first type's definition.
    auto header = boost::make_shared<ros::M_string>();
    (*header)["topic"] = topic;
    (*header)["type"] = m.datatype;
    (*header)["md5sum"] = m.md5sum;
    (*header)["message_definition"] = m.definition;
    (*header)["callerid"] = "/apex";
    (*header)["latching"] = "0";
    try {
      bag_->write(topic, std::max(at, ros::TIME_MIN), message, header);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("cannot write to bag '" + path_ + ".active': " + e.what());
    }
  }

  apex::Param<std::string> file_{this, kFile};
  apex::Param<std::vector<std::string>> topics_{this, kTopics};
  apex::Param<double> split_size_{this, kSplitSize};
  apex::Param<bool> recording_{this, kRecording};
  apex::Param<bool> stop_at_end_{this, kStopAtEnd};
  apex::Param<bool> overwrite_{this, kOverwrite};

  std::unique_ptr<rosbag::Bag> bag_;
  std::string path_;  // the file bag_ becomes when closed
  bool part_open_ = false;  // bag_ is one of split_size's parts
  int part_ = 0;  // with split_size: the part written next
  std::map<std::string, ros::Time> last_stamp_;  // topic → the stamp recorded last
  std::set<std::string> created_;  // files this node recorded: `start` records them anew
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::BagWriter, "apex_nodes/BagWriter");
