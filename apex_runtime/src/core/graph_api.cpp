// Graph's public calls: each forwards to Graph::Impl (graph_impl.hpp), which holds the
// graph, so that graph.hpp shows the API and nothing of how it is kept.
#include "graph_impl.hpp"

namespace apex {

Graph::Graph(NodeRegistry registry) : impl_(std::make_unique<Impl>(std::move(registry))) {}
Graph::~Graph() = default;  // Impl's destructor stops the graph

const NodeRegistry& Graph::registry() const { return impl_->registry_; }
NodeRegistry& Graph::registry() { return impl_->registry_; }
void Graph::setHost(std::shared_ptr<const Host> host) { impl_->setHost(std::move(host)); }
void Graph::setRerunOnEdit(bool on) { impl_->rerun_on_edit_.store(on); }
std::uint64_t Graph::revision() const { return impl_->revisions_->visible.load(std::memory_order_relaxed); }
std::uint64_t Graph::editRevision() const { return impl_->revisions_->edited.load(std::memory_order_relaxed); }

// ------------------------------------------------------------------ edits

Result<std::string> Graph::addNode(const std::string& type, const std::string& name, const std::string& thread_group) {
  return impl_->addNode(type, name, thread_group);
}
Result<std::string> Graph::addNode(const NodeDescription& description) { return impl_->addNode(description); }
Status Graph::removeNode(const std::string& name) { return impl_->removeNode(name); }
Status Graph::group(const std::vector<std::string>& nodes, const std::string& name, bool restore) {
  return impl_->group(nodes, name, restore);
}
Status Graph::ungroup(const std::string& name) { return impl_->ungroup(name); }
Status Graph::rename(const std::string& name, const std::string& new_name) { return impl_->rename(name, new_name); }
Status Graph::connect(const std::string& from_node, const std::string& from_port, const std::string& to_node,
                      const std::string& to_port) {
  return impl_->connect(from_node, from_port, to_node, to_port);
}
Status Graph::disconnect(const std::string& from_node, const std::string& from_port, const std::string& to_node,
                         const std::string& to_port) {
  return impl_->disconnect(from_node, from_port, to_node, to_port);
}
Result<std::string> Graph::setParameter(const std::string& node, const std::string& param, const std::string& yaml_text) {
  return impl_->setParameter(node, param, yaml_text);
}
Status Graph::setInteractive(const std::string& node, const std::string& param, bool interactive) {
  return impl_->setInteractive(node, param, interactive);
}
Status Graph::setEnabled(const std::string& node, bool enabled) { return impl_->setEnabled(node, enabled); }
Status Graph::setThreadGroup(const std::string& node, const std::string& group) { return impl_->setThreadGroup(node, group); }
Status Graph::removeThreadGroup(const std::string& group) { return impl_->removeThreadGroup(group); }
Status Graph::fireSlot(const std::string& node, const std::string& slot) { return impl_->fireSlot(node, slot); }
Status Graph::setUi(const std::string& node, const std::string& ui_yaml) { return impl_->setUi(node, ui_yaml); }
Status Graph::setTap(const std::string& node, const std::string& port, PortTap tap) {
  return impl_->setTap(node, port, std::move(tap));
}

// ------------------------------------------------------------------ running

void Graph::start() { impl_->start(); }
void Graph::stop() { impl_->stop(); }
void Graph::pause() { impl_->pause(); }
void Graph::resume() { impl_->resume(); }
bool Graph::paused() const { return impl_->paused(); }
void Graph::step() { impl_->step(); }
Status Graph::stepFrame(double timeout_s) { return impl_->stepFrame(timeout_s); }
bool Graph::waitIdle(double timeout_s) const { return impl_->waitIdle(timeout_s); }

// ------------------------------------------------------------------ reading

GraphDescription Graph::describe() const { return impl_->describe(); }
Result<NodeDescription> Graph::describeNode(const std::string& name) const { return impl_->describeNode(name); }
std::vector<ConnectionDescription> Graph::connections() const { return impl_->connections(); }
Result<LoadReport> Graph::load(const GraphDescription& description) { return impl_->load(description); }
std::vector<NodeStats> Graph::nodeStats(double stall_after_s) const { return impl_->nodeStats(stall_after_s); }
Result<NodeProfile> Graph::nodeProfile(const std::string& node) const { return impl_->nodeProfile(node); }
std::vector<GroupStats> Graph::groupStats() const { return impl_->groupStats(); }
void Graph::setTracing(bool on) { impl_->setTracing(on); }
bool Graph::tracing() const {
  auto lock = impl_->lockEdits();
  return impl_->tracing_;
}
Trace Graph::trace(double seconds) const { return impl_->trace(seconds); }
std::shared_ptr<const NodeType> Graph::nodeType(const std::string& node) const { return impl_->nodeType(node); }
std::shared_ptr<const Manifest> Graph::nodeInterface(const std::string& node) const { return impl_->nodeInterface(node); }
Node* Graph::nodeObject(const std::string& node) const { return impl_->nodeObject(node); }
std::size_t Graph::size() const { return impl_->size(); }
Result<ParamValue> Graph::parameterValue(const std::string& node, const std::string& param) const {
  return impl_->parameterValue(node, param);
}

}  // namespace apex
