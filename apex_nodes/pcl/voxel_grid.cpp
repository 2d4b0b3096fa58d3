// VoxelGrid: one point per voxel, the centroid of every field. PCL's field-generic VoxelGrid is
// 2x slower than its typed ones (docs/architecture.md), so a cloud whose fields are those of a
// PCL point type goes through that type; any other (ring, time...) through the generic one.
#include <pcl/filters/voxel_grid.h>

#include <set>
#include <string>
#include <tuple>
#include <typeinfo>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/cloud_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** The typed cloud of the last firing's point type, kept for the next: a steady stream converts
 *  into the same memory (a new megabyte per frame costs its page faults). */
class TypedScratch {
 public:
  template <class PointT>
  std::shared_ptr<pcl::PointCloud<PointT>> get() {
    if (type_ != &typeid(PointT) || !cloud_ || cloud_.use_count() > 1) {
      cloud_ = std::make_shared<pcl::PointCloud<PointT>>();
      type_ = &typeid(PointT);
    }
    return std::static_pointer_cast<pcl::PointCloud<PointT>>(cloud_);
  }

 private:
  const std::type_info* type_ = nullptr;
  std::shared_ptr<void> cloud_;
};

template <class PointT>
std::shared_ptr<Blob> voxelTyped(const Cloud& in, float leaf, TypedScratch& scratch, std::shared_ptr<Blob> into) {
  const auto typed = scratch.get<PointT>();
  pcl::fromPCLPointCloud2(*in.points, *typed);
  pcl::VoxelGrid<PointT> filter;
  filter.setInputCloud(typed);
  filter.setLeafSize(leaf, leaf, leaf);
  pcl::PointCloud<PointT> out;
  filter.filter(out);
  pcl::toPCLPointCloud2(out, *into);  // sets every member but is_bigendian
  into->is_bigendian = false;
  return into;
}

std::shared_ptr<Blob> voxelAnyFields(const Cloud& in, float leaf) {
  pcl::VoxelGrid<pcl::PCLPointCloud2> filter;
  filter.setInputCloud(in.points);
  filter.setLeafSize(leaf, leaf, leaf);
  auto out = std::make_shared<Blob>();
  filter.filter(*out);
  return out;
}

using Signature = std::set<std::tuple<std::string, int, int>>;  // (name, datatype, count) of each field

Signature signature(const Blob& points) {
  Signature out;
  for (const auto& f : points.fields)
    if (!f.name.empty() && f.name != "_") out.emplace(f.name, f.datatype, f.count);  // not padding
  return out;
}

/** The cloud has exactly the fields of PCL's `PointT` (names and datatypes): it converts losslessly. */
template <class PointT>
bool fieldsOf(const Blob& points) {
  static const Signature kFields = [] {
    Blob empty;
    pcl::toPCLPointCloud2(pcl::PointCloud<PointT>(), empty);
    return signature(empty);
  }();
  return signature(points) == kFields;
}

/** Downsamples `in` (checked: x, y, z, a finite point) with voxels of edge `leaf`; a cloud of a
 *  PCL point type's fields into `into`. */
std::shared_ptr<Blob> voxelGrid(const Cloud& in, float leaf, TypedScratch& s, std::shared_ptr<Blob> into) {
  requirePoints(in);
  const Blob& p = *in.points;
  if (fieldsOf<pcl::PointXYZ>(p)) return voxelTyped<pcl::PointXYZ>(in, leaf, s, into);
  if (fieldsOf<pcl::PointXYZI>(p)) return voxelTyped<pcl::PointXYZI>(in, leaf, s, into);
  if (fieldsOf<pcl::PointXYZRGB>(p)) return voxelTyped<pcl::PointXYZRGB>(in, leaf, s, into);
  if (fieldsOf<pcl::PointXYZRGBA>(p)) return voxelTyped<pcl::PointXYZRGBA>(in, leaf, s, into);
  if (fieldsOf<pcl::PointNormal>(p)) return voxelTyped<pcl::PointNormal>(in, leaf, s, into);
  if (fieldsOf<pcl::PointXYZRGBNormal>(p)) return voxelTyped<pcl::PointXYZRGBNormal>(in, leaf, s, into);
  if (fieldsOf<pcl::PointXYZINormal>(p)) return voxelTyped<pcl::PointXYZINormal>(in, leaf, s, into);
  return voxelAnyFields(in, leaf);  // e.g. a lidar's ring and time
}

}  // namespace

class VoxelGrid : public apex::Node, public CloudFilterPorts {
 public:
  static inline const apex::ParamDecl<double> kLeafSize =
      param::number("leaf_size").range(0.001, 10.0).step(0.001).init(0.05).describe("voxel edge, metres");
  static apex::Manifest manifest() {
    return filterManifest("Downsamples a cloud to one point per voxel: the centroid of every field").param(kLeafSize);
  }
  void process() override {
    const auto in = in_.get();
    out_.publish(cloudResult(*in, voxelGrid(*in, static_cast<float>(leaf_size_.get()), typed_, points_.next())));
  }

 private:
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kCloudOut};
  apex::Param<double> leaf_size_{this, kLeafSize};
  TypedScratch typed_;  // the input as its point type and the points sent: reused per frame
  Reused<Blob> points_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::VoxelGrid, "apex_nodes/VoxelGrid");
