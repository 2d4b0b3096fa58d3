// EuclideanClustering: groups points closer than a tolerance; each cluster keeps every field.
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {
namespace param = apex::param;

class EuclideanClustering : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::OutputPort<Clusters> kClusters{"clusters", "largest first"};
  static inline const apex::OutputPort<int> kCount{"count"};
  static inline const apex::ParamDecl<double> kTolerance =
      param::number("tolerance").range(0.001, 10.0).step(0.001).init(0.05).describe("metres");
  static inline const apex::ParamDecl<int> kMinSize = param::integer("min_size").range(1, 10000000).step(1).init(50);
  static inline const apex::ParamDecl<int> kMaxSize = param::integer("max_size").range(1, 10000000).step(1).init(1000000);
  static apex::Manifest manifest() {
    return apex::Manifest("Splits a cloud into clusters of points closer than a tolerance")
        .inCategory("cloud segmentation")
        .input(kCloud)
        .output(kClusters)
        .output(kCount)
        .param(kTolerance)
        .param(kMinSize)
        .param(kMaxSize);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in);
    auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    tree->setInputCloud(xyz);
    std::vector<pcl::PointIndices> found;
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(tolerance_.get());
    ec.setMinClusterSize(min_size_.get());
    ec.setMaxClusterSize(max_size_.get());
    ec.setSearchMethod(tree);
    ec.setInputCloud(xyz);
    ec.extract(found);
    auto out = std::make_shared<Clusters>();
    out->header = in->header;
    for (const auto& indices : found) out->clusters.push_back(selectPoints(*in->points, indices.indices));
    count_.publish(static_cast<int>(out->clusters.size()));
    clusters_.publish(out);
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Clusters> clusters_{this, kClusters};
  apex::Output<int> count_{this, kCount};
  apex::Param<double> tolerance_{this, kTolerance};
  apex::Param<int> min_size_{this, kMinSize};
  apex::Param<int> max_size_{this, kMaxSize};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::EuclideanClustering, "apex_nodes/EuclideanClustering");
