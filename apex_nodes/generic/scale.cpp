// Scale: multiplies a number by a factor.
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Scale : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Multiplies a number by a factor")
        .input<double>("in")
        .output<double>("out")
        .param(apex::param::real("factor", 1.0).describe("the factor"));
  }
  void process() override { out_.publish(*in_.get() * factor_.get()); }

 private:
  apex::Input<double> in_{this, "in"};
  apex::Output<double> out_{this, "out"};
  apex::Param<double> factor_{this, "factor"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Scale, "apex_nodes/Scale");
