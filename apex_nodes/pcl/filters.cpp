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
    auto in = input<Cloud>("cloud");
    requirePoints(*in);
    pcl::PassThrough<PointT> filter;
    filter.setInputCloud(in->points);  // shared, not copied
    filter.setFilterFieldName(param<std::string>("field"));
    const apex::Interval& lim = param<apex::Interval>("limits");
    filter.setFilterLimits(static_cast<float>(lim.low), static_cast<float>(lim.high));
    filter.setNegative(param<bool>("negative"));
    auto points = std::make_shared<PclCloud>();
    filter.filter(*points);
    publish<Cloud>("cloud", cloudResult(*in, std::move(points)));
  }
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
    auto in = input<Cloud>("cloud");
    requirePoints(*in);
    pcl::VoxelGrid<PointT> filter;
    filter.setInputCloud(in->points);  // shared, not copied
    const float leaf = static_cast<float>(param<double>("leaf_size"));
    filter.setLeafSize(leaf, leaf, leaf);
    auto points = std::make_shared<PclCloud>();
    filter.filter(*points);
    publish<Cloud>("cloud", cloudResult(*in, std::move(points)));
  }
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PassThrough, "apex_nodes/PassThrough");
APEX_REGISTER_NODE(apex_nodes::VoxelGrid, "apex_nodes/VoxelGrid");
