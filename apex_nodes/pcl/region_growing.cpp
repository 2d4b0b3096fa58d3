// RegionGrowing and RegionGrowingRGB: a cloud split into regions grown from seed points, each
// cluster keeping every field. RegionGrowing joins neighbours whose normals differ little (smooth
// surfaces: a table top, a box's faces apart); RegionGrowingRGB joins close points of like colour
// and merges regions of like mean colour.
#include <pcl/features/normal_3d.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>
#include <pcl/segmentation/region_growing_rgb.h>

#include <cmath>

#include "cluster_segmenter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class RegionGrowing : public ClusterSegmenter {
 public:
  static inline const apex::ParamDecl<int> kNormalK =
      param::integer("normal_k").range(3, 1000).step(1).init(30).describe("neighbours each point's normal is estimated from");
  static inline const apex::ParamDecl<int> kNeighbours =
      param::integer("neighbours").range(1, 1000).step(1).init(30).describe("neighbours a region grows into from each point");
  static inline const apex::ParamDecl<double> kSmoothness = param::number("smoothness")
                                                                .range(0.1, 90.0)
                                                                .step(0.1)
                                                                .init(3.0)
                                                                .describe("degrees: the most two joined normals may differ");
  static inline const apex::ParamDecl<double> kCurvature =
      param::number("curvature")
          .range(0.0, 10.0)
          .step(0.01)
          .init(1.0)
          .describe("points curved less than this seed further growth (PCL's curvature: 0 on a plane, 1/3 at most)");
  static apex::Manifest manifest() {
    return segmenterManifest(
               "Splits a cloud into smooth regions (PCL's RegionGrowing): neighbours join while their normals agree")
        .param(kNormalK)
        .param(kNeighbours)
        .param(kSmoothness)
        .param(kCurvature);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in);
    auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
    pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimate;
    estimate.setSearchMethod(tree);
    estimate.setInputCloud(xyz);
    estimate.setKSearch(normal_k_.get());
    estimate.compute(*normals);
    pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> grow;
    grow.setMinClusterSize(static_cast<pcl::uindex_t>(min_size_.get()));
    grow.setMaxClusterSize(static_cast<pcl::uindex_t>(max_size_.get()));
    grow.setSearchMethod(tree);
    grow.setNumberOfNeighbours(static_cast<unsigned>(neighbours_.get()));
    grow.setInputCloud(xyz);
    grow.setInputNormals(normals);
    grow.setSmoothnessThreshold(static_cast<float>(smoothness_.get() / 180.0 * M_PI));
    grow.setCurvatureThreshold(static_cast<float>(curvature_.get()));
    std::vector<pcl::PointIndices> found;
    grow.extract(found);
    publishClusters(*in, std::move(found));
  }

 private:
  apex::Param<int> normal_k_{this, kNormalK};
  apex::Param<int> neighbours_{this, kNeighbours};
  apex::Param<double> smoothness_{this, kSmoothness};
  apex::Param<double> curvature_{this, kCurvature};
};

class RegionGrowingRGB : public ClusterSegmenter {
 public:
  static inline const apex::ParamDecl<double> kDistance = param::number("distance")
                                                              .range(0.0001, 100.0)
                                                              .step(0.001)
                                                              .init(0.05)
                                                              .describe("metres: neighbours nearer than this may join");
  static inline const apex::ParamDecl<double> kPointColour =
      param::number("point_colour")
          .range(0.0, 442.0)
          .step(0.5)
          .init(6.0)
          .describe("the most a point's colour may differ from its neighbour's to join (distance in RGB)");
  static inline const apex::ParamDecl<double> kRegionColour = param::number("region_colour")
                                                                  .range(0.0, 442.0)
                                                                  .step(0.5)
                                                                  .init(5.0)
                                                                  .describe("regions whose mean colours differ less are merged");
  static apex::Manifest manifest() {
    return segmenterManifest("Splits a coloured cloud into regions of like colour (PCL's RegionGrowingRGB); needs an rgb field")
        .param(kDistance)
        .param(kPointColour)
        .param(kRegionColour);
  }
  void process() override {
    const auto in = cloud_.get();
    requireField(*in, "rgb");
    auto points = std::make_shared<pcl::PointCloud<pcl::PointXYZRGB>>(typedPoints<pcl::PointXYZRGB>(*in));
    pcl::RegionGrowingRGB<pcl::PointXYZRGB> grow;
    grow.setInputCloud(points);
    grow.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZRGB>>());
    grow.setDistanceThreshold(static_cast<float>(distance_.get()));
    grow.setPointColorThreshold(static_cast<float>(point_colour_.get()));
    grow.setRegionColorThreshold(static_cast<float>(region_colour_.get()));
    grow.setMinClusterSize(static_cast<pcl::uindex_t>(min_size_.get()));
    grow.setMaxClusterSize(static_cast<pcl::uindex_t>(max_size_.get()));
    std::vector<pcl::PointIndices> found;
    grow.extract(found);
    publishClusters(*in, std::move(found));
  }

 private:
  apex::Param<double> distance_{this, kDistance};
  apex::Param<double> point_colour_{this, kPointColour};
  apex::Param<double> region_colour_{this, kRegionColour};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::RegionGrowing, "apex_nodes/RegionGrowing");
APEX_REGISTER_NODE(apex_nodes::RegionGrowingRGB, "apex_nodes/RegionGrowingRGB");
