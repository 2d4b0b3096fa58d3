// Service callbacks: request → core call → response. Publishing: ~graph
// (latched) after every change from any source, ~status at 2 Hz, parameter
// values mirrored on the parameter server under ~nodes/<node>/<parameter>.
#include "apex/ros/runtime_host.hpp"
#include "apex/ros/node_handles.hpp"

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/Control.h>
#include <apex/FireSlot.h>
#include <apex/GetGraph.h>
#include <apex/Group.h>
#include <apex/Inspect.h>
#include <apex/ListNodeTypes.h>
#include <apex/LoadGraph.h>
#include <apex/RemoveNode.h>
#include <apex/RenameNode.h>
#include <apex/SaveGraph.h>
#include <apex/SetEnabled.h>
#include <apex/SetInteractive.h>
#include <apex/SetParameter.h>
#include <apex/SetThreadGroup.h>
#include <apex/SetUi.h>
#include <apex/Ungroup.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

#include "apex/core/file_roots.hpp"
#include "apex/core/graph_file.hpp"
#include "apex/core/log.hpp"
#include "balance_service.hpp"
#include "change_publisher.hpp"
#include "profile_service.hpp"
#include "trace_service.hpp"
#include "convert.hpp"
#include "diagnostics.hpp"
#include "inspection.hpp"
#include "param_mirror.hpp"
#include "node_log.hpp"
#include "master_watch.hpp"
#include "paths.hpp"
#include "plugin_types.hpp"
#include "reconfigure.hpp"
#include "recovery.hpp"
#include "request_text.hpp"

namespace apex {
namespace ros_host {

namespace {

template <class Res>
bool answer(Res& res, const Status& st) {
  res.success = st.isOk();
  res.message = st.isOk() ? "" : st.message();
  return true;  // the call itself worked; `success` says whether the edit did
}

}  // namespace

struct RuntimeHost::Impl {
  ros::NodeHandle nh, pnh;
  std::unique_ptr<PluginTypes> plugins;  // first: node code lives in its libraries, so they outlive the graph
  Graph graph;
  FileRoots roots;  // what paths from services may name (~file_roots)
  std::vector<std::string> load_errors;
  Inspection inspection;
  ParamMirror mirror;
  ros::Publisher graph_pub, status_pub;
  std::unique_ptr<Recovery> recovery;  // unsaved edits kept on disk (recovery.hpp); outlives the services
  std::vector<ros::ServiceServer> services;
  std::unique_ptr<BalanceService> balance;  // ~balance, on a thread of its own
  ros::WallTimer change_timer, status_timer;
  std::unique_ptr<Reconfigure> reconfigure;  // after the graph: gone before it
  std::unique_ptr<Diagnostics> diagnostics;
  std::unique_ptr<MasterWatch> master_watch;  // last made, first gone
  std::mutex publish_mutex;
  std::uint64_t published_revision = ~0ull;
  GraphState published;  // publish_mutex: the last ~graph, for the servers still to make
  ChangePublisher publisher{[this] { publishIfChanged(); }};  // calls wake it; it publishes
  const ros::Time started = ros::Time::now();  // in every ~status: a client tells a restarted runtime by it

  Impl(ros::NodeHandle n, ros::NodeHandle p) : nh(n), pnh(p), graph(NodeRegistry()), inspection(pnh), mirror(pnh) {
    graph.setHost(std::make_shared<RosHost>(nh, pnh));  // nodes' topics: in our namespace, with our remappings
  }

  // ------------------------------------------------------------ publishing

  void publishIfChanged() {
    std::lock_guard<std::mutex> lock(publish_mutex);
    const std::uint64_t revision = graph.revision();
    if (revision == published_revision) {  // a few more of a big graph's servers at each tick
      if (reconfigure && reconfigure->pending()) reconfigure->update(published);
      return;
    }
    published_revision = revision;
    published = toGraphState(graph, revision);
    const GraphState& state = published;
    graph_pub.publish(state);
    mirror.update(graph, state);
    if (reconfigure) reconfigure->update(state);

    if (diagnostics) diagnostics->setGraph(state);
  }

  /** A new master has our topics and services again (MasterWatch); its parameter server has
   *  none of our values: set them all, and ~graph anew. */
  void afterNewMaster() {
    {
      std::lock_guard<std::mutex> lock(publish_mutex);
      mirror.forget();
      published_revision = ~0ull;
    }
    publishIfChanged();
  }

  template <class Res>
  bool answered(Res& res, const Status& st) {
    answer(res, st);
    publisher.wake();  // ~graph follows on the publisher's thread: the call answers at once
    return true;
  }

