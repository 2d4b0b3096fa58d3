#include "param_mirror.hpp"

#include <set>

namespace apex {
namespace ros_host {
namespace {

XmlRpc::XmlRpcValue numbers(std::initializer_list<double> values) {
  XmlRpc::XmlRpcValue v;
  v.setSize(static_cast<int>(values.size()));
  int i = 0;
  for (double d : values) v[i++] = d;
  return v;
}

XmlRpc::XmlRpcValue toXmlRpc(const ParamValue& value) {
  struct Visitor {
    XmlRpc::XmlRpcValue operator()(bool b) const { return XmlRpc::XmlRpcValue(b); }
    XmlRpc::XmlRpcValue operator()(int i) const { return XmlRpc::XmlRpcValue(i); }
    XmlRpc::XmlRpcValue operator()(double d) const { return XmlRpc::XmlRpcValue(d); }
    XmlRpc::XmlRpcValue operator()(const std::string& s) const { return XmlRpc::XmlRpcValue(s); }
    XmlRpc::XmlRpcValue operator()(const Interval& i) const { return numbers({i.low, i.high}); }
    XmlRpc::XmlRpcValue operator()(const Pair& p) const { return numbers({p.first, p.second}); }
    XmlRpc::XmlRpcValue operator()(const Color& c) const {
      XmlRpc::XmlRpcValue v;
      v.setSize(3);
      v[0] = c.r, v[1] = c.g, v[2] = c.b;
      return v;
    }
    XmlRpc::XmlRpcValue operator()(const std::vector<double>& list) const {
      XmlRpc::XmlRpcValue v;
      v.setSize(static_cast<int>(list.size()));
      for (std::size_t i = 0; i < list.size(); ++i) v[static_cast<int>(i)] = list[i];
      return v;
    }
    XmlRpc::XmlRpcValue operator()(const std::vector<std::string>& list) const {
      XmlRpc::XmlRpcValue v;
      v.setSize(static_cast<int>(list.size()));
      for (std::size_t i = 0; i < list.size(); ++i) v[static_cast<int>(i)] = list[i];
      return v;
    }
  };
  return std::visit(Visitor{}, value);
}

}  // namespace

void ParamMirror::update(const Graph& graph, const GraphState& state) {
  std::set<std::string> seen;
  for (const auto& node : state.nodes) {
    for (const auto& p : node.parameters) {
      const std::string key = "nodes/" + node.name + "/" + p.name;
      seen.insert(key);
      auto it = last_.find(key);
      if (it != last_.end() && it->second == p.value) continue;
      auto value = graph.parameterValue(node.name, p.name);
      if (!value) continue;  // removed meanwhile
      nh_.setParam(key, toXmlRpc(value.value()));
      last_[key] = p.value;
    }
  }
  for (auto it = last_.begin(); it != last_.end();) {
    if (seen.count(it->first)) {
      ++it;
      continue;
    }
    nh_.deleteParam(it->first);
    it = last_.erase(it);
  }
}

}  // namespace ros_host
}  // namespace apex
