// ICP: PCL's IterativeClosestPoint (point to point) on the x, y, z views of source and target; the
// source comes out moved onto the target with every field, and the transform that moves it.
#include <pcl/registration/icp.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/registration.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Icp : public RegistrationNode<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> {
 public:
  static inline const apex::ParamDecl<int> kMaxIterations = param::integer("max_iterations").range(1, 10000).step(1).init(50);
  static inline const apex::ParamDecl<double> kMaxCorrespondenceDistance = param::number("max_correspondence_distance")
                                                                               .range(0.001, 100.0)
                                                                               .step(0.001)
                                                                               .init(0.5)
                                                                               .describe("metres: farther pairs are not matched");
  static inline const apex::ParamDecl<double> kTransformationEpsilon =
      param::number("transformation_epsilon")
          .range(0.0, 1.0)
          .step(1e-9)
          .init(1e-8)
          .describe("stop when an iteration moves less (squared translation, m^2); 0: off");
  static inline const apex::ParamDecl<double> kEuclideanFitnessEpsilon =
      param::number("euclidean_fitness_epsilon")
          .range(0.0, 10.0)
          .step(1e-6)
          .init(0.0)
          .describe("stop when the mean squared error changes by less (relative); 0: off");
  static apex::Manifest manifest() {
    return registrationManifest("Aligns a cloud to another by iterative closest points (PCL's ICP)")
        .param(kMaxIterations)
        .param(kMaxCorrespondenceDistance)
        .param(kTransformationEpsilon)
        .param(kEuclideanFitnessEpsilon);
  }

 private:
  void configure(pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>& icp) override {
    icp.setMaximumIterations(max_iterations_.get());
    icp.setMaxCorrespondenceDistance(max_correspondence_distance_.get());
    icp.setTransformationEpsilon(transformation_epsilon_.get());
    icp.setEuclideanFitnessEpsilon(euclidean_fitness_epsilon_.get());
  }
  apex::Param<int> max_iterations_{this, kMaxIterations};
  apex::Param<double> max_correspondence_distance_{this, kMaxCorrespondenceDistance};
  apex::Param<double> transformation_epsilon_{this, kTransformationEpsilon};
  apex::Param<double> euclidean_fitness_epsilon_{this, kEuclideanFitnessEpsilon};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Icp, "apex_nodes/ICP");