  // ------------------------------------------------------------ services

  bool listNodeTypes(ListNodeTypes::Request&, ListNodeTypes::Response& res) {
    for (const auto& id : graph.registry().ids()) res.types.push_back(toTypeInfo(*graph.registry().find(id)));
    res.load_errors = load_errors;
    res.success = true;
    return true;
  }

  /** A graph file as a node type: `add_node type:=package://apex/graphs/x.yaml` adds a subgraph. */
  static bool namesGraphFile(const std::string& type) {
    const auto dot = type.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : type.substr(dot);
    return ext == ".yaml" || ext == ".yml";
  }

  bool addNode(AddNode::Request& req, AddNode::Response& res) {
    NodeDescription d;
    d.type = req.type;
    d.name = req.name;
    if (req.type == kSubgraphType)
      return answered(res, Status::error("a subgraph is added from its graph file: add_node with type "
                                         "'package://apex/graphs/camera_detector.yaml' or a path ending in .yaml"));
    if (namesGraphFile(req.type)) {
      auto path = roots.resolve(req.type);
      if (!path) return answered(res, path.status());
      auto inner = readGraphDescription(path.value(), fileOptions(true));
      if (!inner) return answered(res, inner.status());
      d.type = kSubgraphType;
      d.source = req.type.rfind("package://", 0) == 0 ? req.type : path.value();
      d.subgraph = std::make_shared<GraphDescription>(std::move(inner.value()));
      if (d.name.empty()) {  // the file's name: camera_detector, camera_detector_2, ...
        const std::string stem = std::filesystem::path(path.value()).stem().string();
        const GraphDescription now = graph.describe();
        d.name = stem;
        for (int i = 2; findNode(now, d.name); ++i) d.name = stem + "_" + std::to_string(i);
      }
    }
    d.thread_group = req.thread_group;
    auto params = parseParameterMap(req.parameters);
    if (!params) return answered(res, Status::error("parameters: " + params.message()));
    d.parameters = params.value();
    if (d.type != kSubgraphType) {  // "GaussianBlur" is apex_nodes/GaussianBlur: its paths are confined as its
      auto type = graph.registry().lookup(d.type);
      if (!type) return answered(res, type.status());
      d.type = type.value()->id;
      for (const auto& p : type.value()->manifest->params)
        if (p.interactive) d.interactive.push_back(p.name);
    }
    if (auto st = confine(d); !st) return answered(res, st);
    auto added = graph.addNode(d);
    if (added) {
      res.name = added.value();
      if (d.type != kSubgraphType) {  // one node: described alone (the whole graph is O(graph))
        if (auto n = graph.describeNode(res.name)) res.node = toNodeInfo(n.value());
      } else if (const GraphDescription now = graph.describe(); const NodeDescription* n = findNode(now, res.name)) {
        res.node = toNodeInfo(*n);
      }
      res.node.name = res.name;
    }
    return answered(res, added.status());
  }

  bool removeNode(RemoveNode::Request& req, RemoveNode::Response& res) {
    auto st = graph.removeNode(req.name);
    if (st) inspection.forgetNode(req.name);
    return answered(res, st);
  }

  bool connect(Connect::Request& req, Connect::Response& res) {
    return answered(res, graph.connect(req.from_node, req.from_port, req.to_node, req.to_port));
  }

  bool disconnect(Connect::Request& req, Connect::Response& res) {
    return answered(res, graph.disconnect(req.from_node, req.from_port, req.to_node, req.to_port));
  }

  /** One parameter from outside (a service, dynamic_reconfigure): its path confined, then set. */
  Result<std::string> setFromOutside(const std::string& node, const std::string& param, const std::string& text) {
    auto value = pathValue(graph.nodeInterface(node), node, param, text, roots, true);
    return value ? graph.setParameter(node, param, value.value()) : Result<std::string>(value.status());
  }

  bool setParameter(SetParameter::Request& req, SetParameter::Response& res) {
    auto applied = setFromOutside(req.node, req.parameter, req.value);
    if (applied) {
      res.value = applied.value();
    } else if (auto old = graph.parameterValue(req.node, req.parameter)) {
      res.value = toText(old.value());  // refused: the value that stays
    }
    return answered(res, applied.status());
  }

