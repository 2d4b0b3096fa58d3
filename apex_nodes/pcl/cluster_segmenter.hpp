// What the nodes that split a cloud into clusters by a PCL segmentation share (RegionGrowing,
// RegionGrowingRGB, ConditionalEuclideanClustering): a cloud in; the clusters out, largest first,
// each point whole, and their number; the least and the most points a cluster may have.
#pragma once

#include <pcl/PointIndices.h>

#include <string>
#include <utility>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {

class ClusterSegmenter : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::OutputPort<Clusters> kClusters{"clusters", "largest first, each point whole"};
  static inline const apex::OutputPort<int> kCount{"count"};
  static inline const apex::ParamDecl<int> kMinSize = apex::param::integer("min_size").range(1, 100000000).step(1).init(50);
  static inline const apex::ParamDecl<int> kMaxSize = apex::param::integer("max_size").range(1, 100000000).step(1).init(1000000);
  /** @brief The manifest with the ports and the size limits, in "cloud segmentation"; add the rest. */
  static apex::Manifest segmenterManifest(std::string description) {
    return apex::Manifest(std::move(description))
        .inCategory("cloud segmentation")
        .input(kCloud)
        .output(kClusters)
        .output(kCount)
        .param(kMinSize)
        .param(kMaxSize);
  }

 protected:
  /** Sends the clusters found in `in` and their number. */
  void publishClusters(const Cloud& in, std::vector<pcl::PointIndices> found) {
    count_.publish(static_cast<int>(found.size()));
    clusters_.publish(clustersOf(in, std::move(found)));
  }
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Param<int> min_size_{this, kMinSize};
  apex::Param<int> max_size_{this, kMaxSize};

 private:
  apex::Output<Clusters> clusters_{this, kClusters};
  apex::Output<int> count_{this, kCount};
};

}  // namespace apex_nodes
