// PlaneSegmentation: RANSAC plane fit; inliers, outliers and the coefficients.
#include <pcl/filters/extract_indices.h>
#include <pcl/segmentation/sac_segmentation.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_check.hpp"

namespace apex_nodes {

class PlaneSegmentation : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Finds the dominant plane by RANSAC")
        .input<Cloud>("cloud")
        .output<Cloud>("inliers", "the plane's points")
        .output<Cloud>("outliers", "everything else")
        .output<std::vector<double>>("coefficients", "a, b, c, d of ax + by + cz + d = 0")
        .param(apex::param::range("distance_threshold", 0.001, 1.0, 0.001, 0.02).describe("metres"))
        .param(apex::param::range("max_iterations", 1, 100000, 1, 200));
  }
  void process() override {
    auto in = input<Cloud>("cloud");
    requirePoints(*in);
    pcl::SACSegmentation<PointT> seg;
    seg.setOptimizeCoefficients(true);
    seg.setModelType(pcl::SACMODEL_PLANE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(param<double>("distance_threshold"));
    seg.setMaxIterations(param<int>("max_iterations"));
    seg.setInputCloud(in->points);
    auto indices = std::make_shared<pcl::PointIndices>();
    pcl::ModelCoefficients coefficients;
    seg.segment(*indices, coefficients);
    if (indices->indices.empty()) throw std::invalid_argument("no plane found in " + std::to_string(in->points->size()) + " points");
    pcl::ExtractIndices<PointT> extract;
    extract.setInputCloud(in->points);
    extract.setIndices(indices);
    auto inliers = std::make_shared<PclCloud>(), outliers = std::make_shared<PclCloud>();
    extract.filter(*inliers);
    extract.setNegative(true);
    extract.filter(*outliers);
    publish<Cloud>("inliers", cloudResult(*in, std::move(inliers)));
    publish<Cloud>("outliers", cloudResult(*in, std::move(outliers)));
    publish("coefficients", std::vector<double>(coefficients.values.begin(), coefficients.values.end()));
  }
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PlaneSegmentation, "apex_nodes/PlaneSegmentation");
