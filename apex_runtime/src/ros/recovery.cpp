#include "recovery.hpp"

#include <ros/console.h>
#include <sys/stat.h>

#include <apex/Recovery.h>

#include <filesystem>
#include <memory>

#include "apex/core/graph_file.hpp"
#include "request_text.hpp"

namespace apex {
namespace ros_host {
namespace {

namespace fs = std::filesystem;

/** What a copy holds, for the offer: its time and its nodes. */
Recovery::Offer describeCopy(const std::string& path) {
  Recovery::Offer offer;
  offer.path = path;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) offer.written_ns = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  auto text = readGraphFile(path);
  auto graph = text ? parseGraphText(text.value()) : Result<GraphDescription>(text.status());
  if (graph) offer.nodes = graph.value().nodes.size();
  else ROS_WARN_STREAM_NAMED("apex", "the unsaved graph a previous run left does not read: " << graph.message());
  return offer;
}

}  // namespace

Recovery::Recovery(const std::string& folder, const std::string& node, Timing timing)
    : path_(folder + "/" + fileName(node) + ".yaml"),
      offered_path_(folder + "/" + fileName(node) + ".previous.yaml"),
      timing_(timing) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (fs::exists(path_, ec)) {  // the previous run died with unsaved edits: aside, so ours do not replace them
    fs::rename(path_, offered_path_, ec);
    if (ec)
      ROS_WARN_STREAM_NAMED("apex", "cannot set aside " << path_ << " (" << ec.message() << "): this run's edits replace it");
  }
  if (fs::exists(offered_path_, ec)) {
    offer_ = describeCopy(offered_path_);
    ROS_WARN_STREAM_NAMED("apex", "a previous run left an unsaved graph (" << offer_->nodes << " nodes) in " << offered_path_
                                                                           << ": restore or discard it with ~recovery");
  }
}

std::string Recovery::fileName(const std::string& node) {
  std::string name = node.substr(node.find_first_not_of('/') == std::string::npos ? node.size() : node.find_first_not_of('/'));
  for (char& c : name)
    if (c == '/') c = '_';
  return name.empty() ? "apex" : name;
}

void Recovery::saved(const Snapshot& graph) {
  std::lock_guard<std::mutex> lock(mutex_);
  saved_ = graph.text;
  seen_revision_ = graph.revision;  // a later edit is one the file does not have
  pending_ = false;
  unsaved_ = false;
  removeOwn();
}

void Recovery::tick(std::uint64_t revision, const std::function<Snapshot()>& snapshot, Clock::time_point now) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (closed_) return;
  if (revision != seen_revision_) {
    seen_revision_ = revision;
    last_change_ = now;
    if (!pending_) pending_ = true, first_change_ = now;
  }
  if (!pending_ || (now - last_change_ < timing_.quiet && now - first_change_ < timing_.at_most)) return;
  pending_ = false;
  const Snapshot graph = snapshot();
  unsaved_ = graph.nodes > 0 && !(saved_ && *saved_ == graph.text);  // what the copy keeps
  if (graph.nodes == 0 || (saved_ && *saved_ == graph.text)) return removeOwn();  // nothing unsaved to lose
  if (graph.text != written_) write(graph);
}

void Recovery::write(const Snapshot& graph) {
  if (const Status st = writeFileAtomically(path_, graph.text); !st) {
    if (!warned_)  // once: the next bursts try again, quietly, until one succeeds
      ROS_WARN_STREAM_NAMED("apex", "cannot keep the recovery copy of the graph: "
                                        << st.message() << "; unsaved edits are lost if the runtime dies");
    warned_ = true;
    return;
  }
  written_ = graph.text;
  warned_ = false;
}

void Recovery::removeOwn() {
  if (!written_) return;
  std::error_code ec;
  fs::remove(path_, ec);
  if (ec) ROS_WARN_STREAM_NAMED("apex", "cannot remove the recovery copy " << path_ << ": " << ec.message());
  written_.reset();
}

bool Recovery::unsaved() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return unsaved_;
}

void Recovery::close() {
  std::lock_guard<std::mutex> lock(mutex_);
  closed_ = true;
  removeOwn();
}

std::optional<Recovery::Offer> Recovery::offer() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return offer_;
}

Status Recovery::adopt() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!offer_) return Status::error("no unsaved graph of a previous run is offered");
  std::error_code ec;
  fs::rename(offered_path_, path_, ec);  // at once: a crash before the next tick loses nothing
  if (ec) return Status::error("cannot move " + offered_path_ + " to " + path_ + ": " + ec.message());
  offer_.reset();
  saved_.reset();  // in no file of the user's: unsaved until a save
  written_ = "";  // ours now; written again in this run's form at the next tick
  pending_ = true, first_change_ = last_change_ = Clock::now();
  return Status::ok();
}

Status Recovery::discard() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!offer_) return Status::error("no unsaved graph of a previous run is offered");
  std::error_code ec;
  fs::remove(offered_path_, ec);
  if (ec) return Status::error("cannot delete " + offered_path_ + ": " + ec.message());
  offer_.reset();
  return Status::ok();
}

ros::ServiceServer serveRecovery(ros::NodeHandle& pnh, Recovery& recovery,
                                 std::function<bool(LoadGraph::Request&, LoadGraph::Response&)> load) {
  auto busy = std::make_shared<std::mutex>();  // one restore or discard at a time: a copy is loaded once
  auto handle = [&recovery, load, busy](apex::Recovery::Request& req, apex::Recovery::Response& res) {
    std::lock_guard<std::mutex> lock(*busy);
    const auto offer = recovery.offer();
    if (offer) {
      res.path = offer->path;
      res.written.fromNSec(std::uint64_t(offer->written_ns));
      res.nodes = static_cast<std::uint32_t>(offer->nodes);
    }
    res.offered = offer.has_value();
    Status st = Status::ok();
    if (req.action == "restore" || req.action == "discard") {
      if (!offer) {
        st = Status::error("no unsaved graph of a previous run is offered");
      } else if (req.action == "discard") {
        st = recovery.discard();
      } else {
        LoadGraph::Request load_req;
        load_req.path = offer->path;
        LoadGraph::Response load_res;
        load(load_req, load_res);
        res.warnings = load_res.warnings, res.revision = load_res.revision;
        st = load_res.success ? recovery.adopt() : Status::error("cannot restore " + offer->path + ": " + load_res.message);
      }
      res.offered = recovery.offer().has_value();
    } else if (!req.action.empty() && req.action != "keep") {
      st = Status::error("unknown action '" + req.action + "' (actions: keep, restore, discard)");
    }
    res.success = st.isOk();
    res.message = st.isOk() ? "" : st.message();
    return true;  // the call itself worked; `success` says whether the action did
  };
  return advertiseChecked<apex::Recovery::Request, apex::Recovery::Response>(pnh, "recovery", handle);
}

}  // namespace ros_host
}  // namespace apex
