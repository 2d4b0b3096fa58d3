// Node's accessors: thin lookups into the node's runtime state.
#include "apex/core/node.hpp"

#include <stdexcept>

#include "apex/core/node_names.hpp"
#include "edit_requests.hpp"
#include "node_state.hpp"

namespace apex {
namespace {

[[noreturn]] void unknown(const detail::NodeState& s, const std::string& what, std::string_view name, const std::string& list) {
  throw std::invalid_argument(nodeLabel(s.name(), s.typeId()) + " has no " + what + " '" + std::string(name) + "' (" + what +
                              "s: " + list + ")");
}

detail::NodeState& stateOf(detail::NodeState* s) {
  if (!s) throw std::logic_error("this apex::Node is not part of a graph yet (called from its constructor?)");
  return *s;
}

}  // namespace

const std::string& Node::name() const {
  static const std::string kNone;
  auto* s = state_.load(std::memory_order_acquire);
  return s ? s->name() : kNone;
}

void Node::notifyAfter(double seconds) {
  if (auto* s = state_.load(std::memory_order_acquire)) s->notifyAfter(seconds);
}

void Node::notifyNewData() {
  if (auto* s = state_.load(std::memory_order_acquire)) s->notifyNewData();
}

void Node::countDropped(std::uint64_t n) {
  if (auto* s = state_.load(std::memory_order_acquire)) s->countDropped(n);
}

const Host* Node::host() const {
  auto* s = state_.load(std::memory_order_acquire);
  return s ? s->host() : nullptr;
}

const Manifest& Node::interface() const { return stateOf(state_.load(std::memory_order_acquire)).manifest(); }

const Message& Node::inputMessage(std::string_view input) const {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const int i = s.findInput(input);
  if (i < 0) unknown(s, "input", input, s.manifest().listInputs());
  return s.currentInput(i);
}

const Message& Node::inputAt(int index) const { return stateOf(state_.load(std::memory_order_acquire)).currentInput(index); }
Message Node::takeInputAt(int index) { return stateOf(state_.load(std::memory_order_acquire)).takeInput(index); }

void Node::publishMessage(std::string_view output, Message message) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const int i = s.findOutput(output);
  if (i < 0) unknown(s, "output", output, s.manifest().listOutputs());
  publishAt(i, std::move(message));
}

void Node::publishAt(int index, Message&& message) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const TypeInfo* want = s.manifest().outputs[index].type;
  // the port's own type first: the common case, one comparison
  if (message.type() != want && !message.isNothing() && !message.isEndOfSequence() && !compatible(message.type(), want)) {
    throw std::invalid_argument(nodeLabel(s.name()) + " published a " + message.typeName() + " on output '" +
                                s.manifest().outputs[index].name + "', which carries " + want->name);
  }
  s.setOutput(index, std::move(message));
}

const ParamValue& Node::paramValue(std::string_view name) const {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const int i = s.findParam(name);
  if (i < 0) unknown(s, "parameter", name, s.manifest().listParams());
  return s.activeParam(i);
}

const ParamValue& Node::paramAt(int index) const { return stateOf(state_.load(std::memory_order_acquire)).activeParam(index); }

void Node::updateParam(std::string_view name, ParamValue value) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const int i = s.findParam(name);
  if (i < 0) unknown(s, "parameter", name, s.manifest().listParams());
  if (auto st = s.manifest().params[i].validate(value); !st)
    throw std::invalid_argument(nodeLabel(s.name()) + ": " + st.message());
  s.updateParam(i, std::move(value));
}

void Node::requestEdit(std::string_view name, ParamValue value) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  if (auto* edits = s.editRequests()) edits->push(s.weak_from_this(), std::string(name), std::move(value));
}

void Node::runLater(std::function<void()> fn) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  s.postFromAnywhere([fn = std::move(fn)](detail::NodeState& n) { n.runHandler("a function it ran later", fn); });
}

void Node::describeGraph(std::function<void(const GraphSnapshot&)> done) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  auto* edits = s.editRequests();
  if (!edits) return;
  std::weak_ptr<detail::NodeState> weak = s.weak_from_this();
  edits->describe([weak, done = std::move(done)](GraphSnapshot d) {
    auto n = weak.lock();
    if (!n) return;
    auto shared = std::make_shared<GraphSnapshot>(std::move(d));
    n->postFromAnywhere(
        [done, shared](detail::NodeState& state) { state.runHandler("its graph's description", [&] { done(*shared); }); });
  });
}

void Node::trigger(std::string_view name) {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const int i = s.findTrigger(name);
  if (i < 0) unknown(s, "trigger", name, s.manifest().listTriggers());
  s.fireTrigger(i);
}

void Node::endSequence() {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  for (std::size_t i = 0; i < s.outputCount(); ++i) s.setOutput(static_cast<int>(i), Message::endOfSequence());
}

std::vector<ParamTarget> Node::parameterTargets(std::string_view output) const {
  auto& s = stateOf(state_.load(std::memory_order_acquire));
  const int i = s.findOutput(output);
  if (i < 0) unknown(s, "output", output, s.manifest().listOutputs());
  return s.parameterTargets(i);
}

void Node::triggerAt(int index) { stateOf(state_.load(std::memory_order_acquire)).fireTrigger(index); }

void Node::reportError(const std::string& text) { stateOf(state_.load(std::memory_order_acquire)).reportError(text); }

void Node::log(LogLevel level, const std::string& text) const { apex::log(level, name(), text); }

void Node::throwWrongType(std::string_view input, const Message& m, const TypeInfo* want) const {
  throw std::invalid_argument(nodeLabel(name()) + ": input '" + std::string(input) + "' holds a " + m.typeName() + ", not a " +
                              want->name);
}

void Node::throwWrongParamType(std::string_view n) const {
  throw std::invalid_argument(nodeLabel(name()) + ": parameter '" + std::string(n) + "' is read with the wrong C++ type");
}

}  // namespace apex
