// What may feed what: kinds, types, occupied inputs, cycles. One implementation over
// any view of a graph: the core's Graph checks every connect with it, and the panel
// checks its copy of ~graph with it while a link is dragged.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/result.hpp"

namespace apex {

enum class PortKind { Output, ParamOut, Trigger, Input, ParamIn, Slot };

/** @brief A port as the rules see it. */
struct PortView {
  std::string name;
  PortKind kind;
  std::string type;  ///< the type's name (one per type in a process); "any" fits all; empty for events
};

/** @brief A node as the rules see it. */
struct NodeView {
  std::string type;  ///< its type id
  bool placeholder = false;  ///< its type is not loaded: connections are kept as written
  std::vector<PortView> ports;  ///< inputs, outputs, slots, triggers, and both ports of each interactive parameter
  std::vector<std::string> params;  ///< every parameter, interactive or not
};

/** @brief What the rules ask of a graph. */
class ConnectionView {
 public:
  virtual ~ConnectionView() = default;
  virtual std::optional<NodeView> node(const std::string& name) const = 0;
  /** The node feeding input or parameter `port` of `node`; "" if nothing does. */
  virtual std::string feeding(const std::string& node, const std::string& port) const = 0;
  /** True if this trigger-to-slot connection exists. */
  virtual bool hasEvent(const ConnectionDescription& c) const = 0;
  /** The nodes `node` feeds through their data inputs (not parameters). */
  virtual std::vector<std::string> dataReceivers(const std::string& node) const = 0;
};

/** @brief The two ends of an allowed connection (both empty when an end is a placeholder). */
struct ConnectionEnds {
  std::optional<PortView> from, to;
};

/** @brief Checks `c` against every rule; the error reads "cannot connect a/x -> b/y: why". */
Result<ConnectionEnds> checkConnection(const ConnectionView& view, const ConnectionDescription& c);

/** @brief Port `port` of node `name` as a connection's source (`source`) or target; the
 *  error says what the node has instead. */
Result<PortView> connectionEnd(const std::string& name, const NodeView& node, const std::string& port, bool source);
/** @brief "a/x -> b/y" */
std::string connectionLabel(const ConnectionDescription& c);
/** @brief "output", "parameter", "trigger", "input", "slot" */
const char* portKindName(PortKind kind);
/** @brief PortKind from the names of apex/PortInfo ("param_in", ...); false if unknown. */
bool portKindFromName(const std::string& name, PortKind* kind);

}  // namespace apex
