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
    auto in = input<Cloud>("cloud");
    requirePoints(*in);
    pcl::StatisticalOutlierRemoval<PointT> filter;
    filter.setInputCloud(in->points);
    filter.setMeanK(param<int>("mean_k"));
    filter.setStddevMulThresh(param<double>("stddev"));
    auto points = std::make_shared<PclCloud>();
    filter.filter(*points);
    publish<Cloud>("cloud", cloudResult(*in, std::move(points)));
  }
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::StatisticalOutlierRemoval, "apex_nodes/StatisticalOutlierRemoval");
