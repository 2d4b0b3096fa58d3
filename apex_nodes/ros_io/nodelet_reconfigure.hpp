// A hosted nodelet's dynamic_reconfigure parameters as parameters of its node. What a nodelet
// offers is known only once it is loaded (its server's latched `parameter_descriptions` under
// its name), so the node keeps it in a parameter of its own, `reconfigure` (one entry per
// offered parameter, YAML), that shapes its interface: the node asks for it to be set after each
// load (Node::requestEdit), and a saved graph carries it, so the offered values load with it.
#pragma once

#include <XmlRpcValue.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/manifest.hpp"
#include "nodelet_host.hpp"

namespace apex_nodes {
namespace nodelet_host {

/** One parameter a nodelet offers, as an entry of `reconfigure` says it. */
struct Offered {
  std::string name;  ///< as the nodelet names it
  std::string param;  ///< the node's parameter: the name, or nodelet_<name> where the host has one of that name
  std::string type;  ///< bool, int, double or str (dynamic_reconfigure's)
  std::optional<double> min, max;  ///< finite bounds only
  std::string value;  ///< YAML text: its value when the nodelet was loaded
  std::string description;
  std::vector<std::pair<std::string, std::string>> options;  ///< an enum: name and value (YAML text)
};

/** What the loaded nodelet offers, as `reconfigure` entries (sorted by name); none if it serves
 *  no dynamic_reconfigure under its name. Waits up to `timeout` seconds for the server's latched
 *  description and values; throws std::runtime_error naming the nodelet if they do not come. */
std::vector<std::string> offeredBy(HostedNodelet& nodelet, double timeout);

/** Parses `reconfigure` entries; an error names the entry. */
apex::Result<std::vector<Offered>> parseOffered(const std::vector<std::string>& entries);

/** Adds the offered parameters to an interface (NodeletHost's shape). */
apex::Status addOffered(const std::vector<std::string>& entries, apex::Manifest& m);

/** Its value when the nodelet was loaded, as the node's parameter holds it. */
apex::ParamValue valueOf(const Offered& offered);

/** The value as the nodelet takes it (an enum's option: its value). */
XmlRpc::XmlRpcValue toNodelet(const Offered& offered, const apex::ParamValue& value);

/** Sets one offered parameter of the loaded nodelet (its set_parameters service) within `timeout`
 *  seconds; throws std::runtime_error naming the nodelet and the parameter if it does not answer. */
void reconfigure(HostedNodelet& nodelet, const Offered& offered, const apex::ParamValue& value, double timeout);

}  // namespace nodelet_host
}  // namespace apex_nodes