  bool setInteractive(SetInteractive::Request& req, SetInteractive::Response& res) {
    return answered(res, graph.setInteractive(req.node, req.parameter, req.interactive));
  }
  bool setEnabled(SetEnabled::Request& req, SetEnabled::Response& res) {
    return answered(res, graph.setEnabled(req.node, req.enabled));
  }
  bool setThreadGroup(SetThreadGroup::Request& req, SetThreadGroup::Response& res) {
    return answered(res, graph.setThreadGroup(req.node, req.group));
  }
  bool setUi(SetUi::Request& req, SetUi::Response& res) { return answered(res, graph.setUi(req.node, req.ui)); }
  bool group(Group::Request& req, Group::Response& res) {
    auto st = graph.group(req.nodes, req.name, req.restore);
    if (st) inspection.clear();  // taps follow names: inspect again under the new ones
    return answered(res, st);
  }
  bool ungroup(Ungroup::Request& req, Ungroup::Response& res) {
    auto st = graph.ungroup(req.name);
    if (st) inspection.clear();
    return answered(res, st);
  }
  bool renameNode(RenameNode::Request& req, RenameNode::Response& res) {
    auto st = graph.rename(req.name, req.new_name);
    if (st) {
      inspection.forgetNode(req.name);
      const auto slash = req.name.rfind('/');
      res.path = (slash == std::string::npos ? "" : req.name.substr(0, slash + 1)) + req.new_name;
    }
    return answered(res, st);
  }
  bool fireSlot(FireSlot::Request& req, FireSlot::Response& res) { return answered(res, graph.fireSlot(req.node, req.slot)); }

  bool getGraph(GetGraph::Request&, GetGraph::Response& res) {
    res.graph = toGraphState(graph, graph.revision());
    res.yaml = formatGraphText(graph.describe());
    res.success = true;
    return true;
  }

  bool loadGraph(LoadGraph::Request& req, LoadGraph::Response& res) {
    auto path = roots.resolve(req.path);
    if (!path) return answered(res, path.status());
    res.path = path.value();
    auto report = loadGraphFile(graph, path.value(), fileOptions(true));
    if (report) {
      res.warnings = report.value().warnings;
      res.revision = graph.revision();
      inspection.clear();
      for (const auto& w : res.warnings) ROS_WARN_STREAM_NAMED("apex", w);
      recovery->saved(snapshot());
    }
    return answered(res, report.status());
  }

  bool saveGraph(SaveGraph::Request& req, SaveGraph::Response& res) {
    auto path = roots.resolve(req.path, FileRoots::Access::Write);
    if (path) res.path = path.value();  // a relative path: in the first writable root
    const Recovery::Snapshot before = snapshot();  // an edit during the save keeps a copy
    // (Links::Refuse: the folder the roots allowed, not one a link swapped in since sends it elsewhere)
    const Status st = path ? saveGraphFile(graph, path.value(), Links::Refuse) : path.status();
    if (st) recovery->saved(before);
    return answered(res, st);
  }

  Recovery::Snapshot snapshot() const {
    const std::uint64_t revision = graph.editRevision();  // first: an edit meanwhile is one more
    const GraphDescription d = graph.describe();
    return {formatGraphText(d), d.nodes.size(), revision};
  }

  // ------------------------------------------------------------ paths from outside

  /** One node's parameters from a service: its paths confined to the roots. */
  Status confine(NodeDescription& d) { return resolvePaths(graph.registry(), d, roots, true); }

  /** Graph files from services (`confined`) may name subgraph files in the roots only; the
   *  start-up graph, given by whoever launched us, anywhere. package:// is understood. */
  GraphFileOptions fileOptions(bool confined) {
    GraphFileOptions o;
    if (confined) {
      o.check = [this](NodeDescription& d) { return confine(d); };
      o.open = [this](const std::string& path) { return roots.resolve(path); };
    } else {  // ~ and package:// in its paths understood, as in the launch file that named it
      o.check = [this](NodeDescription& d) { return resolvePaths(graph.registry(), d, roots, false); };
      o.open = [](const std::string& path) { return FileRoots::anywhere(packagePath).resolve(path); };
    }
    return o;
  }

  /** After the start-up graph: ~file_roots, $ROS_HOME/apex and the folders of the files the
   *  launch gave (paths.hpp). */
  void loadRoots() {
    roots = launchRoots(pnh, launchFolders());
    ROS_INFO_STREAM_NAMED("apex", "paths from services may name files in: " << roots.list());
  }

  /** The folder of ~graph and those of the paths the start-up graph's parameters hold, after
   *  ~overrides (a bag given to runtime.launch): what the operator's launch file named. */
  LaunchFolders launchFolders() const {
    LaunchFolders folders;
    std::string startup;
    if (pnh.getParam("graph", startup) && !startup.empty())  // saved back beside itself
      folders.writable.push_back(std::filesystem::absolute(startup).parent_path().string());
    pathFolders(graph.registry(), graph.describe(), folders);
    return folders;
  }

