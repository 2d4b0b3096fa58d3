// StatisticalOutlierRemoval: drops points far from their neighbours.
#include <pcl/filters/statistical_outlier_removal.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_check.hpp"

namespace apex_nodes {

class StatisticalOutlierRemoval : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Removes points whose mean distance to their k neighbours is unusually large")
        .input<Cloud>("cloud")
        .output<Cloud>("cloud")
        .param(apex::param::range("mean_k", 1, 200, 1, 20).describe("neighbours considered"))
        .param(apex::param::range("stddev", 0.0, 10.0, 0.1, 1.0).describe("allowed standard deviations"));
  }
  void process() override {
    cloud_out_.publish(filterCloud<pcl::StatisticalOutlierRemoval<PointT>>(*cloud_in_.get(), [&](auto& filter) {
      filter.setMeanK(mean_k_.get());
      filter.setStddevMulThresh(stddev_.get());
    }));
  }

 private:
  apex::Input<Cloud> cloud_in_{this, "cloud"};
  apex::Output<Cloud> cloud_out_{this, "cloud"};
  apex::Param<int> mean_k_{this, "mean_k"};
  apex::Param<double> stddev_{this, "stddev"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::StatisticalOutlierRemoval, "apex_nodes/StatisticalOutlierRemoval");
