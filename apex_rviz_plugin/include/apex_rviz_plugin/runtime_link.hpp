// The panel's only contact with a runtime: its latched ~graph and its ~status
// (received on a spinner of their own), and its services, called in order on a
// worker thread. Every result comes back on the GUI thread, as a signal or a
// callback; nothing here blocks the thread that created the link.
#pragma once

#include <QImage>
#include <QMetaObject>
#include <QObject>
#include <QTimer>

#include <apex/Balance.h>
#include <apex/GraphState.h>
#include <apex/GetNodeProfile.h>
#include <apex/NodeTypeInfo.h>
#include <apex/Recovery.h>
#include <apex/RuntimeStatus.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "apex_rviz_plugin/graph_model.hpp"
#include "apex_rviz_plugin/job_thread.hpp"

namespace apex_rviz_plugin {

/** @brief Whether a graph came from a runtime: every runtime's has its default thread group (a
 *  runtime that changed nothing yet answers at revision 0, as an unanswered call reads). */
inline bool answered(const apex::GraphState& g) { return !g.thread_groups.empty(); }

class RuntimeLink : public QObject {
  Q_OBJECT
 public:
  using Done = std::function<void(bool ok, const std::string& message)>;

  explicit RuntimeLink(QObject* parent = nullptr);
  ~RuntimeLink() override;

  /** @brief The runtime to talk to, e.g. "/apex"; subscribes anew. False if it is the current one. */
  bool setNamespace(const std::string& ns);
  const std::string& ns() const { return ns_; }
  /** @brief Its topics are there and it speaks (its ~status comes). */
  bool connected() const { return connected_ && !silent_; }
  /** @brief A heartbeat (~status) came from this runtime since the link was made: only then can its
   *  silence say it is gone (one that never sent any is taken at its topics' word). */
  bool heardFrom() const { return heard_ != std::chrono::steady_clock::time_point{}; }

  /** @brief Makes the calls in order, stopping at the first refused one; `done` gets its message. */
  void run(std::vector<Call> calls, Done done);
  /** @brief As run, then reads the graph (get_graph): `done` also gets the graph as the runtime
   *  had it right after the calls (an empty GraphState if it did not answer: see answered()). */
  void runThenRead(std::vector<Call> calls, std::function<void(bool, const std::string&, const apex::GraphState& after)> done);
  void listTypes(std::function<void(bool, const std::string&, const std::vector<apex::NodeTypeInfo>&)> done);
  void control(const std::string& command, Done done);
  void saveGraph(const std::string& path, Done done);
  /** ~trace: `command` start, stop or save (the last `seconds`, 0 all, to `path`); `done` gets the
   *  answer's message and whether the runtime traces now. */
  void trace(const std::string& command, const std::string& path, double seconds,
             std::function<void(bool, const std::string&, bool tracing)> done);
  /** `done` also gets the loaded graph's revision: the ~graph with it or a later one shows that graph. */
  void loadGraph(const std::string& path, std::function<void(bool, const std::string&, std::uint64_t revision)> done);
  void fireSlot(const std::string& node, const std::string& slot, Done done);
  /** @brief ~recovery with `action` (keep, restore, discard): `done` gets the unsaved graph a
   *  previous run left, as the runtime reports it after the action. */
  void recovery(const std::string& action, std::function<void(bool, const std::string&, const apex::Recovery::Response&)> done);
  /** @brief ~balance: thread groups proposed for a pipeline over `groups` cores (0: the runtime's
   *  cores) from the node times measured so far (`frames` 0) or over `frames` new frames; `done`
   *  gets the proposal. Only proposes: the panel applies it as an edit of its own. */
  void balance(int frames, int groups, std::function<void(bool, const std::string&, const apex::Balance::Response&)> done);
  /** @brief ~node_profile: `node`'s histograms of firing time and latency. */
  void profile(const std::string& node,
               std::function<void(bool, const std::string&, const apex::GetNodeProfile::Response&)> done);
  /** @brief Asks the runtime to publish a port; `done` gets the topic and its message type. */
  void inspect(const std::string& node, const std::string& port,
               std::function<void(bool, const std::string& message, const std::string& topic, const std::string& type)> done,
               bool preview = false);
  /** @brief Shows a port's previews (inspect with preview) as they come: images as
   *  imageReceived (with what each was, e.g. its real size, as aboutReceived), numbers as
   *  scalarReceived. Until unwatchPreview. */
  void watchPreview(const std::string& node, const std::string& port, const std::string& topic, const std::string& type);
  void unwatchPreview(const std::string& node, const std::string& port);
  /** @brief Shows a port's whole images (an inspection's topic, sensor_msgs/Image) as they come,
   *  as frameReceived: for labelling them (LabelView). One subscription per port, until
   *  unwatchFrames. */
  void watchFrames(const std::string& node, const std::string& port, const std::string& topic);
  void unwatchFrames(const std::string& node, const std::string& port);
  bool watchingPreview(const std::string& node, const std::string& port) const {
    return preview_subs_.count(node + "/" + port) > 0;
  }
  /** @brief Shows the values of a scalar inspection topic (std_msgs) as scalarReceived; one
   *  subscription per port (watched again, e.g. after a Load: the old one is replaced). */
  void watchScalar(const std::string& node, const std::string& port, const std::string& topic, const std::string& type);
  /** @brief Whether a scalar watched on `topic` is connected to its publisher (messages come). */
  bool receiving(const std::string& topic) const;
  std::size_t scalarWatches() const { return scalar_subs_.size(); }
  /** @brief Whether calls to runtimes left behind are still running or waiting (their answers are dropped). */
  bool callsLeftBehind() const {
    for (const auto& j : retired_)
      if (!j->finished()) return true;
    return false;
  }

