#include "apex_rviz_plugin/runtime_link.hpp"

#include "apex_rviz_plugin/box_view.hpp"

#include <apex/Control.h>
#include <apex/FireSlot.h>
#include <apex/FrameTrace.h>
#include <apex/GetGraph.h>
#include <apex/Inspect.h>
#include <apex/ListNodeTypes.h>
#include <apex/LoadGraph.h>
#include <apex/SaveGraph.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>
#include <topic_tools/shape_shifter.h>

#include <QMetaObject>

#include <algorithm>
#include <map>

#include <ros/names.h>
#include <ros/service.h>

namespace apex_rviz_plugin {
namespace {

template <class Req>
struct ServiceOf;
template <>
struct ServiceOf<apex::AddNode::Request> {
  using type = apex::AddNode;
};
template <>
struct ServiceOf<apex::RemoveNode::Request> {
  using type = apex::RemoveNode;
};
template <>
struct ServiceOf<apex::Connect::Request> {
  using type = apex::Connect;
};
template <>
struct ServiceOf<apex::SetParameter::Request> {
  using type = apex::SetParameter;
};
template <>
struct ServiceOf<apex::SetEnabled::Request> {
  using type = apex::SetEnabled;
};
template <>
struct ServiceOf<apex::SetInteractive::Request> {
  using type = apex::SetInteractive;
};
template <>
struct ServiceOf<apex::SetThreadGroup::Request> {
  using type = apex::SetThreadGroup;
};
template <>
struct ServiceOf<apex::SetUi::Request> {
  using type = apex::SetUi;
};
template <>
struct ServiceOf<apex::Group::Request> {
  using type = apex::Group;
};
template <>
struct ServiceOf<apex::Ungroup::Request> {
  using type = apex::Ungroup;
};
template <>
struct ServiceOf<apex::RenameNode::Request> {
  using type = apex::RenameNode;
};

/** Calls a service over a connection the calling thread keeps open for it, opened again when it
 * was closed (the runtime went, or came back). Not a one-off call (ros::service::call): roscpp
 * 1.15 drops one now and then when two threads of a process open and close connections at once
 * (ros_comm#1976; measured here: about 1 call in 5,000 with two threads, none with one thread
 * keeping its connection), and a panel's job thread calls while rviz's other panels or a test do. */
template <class Srv>
bool callKept(const std::string& name, Srv& srv) {
  thread_local std::map<std::string, ros::ServiceClient> kept;
  auto& client = kept[name];
  if (!client.isValid()) client = ros::service::createClient<Srv>(name, true);
  return client.call(srv);
}

/** Calls a service; the response, and in `message` why it failed if it did. */
template <class Srv>
std::pair<bool, typename Srv::Response> callService(const std::string& name, const typename Srv::Request& req,
                                                    std::string* message) {
  Srv srv;
  srv.request = req;
  if (!callKept(name, srv)) {
    *message = "no answer from " + name + ": is the runtime running?";
    return {false, srv.response};
  }
  *message = srv.response.message;
  return {srv.response.success, srv.response};
}

using Result = std::pair<bool, std::string>;

}  // namespace

// ---------------------------------------------------------------- RuntimeLink

RuntimeLink::RuntimeLink(QObject* parent)
    : QObject(parent), owner_(std::make_shared<Owner>()), jobs_(std::make_unique<JobThread>()) {
  owner_->link = this;
  connect(&watchdog_, &QTimer::timeout, this, &RuntimeLink::checkConnection);
  watchdog_.start(250);
}

RuntimeLink::~RuntimeLink() {
  {
    std::lock_guard<std::mutex> lock(owner_->mutex);
    owner_->link = nullptr;  // a call answered from now on is dropped
  }
  if (spinner_) spinner_->stop();
}

template <class T>
void RuntimeLink::async(std::function<T()> work, std::function<void(const T&)> then) {
  jobs_->post([owner = owner_, gen = generation_, work = std::move(work), then = std::move(then)] {
    T result = work();
    std::lock_guard<std::mutex> lock(owner->mutex);  // the link is not destroyed meanwhile
    if (owner->link) owner->link->deliver(gen, [then, result] { then(result); });
  });
}

bool RuntimeLink::setNamespace(const std::string& ns) {
  std::string clean = ns.empty() || ns.front() != '/' ? "/" + ns : ns;
  while (clean.size() > 1 && clean.back() == '/') clean.pop_back();
  if (nh_ && clean == ns_) return false;
  std::string why;
  if (!ros::names::validate(clean, why)) {
    emit connectionChanged(connected_, QString::fromStdString("'" + ns + "' is not a valid namespace: " + why));
    return false;
  }
  if (spinner_) spinner_->stop();
  graph_sub_.shutdown(), status_sub_.shutdown(), scalar_subs_.clear(), preview_subs_.clear(), frame_subs_.clear();
  if (nh_) {  // calls to the runtime left go on on a thread of their own: one that hangs holds up no other
    jobs_->retire();
    retired_.erase(std::remove_if(retired_.begin(), retired_.end(), [](const auto& j) { return j->finished(); }), retired_.end());
    retired_.push_back(std::move(jobs_));
    jobs_ = std::make_unique<JobThread>();
  }
  ++generation_;  // what the runtime left sends or answers from now on is dropped
  ns_ = clean;
  if (!nh_) {
    nh_ = std::make_unique<ros::NodeHandle>();
    nh_->setCallbackQueue(&queue_);
    spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  }
  queue_.clear();
  const std::uint64_t gen = generation_;
  graph_sub_ = nh_->subscribe<apex::GraphState>(service("graph"), 1, [this, gen](const apex::GraphState::ConstPtr& g) {
    deliver(gen, [this, g] { emit graphReceived(*g); });
  });
  status_sub_ = nh_->subscribe<apex::RuntimeStatus>(service("status"), 1, [this, gen](const apex::RuntimeStatus::ConstPtr& s) {
    deliver(gen, [this, s] {
      heard(*s);
      emit statusReceived(*s);
    });
  });
  spinner_->start();
  connected_ = false;
  heard_ = {}, run_started_ = ros::Time(), silent_ = false;
  emit connectionChanged(false, QString("waiting for the runtime at %1").arg(QString::fromStdString(ns_)));
  return true;
}

void RuntimeLink::heard(const apex::RuntimeStatus& status) {
  heard_ = std::chrono::steady_clock::now();
  const bool replaced = !run_started_.isZero() && !status.started.isZero() && status.started != run_started_;
  run_started_ = status.started;
  if (replaced) emit runtimeReplaced();
  if (silent_) checkConnection();  // it speaks again: said at once
}

void RuntimeLink::checkConnection() {
  if (!nh_) return;
  const bool up = graph_sub_.getNumPublishers() > 0;
  const QString ns = QString::fromStdString(ns_);
  if (up != connected_) {
    connected_ = up;
    silent_ = false;
    heard_ = {};  // its heartbeat is waited for anew
    emit connectionChanged(
        up, up ? QString("connected to %1").arg(ns) : QString("the runtime at %1 is gone; reconnecting when it is back").arg(ns));
    return;
  }
  if (!up) return;
  // A killed runtime leaves its topics registered (and roscpp keeps trying its links): only its
  // heartbeat tells. One that never sent a ~status (an older one) is taken at its topics' word.
  const double quiet = heard_ == std::chrono::steady_clock::time_point{}
                           ? 0.0
                           : std::chrono::duration<double>(std::chrono::steady_clock::now() - heard_).count();
  const bool silent = quiet > kSilence;
  if (silent != silent_) {
    silent_ = silent;
    overdue_ = false;
    emit silenceChanged(
        silent, silent ? QString("the runtime at %1 is gone or stuck: no word from it for %2 s").arg(ns).arg(quiet, 0, 'f', 1)
                       : QString("connected to %1").arg(ns));
  }
  if (silent_) return;
  const double waiting = jobs_->busyFor();
  if (waiting > 1.0 || overdue_) {  // slow: said, and the panel goes on
    overdue_ = waiting > 1.0;
    emit answerOverdue(overdue_ ? QString("connected to %1; no answer for %2 s").arg(ns).arg(waiting, 0, 'f', 0)
                                : QString("connected to %1").arg(ns));
  }
}

void RuntimeLink::run(std::vector<Call> calls, Done done) {
  const std::string ns = ns_;
  async<Result>(
      [calls = std::move(calls), ns] {
        std::string message;
        for (const auto& c : calls) {
          const bool ok = std::visit(
              [&](const auto& req) {
                using Srv = typename ServiceOf<std::decay_t<decltype(req)>>::type;
                return callService<Srv>(ns + "/" + c.service, req, &message).first;
              },
              c.request);
          if (!ok && c.if_missing && message.find("already connected") != std::string::npos) continue;
          if (!ok) return Result{false, c.service + ": " + message};
        }
        return Result{true, message};
      },
      [done](const Result& r) { done(r.first, r.second); });
}

void RuntimeLink::runThenRead(std::vector<Call> calls,
                              std::function<void(bool, const std::string&, const apex::GraphState&)> done) {
  // On the job thread after the calls, in order: get_graph answers with them applied.
  auto result = std::make_shared<Result>();
  run(std::move(calls), [result](bool ok, const std::string& m) { *result = {ok, m}; });
  const std::string name = service("get_graph");
  async<apex::GraphState>(
      [name] {
        std::string m;
        return callService<apex::GetGraph>(name, {}, &m).second.graph;
      },
      [result, done](const apex::GraphState& after) { done(result->first, result->second, after); });
}

void RuntimeLink::listTypes(std::function<void(bool, const std::string&, const std::vector<apex::NodeTypeInfo>&)> done) {
  const std::string name = service("list_node_types");
  using Out = std::tuple<bool, std::string, std::vector<apex::NodeTypeInfo>>;
  async<Out>(
      [name] {
        std::string message;
        auto [ok, res] = callService<apex::ListNodeTypes>(name, {}, &message);
        for (const auto& e : res.load_errors) message += (message.empty() ? "" : "; ") + e;
        return Out{ok, message, res.types};
      },
      [done](const Out& r) { done(std::get<0>(r), std::get<1>(r), std::get<2>(r)); });
}

template <class Srv>
void RuntimeLink::callOne(const std::string& name, const typename Srv::Request& req, Done done) {
  const std::string full = service(name);
  async<Result>(
      [full, req] {
        std::string m;
        const bool ok = callService<Srv>(full, req, &m).first;
        return Result{ok, m};
      },
      [done](const Result& r) { done(r.first, r.second); });
}

void RuntimeLink::control(const std::string& command, Done done) {
  apex::Control::Request req;
  req.command = command;
  callOne<apex::Control>("control", req, std::move(done));
}

void RuntimeLink::saveGraph(const std::string& path, Done done) {
  apex::SaveGraph::Request req;
  req.path = path;
  callOne<apex::SaveGraph>("save_graph", req, std::move(done));
}

void RuntimeLink::trace(const std::string& command, const std::string& path, double seconds,
                        std::function<void(bool, const std::string&, bool tracing)> done) {
  apex::FrameTrace::Request req;
  req.command = command, req.path = path, req.seconds = seconds;
  const std::string name = service("trace");
  using Out = std::tuple<bool, std::string, bool>;
  async<Out>(
      [name, req] {
        std::string m;
        auto [ok, res] = callService<apex::FrameTrace>(name, req, &m);
        return Out{ok, m, res.tracing};
      },
      [done](const Out& r) { done(std::get<0>(r), std::get<1>(r), std::get<2>(r)); });
}

void RuntimeLink::loadGraph(const std::string& path, std::function<void(bool, const std::string&, std::uint64_t revision)> done) {
  apex::LoadGraph::Request req;
  req.path = path;
  const std::string name = service("load_graph");
  using Out = std::tuple<bool, std::string, std::uint64_t>;
  async<Out>(
      [name, req] {
        std::string m;
        auto [ok, res] = callService<apex::LoadGraph>(name, req, &m);
        for (const auto& w : res.warnings) m += (m.empty() ? "" : "; ") + w;
        return Out{ok, m, res.revision};
      },
      [done](const Out& r) { done(std::get<0>(r), std::get<1>(r), std::get<2>(r)); });
}

void RuntimeLink::fireSlot(const std::string& node, const std::string& slot, Done done) {
  apex::FireSlot::Request req;
  req.node = node, req.slot = slot;
  callOne<apex::FireSlot>("fire_slot", req, std::move(done));
}

template <class Srv>
void RuntimeLink::callWithAnswer(const std::string& service_name, typename Srv::Request req,
                                 std::function<void(bool, const std::string&, const typename Srv::Response&)> done) {
  using Out = std::tuple<bool, std::string, typename Srv::Response>;
  async<Out>(
      [name = service(service_name), req] {
        std::string m;
        auto [ok, res] = callService<Srv>(name, req, &m);
        return Out{ok, m, res};
      },
      [done](const Out& r) { done(std::get<0>(r), std::get<1>(r), std::get<2>(r)); });
}

void RuntimeLink::recovery(const std::string& action,
                           std::function<void(bool, const std::string&, const apex::Recovery::Response&)> done) {
  apex::Recovery::Request req;
  req.action = action;
  callWithAnswer<apex::Recovery>("recovery", req, std::move(done));
}

void RuntimeLink::balance(int frames, int groups,
                          std::function<void(bool, const std::string&, const apex::Balance::Response&)> done) {
  apex::Balance::Request req;
  req.frames = frames, req.groups = groups, req.apply = false;
  callWithAnswer<apex::Balance>("balance", req, std::move(done));
}

void RuntimeLink::profile(const std::string& node,
                          std::function<void(bool, const std::string&, const apex::GetNodeProfile::Response&)> done) {
  apex::GetNodeProfile::Request req;
  req.node = node;
  callWithAnswer<apex::GetNodeProfile>("node_profile", req, std::move(done));
}

void RuntimeLink::inspect(const std::string& node, const std::string& port,
                          std::function<void(bool, const std::string&, const std::string&, const std::string&)> done,
                          bool preview) {
  apex::Inspect::Request req;
  req.node = node, req.port = port, req.enable = true, req.preview = preview;
  const std::string name = service("inspect");
  using Out = std::tuple<bool, std::string, std::string, std::string>;
  async<Out>(
      [name, req] {
        std::string m;
        auto [ok, res] = callService<apex::Inspect>(name, req, &m);
        return Out{ok, m, res.topic, res.message_type};
      },
      [done](const Out& r) { done(std::get<0>(r), std::get<1>(r), std::get<2>(r), std::get<3>(r)); });
}

void RuntimeLink::watchScalar(const std::string& node, const std::string& port, const std::string& topic,
                              const std::string& type) {
  if (!nh_) return;
  scalar_subs_[node + "/" + port] = watchValues(node, port, topic, type);
}

ros::Subscriber RuntimeLink::watchValues(const std::string& node, const std::string& port, const std::string& topic,
                                         const std::string& type) {
  const QString n = QString::fromStdString(node), p = QString::fromStdString(port);
  return subscribeScalar(topic, type, [this, n, p, gen = generation_](const QString& text) {
    deliver(gen, [this, n, p, text] { emit scalarReceived(n, p, text); });
  });
}

namespace {
/** An image message as a QImage of its own (deep copy); null for encodings not drawn here. */
QImage toQImage(const sensor_msgs::Image& m) {
  const auto* data = m.data.data();
  const int w = static_cast<int>(m.width), h = static_cast<int>(m.height), step = static_cast<int>(m.step);
  if (m.data.size() < static_cast<std::size_t>(step) * h) return {};
  if (m.encoding == "bgr8") return QImage(data, w, h, step, QImage::Format_RGB888).rgbSwapped();
  if (m.encoding == "rgb8") return QImage(data, w, h, step, QImage::Format_RGB888).copy();
  if (m.encoding == "mono8" || m.encoding == "8UC1") return QImage(data, w, h, step, QImage::Format_Grayscale8).copy();
  if (m.encoding == "bgra8") return QImage(data, w, h, step, QImage::Format_ARGB32).copy();
  return {};
}
}  // namespace

void RuntimeLink::watchPreview(const std::string& node, const std::string& port, const std::string& topic,
                               const std::string& type) {
  if (!nh_) return;
  const QString n = QString::fromStdString(node), p = QString::fromStdString(port);
  const std::uint64_t gen = generation_;
  auto& subs = preview_subs_[node + "/" + port];
  subs.clear();
  if (type == "sensor_msgs/Image") {
    subs.push_back(nh_->subscribe<sensor_msgs::Image>(topic, 1, [this, n, p, gen](const sensor_msgs::Image::ConstPtr& m) {
      QImage image = toQImage(*m);  // converted here, on the link's spinner, not on the GUI thread
      deliver(gen, [this, n, p, image] { emit imageReceived(n, p, image); });
    }));
    subs.push_back(nh_->subscribe<std_msgs::String>(topic + "/about", 1, [this, n, p, gen](const std_msgs::String::ConstPtr& m) {
      const QString text = QString::fromStdString(m->data);  // the thumbnail's real size
      deliver(gen, [this, n, p, text] { emit aboutReceived(n, p, text); });
    }));
  } else if (type.empty() || type.rfind("std_msgs/", 0) == 0) {  // numbers, text and YAML text: shown as they are
    subs.push_back(watchValues(node, port, topic, type));
  } else {  // any other message (clouds, regions, keypoints...): what it was, from its describe
    const boost::function<void(const topic_tools::ShapeShifter::ConstPtr&)> ignore = [](const auto&) {};
    subs.push_back(nh_->subscribe<topic_tools::ShapeShifter>(topic, 1, ignore));  // the runtime publishes while subscribed
    subs.push_back(nh_->subscribe<std_msgs::String>(topic + "/about", 1, [this, n, p, gen](const std_msgs::String::ConstPtr& m) {
      const QString text = QString::fromStdString(m->data).left(200);
      deliver(gen, [this, n, p, text] { emit scalarReceived(n, p, text); });
    }));
  }
}

void RuntimeLink::unwatchPreview(const std::string& node, const std::string& port) {
  preview_subs_.erase(node + "/" + port);  // no subscriber left: the runtime publishes nothing
}

void RuntimeLink::watchFrames(const std::string& node, const std::string& port, const std::string& topic) {
  if (!nh_) return;
  const QString n = QString::fromStdString(node), p = QString::fromStdString(port);
  const std::uint64_t gen = generation_;
  frame_subs_[node + "/" + port] =
      nh_->subscribe<sensor_msgs::Image>(topic, 1, [this, n, p, gen](const sensor_msgs::Image::ConstPtr& m) {
        const QImage image = toQImage(*m);  // whole, converted here, on the link's spinner
        const quint64 stamp = m->header.stamp.toNSec();
        const QString encoding = QString::fromStdString(m->encoding);
        deliver(gen, [this, n, p, image, stamp, encoding] { emit frameReceived(n, p, image, stamp, encoding); });
      });
}

void RuntimeLink::unwatchFrames(const std::string& node, const std::string& port) { frame_subs_.erase(node + "/" + port); }

ros::Subscriber RuntimeLink::subscribeScalar(const std::string& topic, const std::string& type,
                                             std::function<void(const QString&)> show) {
  ros::Subscriber sub;
  if (type == "std_msgs/Int32")
    sub =
        nh_->subscribe<std_msgs::Int32>(topic, 1, [show](const std_msgs::Int32::ConstPtr& m) { show(QString::number(m->data)); });
  else if (type == "std_msgs/Float64")
    sub = nh_->subscribe<std_msgs::Float64>(
        topic, 1, [show](const std_msgs::Float64::ConstPtr& m) { show(QString::fromStdString(scalarText(m->data))); });
  else if (type == "std_msgs/Bool")
    sub =
        nh_->subscribe<std_msgs::Bool>(topic, 1, [show](const std_msgs::Bool::ConstPtr& m) { show(m->data ? "true" : "false"); });
  else  // strings, and everything the runtime publishes as its YAML text
    sub = nh_->subscribe<std_msgs::String>(
        topic, 1, [show](const std_msgs::String::ConstPtr& m) { show(QString::fromStdString(m->data).left(200)); });
  return sub;
}

bool RuntimeLink::receiving(const std::string& topic) const {
  for (const auto& [port, s] : scalar_subs_)
    if (s.getTopic() == topic && s.getNumPublishers() > 0) return true;
  return false;
}

}  // namespace apex_rviz_plugin
