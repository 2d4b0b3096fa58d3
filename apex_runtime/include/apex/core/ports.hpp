// Typed handles: a node names each port, parameter and trigger once, as a member, and
// reads or writes it through the handle, found by index at every use (no string look-up
// per firing):
//
//   class Gain : public apex::Node {
//     apex::Input<int> in_{this, "in"};
//     apex::Output<int> out_{this, "out"};
//     apex::Param<int> gain_{this, "gain"};
//     void process() override { out_.publish(*in_.get() * gain_.get()); }
//   };
//
// A handle that names nothing in the manifest, or with the wrong C++ type, is refused when
// the type is registered, with a message saying what to write. Handles are resolved again
// when an instance's interface changes (Manifest::shapedBy); using one whose port is gone
// throws, naming it.
#pragma once

#include <memory>
#include <string>
#include <variant>

#include "apex/core/declare.hpp"
#include "apex/core/message.hpp"
#include "apex/core/node.hpp"
#include "apex/core/param.hpp"
#include "apex/core/result.hpp"

namespace apex {

struct Manifest;

/** @brief What handles have in common: the node, the name, the index in the interface. */
class Handle {
 public:
  enum class Of { Input, Output, Param, Trigger };
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  const std::string& name() const { return name_; }
  /** @brief Finds the handle's port in `iface`; an error says what to write instead. */
  Status resolve(const Manifest& iface);

 protected:
  /** `type`: the C++ type of an input or output; `holds`: whether a value has the C++ type of a Param<T>. */
  Handle(Node* node, Of of, std::string name, const TypeInfo* type, bool (*holds)(const ParamValue&), std::string cpp);
  ~Handle();  // leaves the node's list
  /** The index in the node's current interface; throws if the port is not in it. */
  int index() const {
    if (index_ < 0) throwGone();
    return index_;
  }
  const Message& inputAt(int i) const { return node_->inputAt(i); }
  Message takeInputAt(int i) const { return node_->takeInputAt(i); }
  void publishAt(int i, Message&& m) const { node_->publishAt(i, std::move(m)); }
  const ParamValue& paramAt(int i) const { return node_->paramAt(i); }
  void triggerAt(int i) const { node_->triggerAt(i); }
  [[noreturn]] void throwWrongType(const Message& m) const;

 private:
  [[noreturn]] void throwGone() const;
  Node* node_;
  int index_ = -1;  // beside node_: the two a firing reads (one cache line)
  Of of_;
  std::string name_;
  const TypeInfo* type_;
  bool (*holds_)(const ParamValue&);
  std::string cpp_;  // "Input<int>": for messages
};

/** @brief An input of type T. */
template <class T>
class Input : public Handle {
 public:
  Input(Node* node, std::string name)
      : Handle(node, Of::Input, std::move(name), typeOf<T>(), nullptr, "Input<" + typeOf<T>()->name + ">") {}
  /** @brief The input a port constant declares: only an InputPort<T> fits (declare.hpp). */
  Input(Node* node, const InputPort<T>& port) : Input(node, std::string(port.name)) {}
  /** @brief This firing's payload; nullptr when the input holds Nothing. */
  std::shared_ptr<const T> get() const {
    const Message& m = message();
    if (m.isNothing()) return nullptr;
    auto p = m.as<T>();
    if (!p) throwWrongType(m);
    return p;
  }
  /** @brief True when the input holds a message (not Nothing) this firing. */
  bool has() const { return !message().isNothing(); }
  const Message& message() const { return inputAt(index()); }
  /** @brief This firing's message, moved out: the input holds Nothing for the rest of the firing.
   *  A node that passes its input on unchanged (`out_.publishMessage(in_.take())`) so spares the
   *  message's reference count a rise and a fall: two atomic operations per message. */
  Message take() { return takeInputAt(index()); }
};

/** @brief An output of type T; an output not published in a firing sends Nothing. */
template <class T>
class Output : public Handle {
 public:
  Output(Node* node, std::string name)
      : Handle(node, Of::Output, std::move(name), typeOf<T>(), nullptr, "Output<" + typeOf<T>()->name + ">") {}
  Output(Node* node, const OutputPort<T>& port) : Output(node, std::string(port.name)) {}
  void publish(T value) const { publishAt(index(), Message::make<T>(std::move(value))); }
  void publish(std::shared_ptr<const T> payload) const { publishAt(index(), Message::share<T>(std::move(payload))); }
  /** @brief Sends a message as it is, e.g. one taken from an input (no copy). */
  void publishMessage(Message m) const { publishAt(index(), std::move(m)); }
};

/** @brief A parameter's current value, stable for the whole firing. */
template <class T>
class Param : public Handle {
 public:
  Param(Node* node, std::string name)
      : Handle(
            node, Of::Param, std::move(name), nullptr, [](const ParamValue& v) { return std::holds_alternative<T>(v); },
            "Param<" + typeOf<T>()->name + ">") {}
  Param(Node* node, const ParamDecl<T>& decl) : Param(node, decl.name()) {}
  const T& get() const { return std::get<T>(paramAt(index())); }
};

/** @brief A typed choice's current value (ChoiceDecl): the value of the option it is set to. */
template <class V>
class Choice : public Param<std::string> {
 public:
  Choice(Node* node, const ChoiceDecl<V>& decl) : Param<std::string>(node, decl.name()), decl_(&decl) {}
  const V& get() const { return decl_->valueOf(text()); }
  /** @brief The option's name, e.g. for a message. */
  const std::string& text() const { return Param<std::string>::get(); }

 private:
  const ChoiceDecl<V>* decl_;
};

/** @brief Sends an event on a trigger. */
class Trigger : public Handle {
 public:
  Trigger(Node* node, std::string name) : Handle(node, Of::Trigger, std::move(name), nullptr, nullptr, "Trigger") {}
  Trigger(Node* node, const TriggerPort& port) : Trigger(node, std::string(port.name)) {}
  void fire() const { triggerAt(index()); }
};

}  // namespace apex
