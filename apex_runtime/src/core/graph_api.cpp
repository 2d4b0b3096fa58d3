// Graph's construction and the public calls that are steps of Graph::Impl too (graph_impl.hpp:
// a load adds nodes, a group sets parameters), which forward there. The others are written
// once, as Graph's own methods, in the files of their concern (graph_impl.hpp names them).
#include "graph_impl.hpp"

namespace apex {

Graph::Graph(NodeRegistry registry) : impl_(std::make_unique<Impl>(std::move(registry))) {}
Graph::~Graph() = default;  // Impl's destructor stops the graph

const NodeRegistry& Graph::registry() const { return impl_->registry_; }
NodeRegistry& Graph::registry() { return impl_->registry_; }
void Graph::setRerunOnEdit(bool on) { impl_->rerun_on_edit_.store(on); }
std::uint64_t Graph::revision() const { return impl_->revisions_->visible.load(std::memory_order_relaxed); }
std::uint64_t Graph::editRevision() const { return impl_->revisions_->edited.load(std::memory_order_relaxed); }

// ------------------------------------------------------------------ edits

Result<std::string> Graph::addNode(const std::string& type, const std::string& name, const std::string& thread_group) {
  return impl_->addNode(type, name, thread_group);
}
Result<std::string> Graph::addNode(const NodeDescription& description) { return impl_->addNode(description); }
Status Graph::removeNode(const std::string& name) { return impl_->removeNode(name); }
Result<std::string> Graph::setParameter(const std::string& node, const std::string& param, const std::string& yaml_text) {
  return impl_->setParameter(node, param, yaml_text);
}
Status Graph::setInteractive(const std::string& node, const std::string& param, bool interactive) {
  return impl_->setInteractive(node, param, interactive);
}
Status Graph::setEnabled(const std::string& node, bool enabled) { return impl_->setEnabled(node, enabled); }
Status Graph::fireSlot(const std::string& node, const std::string& slot) { return impl_->fireSlot(node, slot); }
Status Graph::setUi(const std::string& node, const std::string& ui_yaml) { return impl_->setUi(node, ui_yaml); }

// ------------------------------------------------------------------ running

void Graph::stop() { impl_->stop(); }

}  // namespace apex