  bool control(Control::Request& req, Control::Response& res) {
    Status st = Status::ok();
    if (req.command == "pause") {
      graph.pause();
    } else if (req.command == "resume") {
      graph.resume();
    } else if (req.command == "step") {  // one frame through the whole graph
      st = graph.stepFrame();
      if (!st) st = Status::error("step: " + st.message());
    } else if (req.command == "clear") {  // New: every node goes, as a Load of an empty file
      auto report = graph.load(GraphDescription());
      st = report ? Status::ok() : report.status();
      if (st) inspection.clear();
    } else {
      st = Status::error("unknown command '" + req.command + "' (commands: pause, resume, step, clear)");
    }
    res.paused = graph.paused();
    return answered(res, st);
  }

  bool inspect(Inspect::Request& req, Inspect::Response& res) {
    auto topic = inspection.set(graph, req.node, req.port, req.enable, req.preview);
    if (topic) {
      res.topic = topic.value().first;
      res.message_type = topic.value().second;
    }
    return answered(res, topic.status());
  }

  // ------------------------------------------------------------ setup

  template <class Req, class Res>
  void serve(const std::string& name, bool (Impl::*fn)(Req&, Res&)) {
    services.push_back(advertiseChecked<Req, Res>(pnh, name, [this, fn](Req& req, Res& res) { return (this->*fn)(req, res); }));
  }

  void advertise() {
    // first: a panel asks for it as soon as it sees ~graph
    services.push_back(serveRecovery(pnh, *recovery, [this](auto& req, auto& res) { return loadGraph(req, res); }));
    graph_pub = pnh.advertise<GraphState>("graph", 1, true);
    status_pub = pnh.advertise<RuntimeStatus>("status", 1);
    serve("list_node_types", &Impl::listNodeTypes);
    serve("add_node", &Impl::addNode);
    serve("remove_node", &Impl::removeNode);
    serve("connect", &Impl::connect);
    serve("disconnect", &Impl::disconnect);
    serve("set_parameter", &Impl::setParameter);
    serve("set_interactive", &Impl::setInteractive);
    serve("set_enabled", &Impl::setEnabled);
    serve("set_thread_group", &Impl::setThreadGroup);
    balance = std::make_unique<BalanceService>(pnh, graph, [this](auto& req, auto& res) { return setThreadGroup(req, res); });
    serve("set_ui", &Impl::setUi);
    serve("fire_slot", &Impl::fireSlot);
    serve("group", &Impl::group);
    serve("ungroup", &Impl::ungroup);
    serve("rename_node", &Impl::renameNode);
    serve("get_graph", &Impl::getGraph);
    serve("load_graph", &Impl::loadGraph);
    serve("save_graph", &Impl::saveGraph);
    serve("control", &Impl::control);
    serve("inspect", &Impl::inspect);
    services.push_back(serveTrace(pnh, graph, roots, ros::this_node::getName()));
    services.push_back(serveProfile(pnh, graph));
    bool reconfigurable = true, diagnosed = true;
    pnh.param("dynamic_reconfigure", reconfigurable, true);
    pnh.param("diagnostics", diagnosed, true);
    int reconfigure_limit = Reconfigure::kDefaultLimit;
    pnh.param("dynamic_reconfigure_limit", reconfigure_limit, reconfigure_limit);
    if (reconfigurable)
      reconfigure = std::make_unique<Reconfigure>(
          pnh, graph,
          [this](const std::string& node, const std::string& param, const std::string& text) {
            auto applied = setFromOutside(node, param, text);
            publisher.wake();  // parameter_updates, ~graph
            return applied;
          },
          reconfigure_limit);
    if (diagnosed) diagnostics = std::make_unique<Diagnostics>(nh, pnh, graph);
    change_timer = pnh.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) {
      publisher.wake();  // what nodes changed themselves (errors, a player's position)
      recovery->tick(graph.editRevision(), [this] { return snapshot(); });
    });
    status_timer = pnh.createWallTimer(ros::WallDuration(0.5), [this](const ros::WallTimerEvent&) {
      if (status_pub.getNumSubscribers() == 0) return;
      RuntimeStatus status = toStatus(graph);
      status.started = started;
      status.unsaved = recovery->unsaved();
      status_pub.publish(status);
    });
  }

  void loadTypes() {
    std::vector<std::string> extra;
    pnh.getParam("extra_plugin_xml", extra);
    PluginTypes types(extra);
    load_errors = types.registerAll(graph.registry());
    for (const auto& e : load_errors) ROS_ERROR_STREAM_NAMED("apex", e);
    ROS_INFO_STREAM_NAMED("apex", graph.registry().ids().size() << " node types available");
    plugins = std::make_unique<PluginTypes>(std::move(types));
  }

