// A node type's static interface: declared once, listed without an instance.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "apex/core/message.hpp"
#include "apex/core/param.hpp"

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
  Driven,       ///< fires only after notifyNewData(): an outside callback has data
};

/** @brief Everything the registry knows about a node type before creating one. */
struct Manifest {
  std::string description;
  std::vector<PortSpec> inputs, outputs;
  std::vector<ParamSpec> params;
  std::vector<EventSpec> slots, triggers;
  SourceMode source_mode = SourceMode::FreeRunning;

  explicit Manifest(std::string desc = {}) : description(std::move(desc)) {}

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
