// ConditionalEuclideanClustering: clusters of points that are close and alike, each point whole.
// Where EuclideanClustering joins every pair within the tolerance, this also asks that their
// colours be near (PCL's ConditionalEuclideanClustering with a colour condition): two touching
// objects of different colours come apart.
#include <pcl/segmentation/conditional_euclidean_clustering.h>

#include <cmath>

#include "cluster_segmenter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ConditionalEuclideanClustering : public ClusterSegmenter {
 public:
  static inline const apex::ParamDecl<double> kTolerance = param::number("tolerance")
                                                               .range(0.001, 10.0)
                                                               .step(0.001)
                                                               .init(0.05)
                                                               .describe("metres: neighbours nearer than this may join");
  static inline const apex::ParamDecl<double> kColourDistance =
      param::number("colour_distance")
          .range(0.0, 442.0)
          .step(0.5)
          .init(30.0)
          .describe("the most two joined points' colours may differ (distance in RGB)");
  static apex::Manifest manifest() {
    return segmenterManifest("Splits a coloured cloud into clusters of close points of like colour; needs an rgb field")
        .param(kTolerance)
        .param(kColourDistance);
  }
  void process() override {
    const auto in = cloud_.get();
    requireField(*in, "rgb");
    auto points = std::make_shared<pcl::PointCloud<pcl::PointXYZRGB>>(typedPoints<pcl::PointXYZRGB>(*in));
    const float most = static_cast<float>(colour_distance_.get());
    pcl::ConditionalEuclideanClustering<pcl::PointXYZRGB> cec;
    cec.setInputCloud(points);
    cec.setConditionFunction([most](const pcl::PointXYZRGB& a, const pcl::PointXYZRGB& b, float) {
      const float r = float(a.r) - b.r, g = float(a.g) - b.g, bl = float(a.b) - b.b;
      return r * r + g * g + bl * bl <= most * most;
    });
    cec.setClusterTolerance(static_cast<float>(tolerance_.get()));
    cec.setMinClusterSize(min_size_.get());
    cec.setMaxClusterSize(max_size_.get());
    pcl::IndicesClusters found;
    cec.segment(found);
    publishClusters(*in, std::move(found));
  }

 private:
  apex::Param<double> tolerance_{this, kTolerance};
  apex::Param<double> colour_distance_{this, kColourDistance};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ConditionalEuclideanClustering, "apex_nodes/ConditionalEuclideanClustering");
