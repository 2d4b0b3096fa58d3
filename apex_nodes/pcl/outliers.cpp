// StatisticalOutlierRemoval: drops points far from their neighbours.
#include <pcl/filters/statistical_outlier_removal.h>

#include "apex_nodes/cloud_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class StatisticalOutlierRemoval : public CloudFilter<pcl::StatisticalOutlierRemoval<PointT>> {
 public:
  static inline const apex::ParamDecl<int> kMeanK =
      param::integer("mean_k").range(1, 200).step(1).init(20).describe("neighbours considered");
  static inline const apex::ParamDecl<double> kStddev =
      param::number("stddev").range(0.0, 10.0).step(0.1).init(1.0).describe("allowed standard deviations");
  static apex::Manifest manifest() {
    return filterManifest("Removes points whose mean distance to their k neighbours is unusually large").param(kMeanK).param(kStddev);
  }

 private:
  void configure(pcl::StatisticalOutlierRemoval<PointT>& filter) override {
    filter.setMeanK(mean_k_.get());
    filter.setStddevMulThresh(stddev_.get());
  }
  apex::Param<int> mean_k_{this, kMeanK};
  apex::Param<double> stddev_{this, kStddev};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::StatisticalOutlierRemoval, "apex_nodes/StatisticalOutlierRemoval");
