// Scale: multiplies a number by a factor.
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Scale : public apex::Node {
 public:
  static inline const apex::InputPort<double> kIn{"in"};
  static inline const apex::OutputPort<double> kOut{"out"};
  static inline const apex::ParamDecl<double> kFactor = apex::param::number("factor").init(1.0).describe("the factor");
  static apex::Manifest manifest() {
    return apex::Manifest("Multiplies a number by a factor").inCategory("math").input(kIn).output(kOut).param(kFactor);
  }
  void process() override { out_.publish(*in_.get() * factor_.get()); }

 private:
  apex::Input<double> in_{this, kIn};
  apex::Output<double> out_{this, kOut};
  apex::Param<double> factor_{this, kFactor};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Scale, "apex_nodes/Scale");
