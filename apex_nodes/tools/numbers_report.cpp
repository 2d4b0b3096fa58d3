// The number-sign demo's driver (scripts/demo --numbers, launch/numbers.launch): plays the bag
// through the runtime's graph once, through its services as a user would with rosservice, and
// reports what the graph's end-of-pass outputs say.
//   apex_numbers_report export     graphs/export_samples.yaml: how many samples were written
//   apex_numbers_report classify   graphs/number_signs.yaml: detection F1, digit accuracy, the
//                                  confusion matrix and the classifier's time; "numbers: OK" if
//                                  the accuracy is at least 95%
#include <apex/RuntimeStatus.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <map>
#include <mutex>

#include "runtime_client.hpp"

namespace {

constexpr double kRequiredAccuracy = 0.95;

/** The first message of each inspected output (each comes once, at the end of the pass), and the
 *  latest ~status. */
class Results {
 public:
  explicit Results(ros::NodeHandle& nh) : nh_(nh) {
    status_sub_ = nh.subscribe<apex::RuntimeStatus>("/apex/status", 1, [this](const apex::RuntimeStatus::ConstPtr& s) {
      std::lock_guard<std::mutex> l(m_);
      status_ = *s;
    });
  }
  template <class Msg>
  void watch(const std::string& node, const std::string& port) {
    const std::string key = node + "/" + port;
    subs_.push_back(nh_.subscribe<Msg>(apex_tools::inspect(node, port), 1, [this, key](const typename Msg::ConstPtr& m) {
      std::lock_guard<std::mutex> l(m_);
      std::string text;
      if constexpr (std::is_same_v<Msg, std_msgs::String>) text = m->data;
      else text = std::to_string(m->data);
      values_.emplace(key, text);
      cv_.notify_all();
    }));
  }
  /** Waits until every watched output has sent. */
  bool wait(double seconds) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::duration<double>(seconds), [&] {
      return values_.size() == subs_.size() || !ros::ok();
    }) && ros::ok();
  }
  /** Waits until every inspect topic is connected. */
  void connect() {
    for (auto& s : subs_)
      while (s.getNumPublishers() == 0 && ros::ok()) ros::WallDuration(0.01).sleep();
  }
  std::string text(const std::string& key) {
    std::lock_guard<std::mutex> l(m_);
    return values_.count(key) ? values_.at(key) : "";
  }
  double number(const std::string& key) { return std::atof(text(key).c_str()); }
  apex::RuntimeStatus status() {
    std::lock_guard<std::mutex> l(m_);
    return status_;
  }

 private:
  ros::NodeHandle& nh_;
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber status_sub_;
  std::map<std::string, std::string> values_;
  apex::RuntimeStatus status_;
};

/** The nodes in an error state, with their messages, on one line (": a: ...; b: ..."); empty if none. */
std::string errors() {
  std::string out;
  for (const auto& n : apex_tools::graph().nodes)
    if (n.state == "error") out += (out.empty() ? ": " : "; ") + n.name + ": " + n.error;
  return out;
}

const apex::NodeStatus* statusOf(const apex::RuntimeStatus& s, const std::string& node) {
  for (const auto& n : s.nodes)
    if (n.name == node) return &n;
  return nullptr;
}

int reportExport(Results& r) {
  const int samples = static_cast<int>(r.number("export/samples"));
  const std::string failed = errors();
  std::printf("exported: %d labelled samples in %s\n", samples,
              apex_tools::valueOf(apex_tools::graph(), "export", "directory").c_str());
  if (!failed.empty() || samples == 0) std::printf("export: FAILED%s\n", failed.c_str());
  return failed.empty() && samples > 0 ? 0 : 1;
}

int reportClassify(Results& r) {
  ros::WallDuration(0.6).sleep();  // one more ~status (2 Hz) with the whole pass in it
  const double accuracy = r.number("digits/accuracy");
  const int matched = static_cast<int>(r.number("digits/matched")), regions = static_cast<int>(r.number("digits/regions"));
  std::printf("detection:      F1 %.3f (mean over the frames)\n", r.number("f1/mean"));
  std::printf("digits:         accuracy %.3f over the %d signs found (%d regions)\n", accuracy, matched, regions);
  std::printf("confusion matrix (a row per true digit, a column per label; ?: rejected):\n%s\n",
              r.text("digits/confusion").c_str());
  const auto status = r.status();
  if (const auto* c = statusOf(status, "classify"); c && regions > 0)
    std::printf("classification: %.3f ms per frame, %.1f us per region (the classify node, mean over %lu frames)\n", c->mean_ms,
                1000.0 * c->mean_ms * c->firings / regions, static_cast<unsigned long>(c->firings));
  const std::string failed = errors();
  const bool ok = failed.empty() && matched > 0 && accuracy >= kRequiredAccuracy;
  if (ok) std::printf("numbers: OK\n");
  else if (!failed.empty()) std::printf("numbers: FAILED%s\n", failed.c_str());
  else std::printf("numbers: FAILED: the digit accuracy is below %.2f\n", kRequiredAccuracy);
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "apex_numbers_report");
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode != "export" && mode != "classify") {
    std::fprintf(stderr, "usage: apex_numbers_report export|classify\n");
    return 2;
  }
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  try {
    Results r(nh);
    if (mode == "export") {
      r.watch<std_msgs::Int32>("export", "samples");
    } else {
      r.watch<std_msgs::Float64>("f1", "mean");
      r.watch<std_msgs::Float64>("digits", "accuracy");
      r.watch<std_msgs::Int32>("digits", "matched");
      r.watch<std_msgs::Int32>("digits", "regions");
      r.watch<std_msgs::String>("digits", "confusion");
    }
    r.connect();
    apex_tools::set("bag", "playing", "true");  // only now: no result is sent before we listen
    // The pass ends with the results; a player that cannot play (e.g. its bag is unreadable) ends it sooner.
    for (int waited = 0; !r.wait(2); waited += 2) {
      if (!ros::ok()) throw std::runtime_error("interrupted");
      if (apex_tools::nodeIn(apex_tools::graph(), "bag").state == "error" || waited >= 600)
        throw std::runtime_error((waited >= 600 ? "the pass did not end within 600 s" : "the bag does not play") + errors());
    }
    const int rc = mode == "export" ? reportExport(r) : reportClassify(r);
    std::fflush(stdout);
    return rc;
  } catch (const std::exception& e) {
    std::printf("%s: FAILED: %s\n", mode == "export" ? "export" : "numbers", e.what());
    std::fflush(stdout);
    return 1;
  }
}
