// A hosted nodelet's dynamic_reconfigure parameters as parameters of its node. What a nodelet
// offers is known only once it is loaded (its server's latched `parameter_descriptions` under
// its name), so the node keeps it in a parameter of its own, `reconfigure` (one entry per
// offered parameter, YAML), that shapes its interface: the node asks for it to be set after each
// load (Node::requestEdit), and a saved graph carries it, so the offered values load with it.
#pragma once

#include <XmlRpcValue.h>
#include <dynamic_reconfigure/ConfigDescription.h>

#include <map>
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
  std::string value;  ///< YAML text: the nodelet's default
  std::string description;
  std::vector<std::pair<std::string, std::string>> options;  ///< an enum: name and value (YAML text)
};

/** What a loaded nodelet offers. */
struct Offers {
  std::vector<std::string> entries;  ///< `reconfigure` entries (sorted by name)
  std::map<std::string, std::string> values;  ///< by the nodelet's name: the value it has now, YAML text
};

/** What the loaded nodelet offers; none if it serves no dynamic_reconfigure under its name. Waits
 *  up to `timeout` seconds for the server's latched description and values; throws
 *  std::runtime_error naming the nodelet if they do not come. */
Offers offeredBy(HostedNodelet& nodelet, double timeout);

/** The `reconfigure` entry of one parameter of a dynamic_reconfigure description (its type,
 *  bounds where finite, description, an enum's options; its value: the default). */
std::string entryOf(const dynamic_reconfigure::ParamDescription& param, const dynamic_reconfigure::ConfigDescription& all);

/** Parses `reconfigure` entries; an error names the entry. */
apex::Result<std::vector<Offered>> parseOffered(const std::vector<std::string>& entries);

/** Adds the offered parameters to an interface (NodeletHost's shape). */
apex::Status addOffered(const std::vector<std::string>& entries, apex::Manifest& m);

/** The nodelet's value `text` (YAML) as the node's parameter holds it; nullopt if the parameter
 *  cannot hold it (an enum value that is none of its options, out of its bounds). */
std::optional<apex::ParamValue> valueOf(const Offered& offered, const std::string& text);

/** The value as the nodelet takes it (an enum's option: its value). */
XmlRpc::XmlRpcValue toNodelet(const Offered& offered, const apex::ParamValue& value);

/** Sets one offered parameter of the loaded nodelet (its set_parameters service) within `timeout`
 *  seconds; throws std::runtime_error naming the nodelet and the parameter if it does not answer. */
void reconfigure(HostedNodelet& nodelet, const Offered& offered, const apex::ParamValue& value, double timeout);

}  // namespace nodelet_host
}  // namespace apex_nodes
