// PassThrough and VoxelGrid: the point-cloud half of the demo pipeline.
#include <pcl/filters/passthrough.h>
#include <pcl/filters/voxel_grid.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_check.hpp"

namespace apex_nodes {

class PassThrough : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Keeps the points whose x, y or z lies within limits")
        .input<Cloud>("cloud")
        .output<Cloud>("cloud")
        .param(apex::param::options("field", {"x", "y", "z"}, "z"))
        .param(apex::param::interval("limits", -100.0, 100.0, 0.0, 3.0, 0.01).describe("metres"))
        .param(apex::param::boolean("negative", false).describe("keep the points outside instead"));
  }
  void process() override {
    cloud_out_.publish(filterCloud<pcl::PassThrough<PointT>>(*cloud_in_.get(), [&](auto& filter) {
      filter.setFilterFieldName(field_.get());
      const apex::Interval& lim = limits_.get();
      filter.setFilterLimits(static_cast<float>(lim.low), static_cast<float>(lim.high));
      filter.setNegative(negative_.get());
    }));
  }

 private:
  apex::Input<Cloud> cloud_in_{this, "cloud"};
  apex::Output<Cloud> cloud_out_{this, "cloud"};
  apex::Param<std::string> field_{this, "field"};
  apex::Param<apex::Interval> limits_{this, "limits"};
  apex::Param<bool> negative_{this, "negative"};
};

class VoxelGrid : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Downsamples a cloud to one point per voxel (the centroid)")
        .input<Cloud>("cloud")
        .output<Cloud>("cloud")
        .param(apex::param::range("leaf_size", 0.001, 10.0, 0.001, 0.05).describe("voxel edge, metres"));
  }
  void process() override {
    cloud_out_.publish(filterCloud<pcl::VoxelGrid<PointT>>(*cloud_in_.get(), [&](auto& filter) {
      const float leaf = static_cast<float>(leaf_size_.get());
      filter.setLeafSize(leaf, leaf, leaf);
    }));
  }

 private:
  apex::Input<Cloud> cloud_in_{this, "cloud"};
  apex::Output<Cloud> cloud_out_{this, "cloud"};
  apex::Param<double> leaf_size_{this, "leaf_size"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PassThrough, "apex_nodes/PassThrough");
APEX_REGISTER_NODE(apex_nodes::VoxelGrid, "apex_nodes/VoxelGrid");
