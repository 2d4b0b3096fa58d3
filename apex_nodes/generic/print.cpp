// Print: logs each message it receives (numbers and strings by value).
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Print : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::ParamDecl<std::string> kPrefix = apex::param::text("prefix").describe("text before each line");
  static apex::Manifest manifest() {
    return apex::Manifest("Logs each message it receives").inCategory("flow").input(kIn).param(kPrefix);
  }
  void process() override { log(apex::LogLevel::Info, prefix_.get() + text(in_.message())); }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Param<std::string> prefix_{this, kPrefix};

  static std::string text(const apex::Message& m) {
    if (auto v = m.as<int>()) return std::to_string(*v);
    if (auto v = m.as<double>()) return apex::toText(*v);
    if (auto v = m.as<bool>()) return *v ? "true" : "false";
    if (auto v = m.as<std::string>()) return *v;
    return "<" + m.typeName() + ">";
  }
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Print, "apex_nodes/Print");
