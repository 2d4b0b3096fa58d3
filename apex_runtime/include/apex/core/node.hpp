// The base class of user node code. A node reads its inputs, parameters and
// publishes outputs from process(); the runtime calls it on the node's thread
// group, never concurrently with its slot handlers.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/log.hpp"
#include "apex/core/message.hpp"
#include "apex/core/param.hpp"

namespace apex {
struct Manifest;
class Graph;
}  // namespace apex

namespace apex {

class Handle;
class Node;

/** @brief A parameter input that one of a node's outputs feeds (Node::parameterTargets). */
struct ParamTarget {
  std::string node;  ///< the receiving node's name
  ParamSpec spec;  ///< its parameter's declaration (name, kind, range, step)
  ParamValue value;  ///< the value it holds now
};
/** @brief What Node::describeGraph hands over: the graph as plain data, and a maker of new empty
 *  graphs with its node types and host, e.g. for copies of a part of it that run beside it. */
struct GraphSnapshot {
  GraphDescription description;
  std::function<std::unique_ptr<Graph>()> makeGraph;
};

namespace detail {
class NodeState;
/** Resolves every typed handle of `node` against `iface`; the first error, naming the handle. */
Status resolveHandles(Node& node, const Manifest& iface);
}  // namespace detail

/** @brief What the program hosting a graph offers its nodes, e.g. the ROS runtime's node
 *  handles (apex/ros/node_handles.hpp). The core only passes it on. */
class Host {
 public:
  virtual ~Host() = default;
};

class Node {
 public:
  virtual ~Node() = default;
  Node() = default;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  /** @brief One firing: every connected input holds a message. Throwing puts the
   *  node in an error state for this firing; its outputs send Nothing. */
  virtual void process() = 0;
  /** @brief Called instead of process() in a firing where an input holds the end-of-sequence
   *  token (Message::endOfSequence()). The default sends it on every output (endSequence()),
   *  so the end of a sequence reaches every node downstream, after its last frame. A node
   *  that sums a sequence up publishes its result here instead. */
  virtual void endOfSequence() { endSequence(); }
  /** @brief Called on the node's thread group before a firing, after a parameter changed. */
  virtual void parameterChanged(const std::string& /*name*/) {}
  /** @brief Sources only: called on the node's thread group after an edit downstream of it
   *  (a parameter of a node its data reaches was set, a connection there changed). A source
   *  that holds a frame sends it again here, so the change shows on that frame (BagReader
   *  does). A burst of edits calls it about once per pass of a frame through the nodes it
   *  feeds, and always once after the last edit. */
  virtual void downstreamChanged() {}
  /** @brief Called once on the node's thread group when it is in a graph, before its
   *  first firing: start subscriptions or timers here, not in the constructor. */
  virtual void setup() {}

  /** @brief The node's name in its graph ("" before it is added to one). */
  const std::string& name() const;
  /** @brief This instance's ports, events and parameters: the type's manifest, or what its
   *  interface function (Manifest::shapedBy) made for the current parameters. For
   *  process() and slot handlers. */
  const Manifest& interface() const;
  /** @brief What the graph's host offers (Graph::setHost), or nullptr. */
  const Host* host() const;

  /** @brief For Driven sources: new data arrived from outside. Callable from any
   *  thread once the node is in a graph (a call from its constructor is lost);
   *  repeated calls before the next firing collapse into one. The other methods
   *  below are for process() and slot handlers only. */
  void notifyNewData();
  /** @brief notifyNewData() after a delay, from the node's thread group's timer (no
   *  thread of its own): a source at a rate calls it from process(). */
  void notifyAfter(double seconds);
  /** @brief Runs `fn` soon on the node's thread group as a slot handler runs (it may publish,
   *  trigger and report errors), never beside process(). Callable from any thread once the node is
   *  in a graph, e.g. from a worker it started or from another graph's tap; dropped if the node
   *  has left its graph by then. */
  void runLater(std::function<void()> fn);
  /** @brief A source that keeps only the newest lost `n` frames: newer ones came before the graph
   *  took them. Counted in its status (NodeStats::dropped). Callable from any thread. */
  void countDropped(std::uint64_t n = 1);

