// A node type's static interface: declared once, listed without an instance.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "apex/core/declare.hpp"
#include "apex/core/message.hpp"
#include "apex/core/param.hpp"
#include "apex/core/result.hpp"

namespace apex {

class Node;

/** @brief A data input or output. */
struct PortSpec {
  std::string name;
  const TypeInfo* type = nullptr;
  bool optional = false;  ///< inputs only: ignored while unconnected, may receive Nothing
  std::string description;
};

/** @brief A slot (receives events) or a trigger (sends them). Slots have a handler. */
struct EventSpec {
  std::string name;
  std::string description;
  std::function<void(Node&)> handler;  ///< slots only; runs on the node's thread group
};

/** @brief How a node without inputs is scheduled. */
enum class SourceMode {
  FreeRunning,  ///< fires whenever its outputs are free
  Driven,  ///< fires only after notifyNewData(): an outside callback has data
  /** Driven, holding only the newest of what arrives (a subscriber): it sends to a receiver
   *  only once that receiver's firing has ended, not when it took the last message, so the
   *  receiver's next firing starts from the newest frame, in any thread group. */
  Newest,
};

struct Manifest;

/** @brief One instance's parameter values by name, as an interface function sees them. */
class ParamValues {
 public:
  ParamValues() = default;
  void set(std::string name, ParamValue value) { values_[std::move(name)] = std::move(value); }
  /** @brief The value as T; throws std::invalid_argument for an unknown name or another type. */
  template <class T>
  const T& get(std::string_view name) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw std::invalid_argument("no parameter '" + std::string(name) + "'");
    if (const T* v = std::get_if<T>(&it->second)) return *v;
    throw std::invalid_argument("parameter '" + std::string(name) + "' is read with the wrong C++ type");
  }

 private:
  std::map<std::string, ParamValue, std::less<>> values_;
};

/** @brief Makes an instance's interface from its parameters: gets the type's manifest in
 *  `iface` and adds, removes or retypes ports, events and parameters (not the built-in
 *  events, nor the parameters marked shapesInterface()). An error refuses the parameter
 *  change that asked for it. Must be a function of `params` only: it runs on the thread
 *  of the edit, possibly while the node's process() runs. */
using InterfaceFn = std::function<Status(const ParamValues& params, Manifest& iface)>;

/** @brief Everything the registry knows about a node type before creating one. */
struct Manifest {
  std::string description;
  std::string category;  ///< where the palette and docs/nodes.md list the type, e.g. "image filters"
  /** What the node keeps from one frame to the next (a background model, the last frame, a file
   *  it writes), so that a re-run of a held frame changes it; empty: its output is a function of
   *  its inputs and parameters alone. */
  std::string keeps;
  std::vector<PortSpec> inputs, outputs;
  std::vector<ParamSpec> params;
  std::vector<EventSpec> slots, triggers;
  SourceMode source_mode = SourceMode::FreeRunning;
  InterfaceFn shape;  ///< empty: every instance has exactly these ports

  explicit Manifest(std::string desc = {}) : description(std::move(desc)) {}

  /** @brief The type's category, e.g. `Manifest("Smooths an image").inCategory("image filters")`. */
  Manifest& inCategory(std::string name) {
    category = std::move(name);
    return *this;
  }

  /** @brief What the node keeps from frame to frame, e.g. `.keepsState("its background model")`:
   *  the panel says so on a held frame, whose re-runs change it. */
  Manifest& keepsState(std::string what) {
    keeps = std::move(what);
    return *this;
  }

  template <class T>
  Manifest& input(std::string name, std::string desc = {}) {
    inputs.push_back({std::move(name), typeOf<T>(), false, std::move(desc)});
    return *this;
  }
  template <class T>
  Manifest& optionalInput(std::string name, std::string desc = {}) {
    inputs.push_back({std::move(name), typeOf<T>(), true, std::move(desc)});
    return *this;
  }
  template <class T>
  Manifest& output(std::string name, std::string desc = {}) {
    outputs.push_back({std::move(name), typeOf<T>(), false, std::move(desc)});
    return *this;
  }
  /** @brief A port declared once (declare.hpp): `.input(kImage)`. */
  template <class T>
  Manifest& input(const InputPort<T>& port) {
    inputs.push_back({port.name, typeOf<T>(), port.optional, port.description});
    return *this;
  }
  template <class T>
  Manifest& output(const OutputPort<T>& port) {
    outputs.push_back({port.name, typeOf<T>(), false, port.description});
    return *this;
  }
  Manifest& trigger(const TriggerPort& port) { return trigger(port.name, port.description); }
  /** @brief A parameter: a ParamDecl (declare.hpp) or a ParamSpec. */
  Manifest& param(ParamSpec spec) {
    params.push_back(std::move(spec));
    return *this;
  }
  /** @brief A slot calling `fn` on the node, e.g. .slot("reset", &Counter::reset). */
  template <class N>
  Manifest& slot(std::string name, void (N::*fn)(), std::string desc = {}) {
    slots.push_back({std::move(name), std::move(desc), [fn](Node& n) { (static_cast<N&>(n).*fn)(); }});
    return *this;
  }
  Manifest& trigger(std::string name, std::string desc = {}) {
    triggers.push_back({std::move(name), std::move(desc), nullptr});
    return *this;
  }
  Manifest& driven() {
    source_mode = SourceMode::Driven;
    return *this;
  }
  /** @brief Driven, keeping only the newest of what arrives (SourceMode::Newest). */
  Manifest& keepsNewest() {
    source_mode = SourceMode::Newest;
    return *this;
  }
  /** @brief Interfaces per instance: `fn` decides the ports from the parameters marked
   *  shapesInterface(), when a node is made and whenever one of them is set. The ports
   *  declared above are what the palette shows and what `fn` starts from. */
  Manifest& shapedBy(InterfaceFn fn) {
    shape = std::move(fn);
    return *this;
  }

  /** @brief Names valid and unique per side of a connection, defaults within their specs. */
  Status check() const;

  const PortSpec* findInput(const std::string& name) const;
  const PortSpec* findOutput(const std::string& name) const;
  const ParamSpec* findParam(const std::string& name) const;
  const EventSpec* findSlot(const std::string& name) const;
  const EventSpec* findTrigger(const std::string& name) const;
  /** @brief Names of every input, or output, slot, trigger, parameter: for error messages. */
  std::string listInputs() const;
  std::string listOutputs() const;
  std::string listParams() const;
  std::string listSlots() const;
  std::string listTriggers() const;
};

/** Built-in events every node has. */
inline constexpr const char* kEnableSlot = "enable";
inline constexpr const char* kDisableSlot = "disable";
inline constexpr const char* kProcessedTrigger = "processed";

}  // namespace apex