  void loadStartupGraph() {
    std::string path;
    if (!pnh.getParam("graph", path) || path.empty()) return;
    auto report = loadGraphFile(graph, path, fileOptions(false));
    if (!report) {
      ROS_ERROR_STREAM_NAMED("apex", "cannot load the graph: " << report.message() << "; starting with an empty graph");
      return;
    }
    for (const auto& w : report.value().warnings) ROS_WARN_STREAM_NAMED("apex", w);
    ROS_INFO_STREAM_NAMED("apex", "loaded " << path << " (" << graph.size() << " nodes)");
    applyOverrides();
  }

  /** ~overrides: {node: {parameter: value}} set after the start-up graph loads, so one
   *  graph file serves several robots, bags or topics. */
  void applyOverrides() {
    XmlRpc::XmlRpcValue overrides;
    if (!pnh.getParam("overrides", overrides)) return;
    if (overrides.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      ROS_ERROR_STREAM_NAMED("apex", "~overrides must be a mapping {node: {parameter: value}}");
      return;
    }
    for (auto& [node, params] : overrides) {
      if (params.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
        ROS_ERROR_STREAM_NAMED("apex", "override '" << node << "': must be a mapping {parameter: value}");
        continue;
      }
      for (auto& [param, value] : params) {
        auto text = pathValue(graph.nodeInterface(node), node, param, yamlText(value), roots, false);  // ~/bags/x.bag
        auto applied = text ? graph.setParameter(node, param, text.value()) : Result<std::string>(text.status());
        if (applied) ROS_INFO_STREAM_NAMED("apex", "override " << node << "/" << param << " = " << applied.value());
        else ROS_ERROR_STREAM_NAMED("apex", "override " << node << "/" << param << ": " << applied.message());
      }
    }
  }
  /** A parameter-server value as YAML text. */
  static std::string yamlText(XmlRpc::XmlRpcValue& v) {
    switch (v.getType()) {
      case XmlRpc::XmlRpcValue::TypeBoolean:
        return bool(v) ? "true" : "false";
      case XmlRpc::XmlRpcValue::TypeInt:
        return std::to_string(int(v));
      case XmlRpc::XmlRpcValue::TypeDouble:
        return toText(double(v));
      case XmlRpc::XmlRpcValue::TypeString:
        return yamlQuoted(std::string(v));
      case XmlRpc::XmlRpcValue::TypeArray: {
        std::string out = "[";
        for (int i = 0; i < v.size(); ++i) out += (i ? ", " : "") + yamlText(v[i]);
        return out + "]";
      }
      default:
        return "~";
    }
  }
};

RuntimeHost::RuntimeHost(ros::NodeHandle nh, ros::NodeHandle pnh) : impl_(new Impl(nh, pnh)) {
  installRosconsoleSink();
  for (auto& s : serveLoggerServices(impl_->pnh)) impl_->services.push_back(std::move(s));
  impl_->loadTypes();
  bool rerun = true;  // ~rerun_on_edit: false for headless tuning, where every pass is a replay
  impl_->pnh.param("rerun_on_edit", rerun, true);
  impl_->graph.setRerunOnEdit(rerun);
  impl_->loadStartupGraph();  // trusted, like ~overrides: the operator's own launch file
  impl_->loadRoots();  // its folders among them
  impl_->recovery = std::make_unique<Recovery>(ownFolder() + "/recovery", impl_->pnh.getNamespace());
  impl_->recovery->saved(impl_->snapshot());  // the start-up graph, as its launch gives it again
  impl_->graph.start();
  impl_->advertise();
  impl_->publishIfChanged();
  impl_->master_watch = std::make_unique<MasterWatch>(
      [impl = impl_.get()] { impl->afterNewMaster(); },
      [impl = impl_.get()] { return impl->graph.editRevision(); });  // (reconfigure's services follow edits)
}

RuntimeHost::~RuntimeHost() {
  impl_->change_timer.stop();
  impl_->publisher.stop();
  impl_->recovery->close();  // first: a stop that then waits for a node in process() is still clean
  impl_->balance.reset();  // a balance waiting for frames ends
  impl_->master_watch.reset();
  {
    std::lock_guard<std::mutex> lock(impl_->publish_mutex);  // they are used under it
    impl_->diagnostics.reset();
    impl_->reconfigure.reset();
  }
  impl_->graph.stop();
  impl_->inspection.clear();
}

}  // namespace ros_host
}  // namespace apex