 signals:
  void graphReceived(const apex::GraphState& graph);
  void statusReceived(const apex::RuntimeStatus& status);
  /** The runtime appeared (up) or is gone; `text` says which, for the user. */
  void connectionChanged(bool up, const QString& text);
  /** The runtime sent no ~status (its heartbeat, twice a second) for over a second: killed or stuck
   *  (a killed process leaves its topics registered), or it speaks again; `text` says which. */
  void silenceChanged(bool silent, const QString& text);
  /** Another runtime answers at the namespace (its ~status says it started anew): what the panel
   *  knew of the one before (its graph, the history, previews) no longer applies. */
  void runtimeReplaced();
  /** A call has waited more than a second for its answer (or the answer came): what to show. */
  void answerOverdue(const QString& text);
  void scalarReceived(const QString& node, const QString& port, const QString& text);
  void imageReceived(const QString& node, const QString& port, const QImage& image);
  void aboutReceived(const QString& node, const QString& port, const QString& text);
  /** A whole image of a port watched with watchFrames: `image` null for an encoding not drawn here
   *  (bgr8, rgb8, mono8 and bgra8 are), `stamp` its header's (ns). */
  void frameReceived(const QString& node, const QString& port, const QImage& image, quint64 stamp, const QString& encoding);

 private:
  /** Runs `work` on the job thread and `then` with its result on the GUI thread. */
  template <class T>
  void async(std::function<T()> work, std::function<void(const T&)> then);
  /** A call of service `Srv` on the worker thread; `done` gets success, the message and the answer. */
  template <class Srv>
  void callWithAnswer(const std::string& service_name, typename Srv::Request req,
                      std::function<void(bool, const std::string&, const typename Srv::Response&)> done);
  /** Calls one service off the GUI thread; `done` gets success and message. */
  template <class Srv>
  void callOne(const std::string& name, const typename Srv::Request& req, Done done);
  void checkConnection();
  /** Runs `fn` on the GUI thread, if the link still talks to the runtime it talked to at `gen`
   *  (a late answer or message from a runtime left behind is dropped). Any thread. */
  template <class F>
  void deliver(std::uint64_t gen, F fn) {
    QMetaObject::invokeMethod(
        this,
        [this, gen, fn = std::move(fn)] {
          if (gen == generation_) fn();
        },
        Qt::QueuedConnection);
  }
  std::string service(const std::string& name) const { return ns_ + "/" + name; }

  std::string ns_;
  std::uint64_t generation_ = 0;  // counts namespaces: GUI thread only
  bool connected_ = false;
  bool overdue_ = false;  // a call has waited for its answer more than a second
  // The heartbeat: when the last ~status came (none yet: the epoch), and the run it was from.
  std::chrono::steady_clock::time_point heard_{};
  ros::Time run_started_;
  bool silent_ = false;  // no ~status for kSilence
  static constexpr double kSilence = 1.2;  // seconds: ~status comes every 0.5 s
  /** A ~status came: the runtime speaks; a new run is another runtime. */
  void heard(const apex::RuntimeStatus& status);
  ros::CallbackQueue queue_;
  std::unique_ptr<ros::NodeHandle> nh_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  ros::Subscriber graph_sub_, status_sub_;
  std::map<std::string, ros::Subscriber> scalar_subs_;  // "node/port"
  std::map<std::string, std::vector<ros::Subscriber>> preview_subs_;  // "node/port"
  std::map<std::string, ros::Subscriber> frame_subs_;  // "node/port": whole images, for labelling
  /** A subscription to a port's numbers or strings, shown as scalarReceived. */
  ros::Subscriber watchValues(const std::string& node, const std::string& port, const std::string& topic,
                              const std::string& type);
  /** Subscribes to a scalar topic; `show` gets its value as text. */
  ros::Subscriber subscribeScalar(const std::string& topic, const std::string& type, std::function<void(const QString&)> show);
  QTimer watchdog_;
  /** What a finished job may reach: the link, until it is gone (a job may outlive it). */
  struct Owner {
    std::mutex mutex;
    RuntimeLink* link;
  };
  std::shared_ptr<Owner> owner_;
  std::vector<std::unique_ptr<JobThread>> retired_;  // of namespaces left: they finish what they were given
  std::unique_ptr<JobThread> jobs_;  // last: destroyed first, before what its jobs use
};

}  // namespace apex_rviz_plugin
