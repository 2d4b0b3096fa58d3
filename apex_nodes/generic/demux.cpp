// Demux: the demultiplexer, Select's opposite: one input to the output chosen by `choice`.
#include "apex/core/registry.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Demux : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::OutputPort<apex::Any> kOut0{"out_0", "`in` (the same object) if `choice` is 0, else Nothing"};
  static inline const apex::OutputPort<apex::Any> kOut1{"out_1", "`in` if `choice` is 1, else Nothing"};
  static inline const apex::ParamDecl<int> kOutputs =
      param::integer("outputs").range(2, 16).step(1).init(2).describe("how many outputs: out_0, out_1, ...").shapesInterface();
  static inline const apex::ParamDecl<int> kChoice =
      param::integer("choice").range(0, 15).step(1).describe("the output that gets the message").interactive();
  static apex::Manifest manifest() {
    return apex::Manifest("Sends its input on the output chosen by `choice` and Nothing on the others (Select's opposite)")
        .inCategory("flow")
        .input(kIn)
        .output(kOut0)
        .output(kOut1)
        .param(kOutputs)
        .param(kChoice)
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.outputs.clear();
          for (int i = 0; i < p.get<int>(kOutputs.name()); ++i)
            m.output<apex::Any>("out_" + std::to_string(i), "`in` if `choice` is " + std::to_string(i) + ", else Nothing");
          return apex::Status::ok();
        });
  }
  void process() override {
    const auto& ports = interface().outputs;
    const int choice = choice_.get();
    if (choice >= static_cast<int>(ports.size()))
      throw std::invalid_argument("choice " + std::to_string(choice) + " but only " + std::to_string(ports.size()) +
                                  " outputs (out_0 to out_" + std::to_string(ports.size() - 1) + ")");
    publishMessage(ports[choice].name, in_.take());
  }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Param<int> choice_{this, kChoice};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Demux, "apex_nodes/Demux");
