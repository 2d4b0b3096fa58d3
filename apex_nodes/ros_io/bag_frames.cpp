#include "bag_frames.hpp"

#include <cctype>
#include <filesystem>
#include <mutex>
#include <set>
#include <stdexcept>

#include "shared_image_transport.hpp"

namespace apex_nodes {

namespace {

/** A bag opened in `mode`; a failure is std::invalid_argument "cannot <verb> bag '<file>': why". */
std::unique_ptr<rosbag::Bag> openIn(const std::string& file, rosbag::bagmode::BagMode mode, const char* verb) {
  // rosbag loads its encryptor plugins through pluginlib when a bag opens: under the node
  // library's plugin lock, or another thread group's image_transport set-up crashes the process.
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  auto bag = std::make_unique<rosbag::Bag>();
  try {
    bag->open(file, mode);
  } catch (const rosbag::BagException& e) {
    throw std::invalid_argument(std::string("cannot ") + verb + " bag '" + file + "': " + e.what());
  }
  return bag;
}

}  // namespace

std::unique_ptr<rosbag::Bag> openBag(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::invalid_argument("cannot open bag '" + file +
                                "': " + (std::filesystem::exists(file, ec) ? "not a regular file" : "no such file"));
  return openIn(file, rosbag::bagmode::Read, "open");
}

std::unique_ptr<rosbag::Bag> createBag(const std::string& file) { return openIn(file, rosbag::bagmode::Write, "write"); }

void closeBag(std::unique_ptr<rosbag::Bag>& bag) {
  std::lock_guard<std::mutex> lock(pluginLoaderMutex());
  if (!bag) return;
  try {
    bag->close();  // here, not in the destructor: a failure to write the index (a full disk) throws
  } catch (const std::exception& e) {
    const std::string file = bag->getFileName();
    (void)bag.release();  // its destructor would try again and throw where nothing can catch it
    throw std::runtime_error("cannot close bag '" + file + "': " + e.what());
  }
  bag.reset();
}

std::map<std::string, std::string> topicTypes(rosbag::Bag& bag) {
  std::map<std::string, std::string> out;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) out[c->topic] = c->datatype;
  return out;
}

std::vector<BagFrame> indexFrames(rosbag::Bag& bag, const std::vector<std::string>& topics, double window) {
  std::vector<BagFrame> frames;
  std::set<std::string> in_frame;
  const ros::Duration span(window);
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topics))) {
    const ros::Time t = m.getTime();  // from the index: no message is read
    if (frames.empty() || t - frames.back().start > span || !in_frame.insert(m.getTopic()).second) {
      frames.push_back({t, t});
      in_frame = {m.getTopic()};
    }
    frames.back().end = t;
  }
  return frames;
}

std::shared_ptr<const RosMessage> readMessage(const rosbag::MessageInstance& m, const ros::Time* stamp) {
  auto out = std::make_shared<RosMessage>();
  out->datatype = m.getDataType();
  out->md5sum = m.getMD5Sum();
  out->definition = m.getMessageDefinition();
  out->bytes.resize(m.size());
  ros::serialization::OStream stream(out->bytes.data(), static_cast<std::uint32_t>(out->bytes.size()));
  m.write(stream);
  if (stamp) out->setStamp(*stamp);
  return out;
}

std::string portForTopic(const std::string& topic) {
  std::string out;
  for (char c : topic) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    if (!ok && (out.empty() || out.back() == '_')) continue;  // no leading or doubled separators
    out += ok ? c : '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "topic_" + out;
  return out;
}

}  // namespace apex_nodes
