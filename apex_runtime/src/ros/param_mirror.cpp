#include "param_mirror.hpp"

#include <xmlrpcpp/XmlRpcException.h>

#include <map>
#include <utility>
#include <vector>

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
  std::map<std::string, std::string> now;  // key → value text
  std::vector<std::pair<std::string, std::string>> changed;  // key, node
  for (const auto& node : state.nodes)
    for (const auto& p : node.parameters) {
      const std::string key = "nodes/" + node.name + "/" + p.name;
      now[key] = p.value;
      auto it = last_.find(key);
      if (it == last_.end() || it->second != p.value) changed.emplace_back(key, node.name);
    }
  std::size_t gone = 0;
  for (const auto& [key, value] : last_) gone += now.count(key) ? 0 : 1;
  if (changed.size() + gone > kOneByOne && setAll(graph, state)) {
    last_ = std::move(now);
    return;
  }
  for (const auto& [key, node] : changed) {
    auto value = graph.parameterValue(node, key.substr(key.rfind('/') + 1));
    if (!value) continue;  // removed meanwhile
    nh_.setParam(key, toXmlRpc(value.value()));
    last_[key] = now[key];
  }
  for (auto it = last_.begin(); it != last_.end();) {
    if (now.count(it->first)) {
      ++it;
      continue;
    }
    nh_.deleteParam(it->first);
    it = last_.erase(it);
  }
}

bool ParamMirror::setAll(const Graph& graph, const GraphState& state) {
  XmlRpc::XmlRpcValue tree;
  try {
    for (const auto& node : state.nodes) {
      XmlRpc::XmlRpcValue values;
      for (const auto& p : node.parameters)
        if (auto value = graph.parameterValue(node.name, p.name)) values[p.name] = toXmlRpc(value.value());
      if (values.getType() != XmlRpc::XmlRpcValue::TypeStruct) continue;  // none (an empty entry is invalid)
      XmlRpc::XmlRpcValue* at = &tree;
      std::size_t from = 0;
      for (std::size_t slash; (slash = node.name.find('/', from)) != std::string::npos; from = slash + 1)
        at = &(*at)[node.name.substr(from, slash - from)];  // a node in a subgraph: nested
      XmlRpc::XmlRpcValue& entry = (*at)[node.name.substr(from)];  // (a subgraph's nodes may be in it already)
      for (auto& [param, value] : values) entry[param] = value;
    }
  } catch (const XmlRpc::XmlRpcException&) {  // a path that is a node and a subgraph's: one by one
    return false;
  }
  if (tree.getType() == XmlRpc::XmlRpcValue::TypeStruct)
    nh_.setParam("nodes", tree);  // replaces the tree: what is gone goes with it
  else nh_.deleteParam("nodes");  // no parameter left
  return true;
}

}  // namespace ros_host
}  // namespace apex