 protected:
  /** @brief The message at an input this firing (Nothing if none). */
  const Message& inputMessage(std::string_view input) const;
  /** @brief The payload at an input as T; nullptr when it holds Nothing.
   *  Throws std::invalid_argument for an unknown input, or a payload of another type. */
  template <class T>
  std::shared_ptr<const T> input(std::string_view name) const {
    const Message& m = inputMessage(name);
    if (m.isNothing()) return nullptr;
    auto p = m.as<T>();
    if (!p) throwWrongType(name, m, typeOf<T>());
    return p;
  }
  /** @brief True when the input holds a message (not Nothing) this firing. */
  bool hasInput(std::string_view name) const { return !inputMessage(name).isNothing(); }

  /** @brief Sends on an output; an output not published this firing sends Nothing.
   *  A slot handler may publish too: its messages leave when it returns, on outputs whose
   *  receivers have all read the last message (else it is dropped and the node reports it);
   *  outputs it does not publish send nothing at all. */
  void publishMessage(std::string_view output, Message message);
  template <class T>
  void publish(std::string_view output, std::shared_ptr<const T> payload) {
    publishMessage(output, Message::share<T>(std::move(payload)));
  }
  template <class T>
  void publish(std::string_view output, T value) {
    publishMessage(output, Message::make<T>(std::move(value)));
  }

  /** @brief The current value of a parameter; stable for the whole firing. */
  const ParamValue& paramValue(std::string_view name) const;
  template <class T>
  const T& param(std::string_view name) const {
    const ParamValue& v = paramValue(name);
    if (const T* p = std::get_if<T>(&v)) return *p;
    throwWrongParamType(name);
  }

  /** @brief Sets one of the node's own parameters from process() or a slot handler, e.g. a
   *  player's current frame: the value shows in the graph's description and goes out on the
   *  parameter's output with the firing's outputs; parameterChanged() is not called. A value set meanwhile by an edit
   *  wins. Throws std::invalid_argument for an unknown parameter or a value its spec refuses. */
  void updateParam(std::string_view name, ParamValue value);

  /** @brief Asks the graph to set one of the node's own parameters as an edit does: one that
   *  shapes the interface (ParamSpec::shapesInterface) changes the node's ports and parameters,
   *  e.g. to what a plugin it loaded offers, known only after setup(). From setup(), process(),
   *  parameterChanged() or a slot handler; applied soon after by a thread of the graph's, never
   *  within the call, and then parameterChanged() runs as after any edit. Dropped if the node is
   *  gone by then; a value its interface refuses becomes the node's error. */
  void requestEdit(std::string_view name, ParamValue value);

  /** @brief Asks for the whole graph as plain data (Graph::describe()) and a maker of graphs like
   *  it: made soon by a thread of the graph's (node code cannot read its graph: an edit may be
   *  waiting for its thread group) and handed to `done` as runLater() runs a function. From
   *  setup(), process() or a slot handler; dropped if the node has left the graph by then. */
  void describeGraph(std::function<void(const GraphSnapshot&)> done);

  /** @brief Sends the end-of-sequence token on every output this firing. */
  void endSequence();

  /** @brief Sends an event on one of the node's triggers. From process() or a slot handler,
   *  events leave after the messages it published: a receiver of both sees the data first. */
  void trigger(std::string_view name);

  /** @brief The parameter inputs an output feeds now, in connection order (for process() and
   *  slot handlers). Throws std::invalid_argument for an unknown output. */
  std::vector<ParamTarget> parameterTargets(std::string_view output) const;

  /** @brief Puts the node in an error state as a throw would, but what it published still goes
   *  out (e.g. a run that stopped gives its targets their values back). The next process() that
   *  neither throws nor reports clears it. For process(), slot handlers and setup(). */
  void reportError(const std::string& text);

  /** @brief Logs a line named after this node (rosconsole under the ROS host). */
  void log(LogLevel level, const std::string& text) const;

 private:
  friend class detail::NodeState;
  friend class Handle;
  friend Status detail::resolveHandles(Node& node, const Manifest& iface);
  // By index in the current interface: for typed handles (ports.hpp).
  const Message& inputAt(int index) const;
  Message takeInputAt(int index);
  void publishAt(int index, Message&& message);
  const ParamValue& paramAt(int index) const;
  void triggerAt(int index);
  std::vector<Handle*> handles_;  // registered by their constructors
  [[noreturn]] void throwWrongType(std::string_view input, const Message& m, const TypeInfo* want) const;
  [[noreturn]] void throwWrongParamType(std::string_view name) const;
  std::atomic<detail::NodeState*> state_{nullptr};  // set when the node joins a graph
};

}  // namespace apex
