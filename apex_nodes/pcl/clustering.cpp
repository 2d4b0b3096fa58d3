// EuclideanClustering: groups points closer than a tolerance.
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_check.hpp"

namespace apex_nodes {

class EuclideanClustering : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Splits a cloud into clusters of points closer than a tolerance")
        .input<Cloud>("cloud")
        .output<Clusters>("clusters", "largest first")
        .output<int>("count")
        .param(apex::param::range("tolerance", 0.001, 10.0, 0.001, 0.05).describe("metres"))
        .param(apex::param::range("min_size", 1, 10000000, 1, 50))
        .param(apex::param::range("max_size", 1, 10000000, 1, 1000000));
  }
  void process() override {
    auto in = cloud_.get();
    requirePoints(*in);
    auto tree = std::make_shared<pcl::search::KdTree<PointT>>();
    tree->setInputCloud(in->points);
    std::vector<pcl::PointIndices> found;
    pcl::EuclideanClusterExtraction<PointT> ec;
    ec.setClusterTolerance(tolerance_.get());
    ec.setMinClusterSize(min_size_.get());
    ec.setMaxClusterSize(max_size_.get());
    ec.setSearchMethod(tree);
    ec.setInputCloud(in->points);
    ec.extract(found);
    auto out = std::make_shared<Clusters>();
    out->header = in->header;
    for (const auto& indices : found) {
      auto c = std::make_shared<PclCloud>();
      for (int i : indices.indices) c->push_back((*in->points)[i]);
      out->clusters.push_back(std::move(c));
    }
    count_.publish(static_cast<int>(out->clusters.size()));
    clusters_.publish(out);
  }

 private:
  apex::Input<Cloud> cloud_{this, "cloud"};
  apex::Output<Clusters> clusters_{this, "clusters"};
  apex::Output<int> count_{this, "count"};
  apex::Param<double> tolerance_{this, "tolerance"};
  apex::Param<int> min_size_{this, "min_size"};
  apex::Param<int> max_size_{this, "max_size"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::EuclideanClustering, "apex_nodes/EuclideanClustering");
