// PlaneSegmentation: RANSAC plane fit; inliers, outliers (every field) and the coefficients.
#include <pcl/segmentation/sac_segmentation.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {
namespace param = apex::param;

class PlaneSegmentation : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::OutputPort<Cloud> kInliers{"inliers", "the plane's points"};
  static inline const apex::OutputPort<Cloud> kOutliers{"outliers", "everything else"};
  static inline const apex::OutputPort<std::vector<double>> kCoefficients{"coefficients", "a, b, c, d of ax + by + cz + d = 0"};
  static inline const apex::ParamDecl<double> kDistanceThreshold =
      param::number("distance_threshold").range(0.001, 1.0).step(0.001).init(0.02).describe("metres");
  static inline const apex::ParamDecl<int> kMaxIterations = param::integer("max_iterations").range(1, 100000).step(1).init(200);
  static apex::Manifest manifest() {
    return apex::Manifest("Finds the dominant plane by RANSAC")
        .inCategory("cloud segmentation")
        .input(kCloud)
        .output(kInliers)
        .output(kOutliers)
        .output(kCoefficients)
        .param(kDistanceThreshold)
        .param(kMaxIterations);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in);
    pcl::SACSegmentation<pcl::PointXYZ> seg;
    seg.setOptimizeCoefficients(true);
    seg.setModelType(pcl::SACMODEL_PLANE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(distance_threshold_.get());
    seg.setMaxIterations(max_iterations_.get());
    seg.setInputCloud(xyz);
    pcl::PointIndices inliers;
    pcl::ModelCoefficients coefficients;
    seg.segment(inliers, coefficients);
    if (inliers.indices.empty()) throw std::invalid_argument("no plane found in " + std::to_string(xyz->size()) + " points");
    inliers_.publish(cloudResult(*in, selectPoints(*in->points, inliers.indices)));
    outliers_.publish(cloudResult(*in, selectPoints(*in->points, complement(inliers.indices, xyz->size()))));
    coefficients_.publish(std::vector<double>(coefficients.values.begin(), coefficients.values.end()));
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Cloud> inliers_{this, kInliers};
  apex::Output<Cloud> outliers_{this, kOutliers};
  apex::Output<std::vector<double>> coefficients_{this, kCoefficients};
  apex::Param<double> distance_threshold_{this, kDistanceThreshold};
  apex::Param<int> max_iterations_{this, kMaxIterations};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PlaneSegmentation, "apex_nodes/PlaneSegmentation");
