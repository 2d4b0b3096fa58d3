// NDT: PCL's NormalDistributionsTransform on the x, y, z views of source and target; the source
// comes out moved onto the target with every field, and the transform that moves it.
#include <pcl/registration/ndt.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/registration.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Ndt : public RegistrationNode<pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ>> {
 public:
  static inline const apex::ParamDecl<double> kResolution =
      param::number("resolution").range(0.01, 100.0).step(0.01).init(1.0).describe("metres: the side of the target's cells");
  static inline const apex::ParamDecl<double> kStepSize =
      param::number("step_size").range(0.001, 10.0).step(0.001).init(0.1).describe("metres: the line search's longest step");
  static inline const apex::ParamDecl<double> kTransformationEpsilon =
      param::number("transformation_epsilon")
          .range(0.0, 1.0)
          .step(1e-6)
          .init(0.01)
          .describe("stop when an iteration moves less (squared translation, m^2); 0: run max_iterations");
  static inline const apex::ParamDecl<int> kMaxIterations = param::integer("max_iterations").range(1, 10000).step(1).init(35);
  static apex::Manifest manifest() {
    return registrationManifest("Aligns a cloud to another by the normal distributions transform (PCL's NDT)")
        .param(kResolution)
        .param(kStepSize)
        .param(kTransformationEpsilon)
        .param(kMaxIterations);
  }

 private:
  void configure(pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ>& ndt) override {
    ndt.setResolution(static_cast<float>(resolution_.get()));
    ndt.setStepSize(step_size_.get());
    ndt.setTransformationEpsilon(transformation_epsilon_.get());
    ndt.setMaximumIterations(max_iterations_.get());
  }
  apex::Param<double> resolution_{this, kResolution};
  apex::Param<double> step_size_{this, kStepSize};
  apex::Param<double> transformation_epsilon_{this, kTransformationEpsilon};
  apex::Param<int> max_iterations_{this, kMaxIterations};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Ndt, "apex_nodes/NDT");
