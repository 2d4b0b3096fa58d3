// ClustersToCloud: clusters as one labelled cloud, every field of their points kept and a
// "label" field (uint32, the cluster's index, as pcl::PointXYZL names it) added: for rviz (colour
// by the label channel), a recorder, or a node that takes one cloud.
#include <cstring>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_transform.hpp"

namespace apex_nodes {
namespace {

/** The clusters' points in one row, each with its cluster's index in a uint32 "label"
 *  field appended (replacing a "label" the points had). Throws if the clusters' fields differ. */
std::shared_ptr<Blob> labelledPoints(const Clusters& clusters) {
  std::vector<PlacedPoints> parts;
  std::vector<std::uint32_t> labels;  // per point
  for (std::size_t c = 0; c < clusters.clusters.size(); ++c) {
    const auto& points = clusters.clusters[c];
    if (!points || std::size_t(points->width) * points->height == 0) continue;
    parts.push_back({points});
    labels.insert(labels.end(), std::size_t(points->width) * points->height, static_cast<std::uint32_t>(c));
  }
  if (parts.empty()) return std::make_shared<Blob>();
  const auto merged = mergePoints(parts);
  auto out = std::make_shared<Blob>();
  out->header = merged->header;
  out->height = 1, out->width = merged->width, out->is_bigendian = merged->is_bigendian, out->is_dense = merged->is_dense;
  for (const auto& f : merged->fields)
    if (f.name != "label") out->fields.push_back(f);
  pcl::PCLPointField label;
  label.name = "label", label.offset = merged->point_step, label.datatype = pcl::PCLPointField::UINT32, label.count = 1;
  out->fields.push_back(label);
  out->point_step = merged->point_step + 4;
  out->row_step = out->point_step * out->width;
  out->data.resize(std::size_t(out->row_step));
  for (std::size_t i = 0; i < labels.size(); ++i) {
    std::memcpy(&out->data[i * out->point_step], &merged->data[i * merged->point_step], merged->point_step);
    std::memcpy(&out->data[i * out->point_step + label.offset], &labels[i], sizeof(std::uint32_t));
  }
  return out;
}

}  // namespace

class ClustersToCloud : public apex::Node {
 public:
  static inline const apex::InputPort<Clusters> kClusters{"clusters"};
  static inline const apex::OutputPort<Cloud> kCloud{"cloud", "every cluster's points, with a uint32 field 'label'"};
  static apex::Manifest manifest() {
    return apex::Manifest("Joins clusters into one cloud whose 'label' field says each point's cluster")
        .inCategory("clouds")
        .input(kClusters)
        .output(kCloud);
  }
  void process() override {
    const auto in = clusters_.get();
    auto out = std::make_shared<Cloud>();
    out->header = in->header;
    out->points = labelledPoints(*in);
    cloud_.publish(std::move(out));
  }

 private:
  apex::Input<Clusters> clusters_{this, kClusters};
  apex::Output<Cloud> cloud_{this, kCloud};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ClustersToCloud, "apex_nodes/ClustersToCloud");
