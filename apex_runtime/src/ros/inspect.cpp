#include "apex/ros/inspect.hpp"

#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <typeindex>

#include "apex/core/param.hpp"

namespace apex {
namespace {

std::mutex& tableMutex() {
  static std::mutex m;
  return m;
}
std::map<const TypeInfo*, Inspector>& table() {
  static std::map<const TypeInfo*, Inspector> t;
  return t;
}

template <class T>
std_msgs::String text(const T& v) {
  std_msgs::String s;
  s.data = toText(ParamValue(v));
  return s;
}

const bool kBuiltins = [] {
  addInspector<int, std_msgs::Int32>([](int v) {
    std_msgs::Int32 m;
    m.data = v;
    return m;
  });
  addInspector<double, std_msgs::Float64>([](double v) {
    std_msgs::Float64 m;
    m.data = v;
    return m;
  });
  addInspector<bool, std_msgs::Bool>([](bool v) {
    std_msgs::Bool m;
    m.data = v;
    return m;
  });
  addInspector<std::string, std_msgs::String>([](const std::string& v) {
    std_msgs::String m;
    m.data = v;
    return m;
  });
  addInspector<Interval, std_msgs::String>([](const Interval& v) { return text(v); });
  addInspector<Pair, std_msgs::String>([](const Pair& v) { return text(v); });
  addInspector<Color, std_msgs::String>([](const Color& v) { return text(v); });
  addInspector<std::vector<double>, std_msgs::String>([](const std::vector<double>& v) { return text(v); });
  return true;
}();

}  // namespace

bool registerInspector(const TypeInfo* type, Inspector inspector) {
  std::lock_guard<std::mutex> lock(tableMutex());
  table()[type] = std::move(inspector);
  return true;
}

namespace {
/** Sets one member of the inspector registered for `type`; false if none is. */
template <class Member, class Value>
bool amend(const TypeInfo* type, Member Inspector::*member, Value value) {
  std::lock_guard<std::mutex> lock(tableMutex());
  auto it = table().find(type);
  if (it == table().end()) return false;
  it->second.*member = std::move(value);
  return true;
}
}  // namespace

bool registerShrink(const TypeInfo* type, std::function<Message(const Message&, int)> shrink) {
  return amend(type, &Inspector::shrink, std::move(shrink));
}

bool registerDescribe(const TypeInfo* type, std::function<std::string(const Message&)> describe) {
  return amend(type, &Inspector::describe, std::move(describe));
}

std::vector<std::string> inspectedTypes() {
  (void)kBuiltins;
  std::vector<std::string> out;
  {
    std::lock_guard<std::mutex> lock(tableMutex());
    for (const auto& entry : table())
      if (entry.second.serialize) out.push_back(entry.first->name);
  }
  std::sort(out.begin(), out.end());
  return out;
}

Inspector findInspector(const TypeInfo* type) {
  (void)kBuiltins;
  {
    std::lock_guard<std::mutex> lock(tableMutex());
    auto it = table().find(type);
    if (it != table().end()) return it->second;
  }
  // Unknown types: their readable type name, so a person sees that messages flow.
  return Inspector{"std_msgs/String",
                   [](ros::NodeHandle& nh, const std::string& topic, const ros::SubscriberStatusCallback& connected) {
                     return nh.advertise<std_msgs::String>(topic, 1, connected);
                   },
                   [](const ros::Publisher& pub, const Message& m) {
                     std_msgs::String s;
                     s.data = "<" + m.typeName() + ">";
                     pub.publish(s);
                   },
                   nullptr,
                   nullptr,
                   nullptr,
                   nullptr};
}

}  // namespace apex
