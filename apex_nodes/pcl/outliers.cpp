// StatisticalOutlierRemoval and RadiusOutlierRemoval: drop points far from their neighbours.
#include <pcl/filters/radius_outlier_removal.h>
#include <pcl/filters/statistical_outlier_removal.h>

#include "apex_nodes/cloud_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class StatisticalOutlierRemoval : public CloudFilter<pcl::StatisticalOutlierRemoval<pcl::PointXYZ>> {
 public:
  static inline const apex::ParamDecl<int> kMeanK =
      param::integer("mean_k").range(1, 200).step(1).init(20).describe("neighbours considered");
  static inline const apex::ParamDecl<double> kStddev =
      param::number("stddev").range(0.0, 10.0).step(0.1).init(1.0).describe("allowed standard deviations");
  static apex::Manifest manifest() {
    return filterManifest("Removes points whose mean distance to their k neighbours is unusually large")
        .param(kMeanK)
        .param(kStddev);
  }

 private:
  void configure(pcl::StatisticalOutlierRemoval<pcl::PointXYZ>& filter) override {
    filter.setMeanK(mean_k_.get());
    filter.setStddevMulThresh(stddev_.get());
  }
  apex::Param<int> mean_k_{this, kMeanK};
  apex::Param<double> stddev_{this, kStddev};
};

class RadiusOutlierRemoval : public CloudFilter<pcl::RadiusOutlierRemoval<pcl::PointXYZ>> {
 public:
  static inline const apex::ParamDecl<double> kRadius =
      param::number("radius").range(0.001, 10.0).step(0.001).init(0.05).describe("metres");
  static inline const apex::ParamDecl<int> kMinNeighbours =
      param::integer("min_neighbours").range(0, 1000).step(1).init(5).describe("within the radius, to be kept");
  static apex::Manifest manifest() {
    return filterManifest("Removes points with fewer than min_neighbours others within radius")
        .param(kRadius)
        .param(kMinNeighbours);
  }

 private:
  void configure(pcl::RadiusOutlierRemoval<pcl::PointXYZ>& filter) override {
    filter.setRadiusSearch(radius_.get());
    filter.setMinNeighborsInRadius(min_neighbours_.get());
  }
  apex::Param<double> radius_{this, kRadius};
  apex::Param<int> min_neighbours_{this, kMinNeighbours};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::StatisticalOutlierRemoval, "apex_nodes/StatisticalOutlierRemoval");
APEX_REGISTER_NODE(apex_nodes::RadiusOutlierRemoval, "apex_nodes/RadiusOutlierRemoval");
