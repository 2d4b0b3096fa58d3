// Typed handles: registered with their node when constructed, resolved against the node's
// interface when it joins a graph, when the interface changes, and once at registration.
#include "apex/core/ports.hpp"

#include <algorithm>
#include <stdexcept>

#include "apex/core/manifest.hpp"
#include "apex/core/node_names.hpp"
#include "names.hpp"

namespace apex {
Handle::Handle(Node* node, Of of, std::string name, const TypeInfo* type, bool (*holds)(const ParamValue&), std::string cpp)
    : node_(node), of_(of), name_(std::move(name)), type_(type), holds_(holds), cpp_(std::move(cpp)) {
  node_->handles_.push_back(this);
}

Handle::~Handle() {
  auto& list = node_->handles_;
  list.erase(std::remove(list.begin(), list.end(), this), list.end());
}

Status Handle::resolve(const Manifest& m) {
  index_ = -1;
  auto missing = [&](const char* what, const std::string& list) {
    return Status::error(cpp_ + " '" + name_ + "': manifest() declares no " + what + " '" + name_ + "' (" + what + "s: " + list +
                         "): name one of those, or declare it in manifest()");
  };
  int i = -1;
  switch (of_) {
    case Of::Input:
      if ((i = indexOf(m.inputs, name_)) < 0) return missing("input", m.listInputs());
      if (!compatible(m.inputs[i].type, type_))
        return Status::error(cpp_ + " '" + name_ + "': input '" + name_ + "' carries " + m.inputs[i].type->name +
                             ": write Input<" + m.inputs[i].type->name + ">");
      break;
    case Of::Output:
      if ((i = indexOf(m.outputs, name_)) < 0) return missing("output", m.listOutputs());
      if (!compatible(type_, m.outputs[i].type))
        return Status::error(cpp_ + " '" + name_ + "': output '" + name_ + "' carries " + m.outputs[i].type->name +
                             ": write Output<" + m.outputs[i].type->name + ">");
      break;
    case Of::Param:
      if ((i = indexOf(m.params, name_)) < 0) return missing("parameter", m.listParams());
      if (!holds_(m.params[i].default_value))
        return Status::error(cpp_ + " '" + name_ + "': parameter '" + name_ + "' is a " + m.params[i].kindName() + " of " +
                             m.params[i].portType()->name + ": write Param<" + m.params[i].portType()->name + ">");
      break;
    case Of::Trigger:
      if ((i = indexOf(m.triggers, name_)) < 0) return missing("trigger", m.listTriggers());
      break;
  }
  index_ = i;
  return Status::ok();
}

void Handle::throwGone() const {
  throw std::invalid_argument(nodeLabel(node_->name()) + ": " + cpp_ + " '" + name_ +
                              "' is not in this instance's interface (its parameters removed it)");
}

void Handle::throwWrongType(const Message& m) const {
  throw std::invalid_argument(nodeLabel(node_->name()) + ": input '" + name_ + "' holds a " + m.typeName() + ", not a " +
                              type_->name);
}

namespace detail {
Status resolveHandles(Node& node, const Manifest& iface) {
  Status first = Status::ok();
  for (Handle* h : node.handles_)
    if (auto st = h->resolve(iface); !st && first) first = st;
  return first;
}
}  // namespace detail

}  // namespace apex
