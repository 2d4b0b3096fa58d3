// PassThrough and VoxelGrid: the point-cloud half of the demo pipeline.
#include <pcl/filters/passthrough.h>
#include <pcl/filters/voxel_grid.h>

#include "apex_nodes/cloud_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class PassThrough : public CloudFilter<pcl::PassThrough<PointT>> {
 public:
  static inline const apex::ParamDecl<std::string> kField = param::choice("field", {"x", "y", "z"}).init("z");
  static inline const apex::ParamDecl<apex::Interval> kLimits =
      param::interval("limits").range(-100.0, 100.0).step(0.01).init({0.0, 3.0}).describe("metres");
  static inline const apex::ParamDecl<bool> kNegative = param::flag("negative").describe("keep the points outside instead");
  static apex::Manifest manifest() {
    return filterManifest("Keeps the points whose x, y or z lies within limits").param(kField).param(kLimits).param(kNegative);
  }

 private:
  void configure(pcl::PassThrough<PointT>& filter) override {
    filter.setFilterFieldName(field_.get());
    filter.setFilterLimits(static_cast<float>(limits_.get().low), static_cast<float>(limits_.get().high));
    filter.setNegative(negative_.get());
  }
  apex::Param<std::string> field_{this, kField};
  apex::Param<apex::Interval> limits_{this, kLimits};
  apex::Param<bool> negative_{this, kNegative};
};

class VoxelGrid : public CloudFilter<pcl::VoxelGrid<PointT>> {
 public:
  static inline const apex::ParamDecl<double> kLeafSize =
      param::number("leaf_size").range(0.001, 10.0).step(0.001).init(0.05).describe("voxel edge, metres");
  static apex::Manifest manifest() {
    return filterManifest("Downsamples a cloud to one point per voxel (the centroid)").param(kLeafSize);
  }

 private:
  void configure(pcl::VoxelGrid<PointT>& filter) override {
    const float leaf = static_cast<float>(leaf_size_.get());
    filter.setLeafSize(leaf, leaf, leaf);
  }
  apex::Param<double> leaf_size_{this, kLeafSize};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PassThrough, "apex_nodes/PassThrough");
APEX_REGISTER_NODE(apex_nodes::VoxelGrid, "apex_nodes/VoxelGrid");
