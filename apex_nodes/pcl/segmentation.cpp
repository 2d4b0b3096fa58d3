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
    auto in = cloud_.get();
    requirePoints(*in);
    pcl::SACSegmentation<PointT> seg;
    seg.setOptimizeCoefficients(true);
    seg.setModelType(pcl::SACMODEL_PLANE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(distance_threshold_.get());
    seg.setMaxIterations(max_iterations_.get());
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
    inliers_.publish(cloudResult(*in, std::move(inliers)));
    outliers_.publish(cloudResult(*in, std::move(outliers)));
    coefficients_.publish(std::vector<double>(coefficients.values.begin(), coefficients.values.end()));
  }

 private:
  apex::Input<Cloud> cloud_{this, "cloud"};
  apex::Output<Cloud> inliers_{this, "inliers"};
  apex::Output<Cloud> outliers_{this, "outliers"};
  apex::Output<std::vector<double>> coefficients_{this, "coefficients"};
  apex::Param<double> distance_threshold_{this, "distance_threshold"};
  apex::Param<int> max_iterations_{this, "max_iterations"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PlaneSegmentation, "apex_nodes/PlaneSegmentation");
