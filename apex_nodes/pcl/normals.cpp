// NormalEstimation: each point's surface normal and curvature (PCL's NormalEstimationOMP on the
// x, y, z view), added to the cloud as normal_x, normal_y, normal_z and curvature; every other
// field kept. SACSegmentation's normal models read them.
#include <pcl/features/normal_3d_omp.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"
#include "three_numbers.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

const char* const kNormalFields[4] = {"normal_x", "normal_y", "normal_z", "curvature"};

/** The offset of a float32 field named `name` (count 1), or -1. */
long floatField(const Blob& points, const char* name) {
  for (const auto& f : points.fields)
    if (f.name == name) return f.datatype == pcl::PCLPointField::FLOAT32 && f.count == 1 ? long(f.offset) : -1;
  return -1;
}

/** `points` with `normals` (one per point) as normal_x, normal_y, normal_z and curvature: written
 *  in place where the cloud has all four as float32 already; else appended after each point's
 *  bytes, any field of those names dropped (its bytes stay, unnamed). Rows come out unpadded. */
std::shared_ptr<Blob> withNormals(const Blob& points, const pcl::PointCloud<pcl::Normal>& normals) {
  auto out = std::make_shared<Blob>();
  out->header = points.header;
  out->height = points.height;
  out->width = points.width;
  out->is_bigendian = points.is_bigendian;
  out->is_dense = points.is_dense;
  std::uint32_t offsets[4];
  bool in_place = true;
  for (int k = 0; k < 4; ++k) {
    const long offset = floatField(points, kNormalFields[k]);
    in_place = in_place && offset >= 0;
    offsets[k] = static_cast<std::uint32_t>(std::max(0L, offset));
  }
  if (in_place) {
    out->fields = points.fields;
    out->point_step = points.point_step;
  } else {
    for (const auto& f : points.fields)
      if (std::none_of(std::begin(kNormalFields), std::end(kNormalFields), [&](const char* n) { return f.name == n; }))
        out->fields.push_back(f);
    const std::uint32_t base = (points.point_step + 3) / 4 * 4;  // aligned floats
    for (std::uint32_t k = 0; k < 4; ++k) {
      pcl::PCLPointField f;
      f.name = kNormalFields[k], f.offset = base + 4 * k, f.datatype = pcl::PCLPointField::FLOAT32, f.count = 1;
      out->fields.push_back(f);
      offsets[k] = f.offset;
    }
    out->point_step = base + 16;
  }
  out->row_step = out->point_step * out->width;
  out->data.assign(std::size_t(out->row_step) * out->height, 0);
  const std::size_t width = points.width;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    std::uint8_t* to = &out->data[i * out->point_step];
    std::memcpy(to, &points.data[(i / width) * points.row_step + (i % width) * points.point_step], points.point_step);
    const pcl::Normal& n = normals[i];
    const float values[4] = {n.normal_x, n.normal_y, n.normal_z, n.curvature};
    for (int k = 0; k < 4; ++k) std::memcpy(to + offsets[k], &values[k], sizeof(float));
  }
  return out;
}

}  // namespace

class NormalEstimation : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud"};
  static inline const apex::OutputPort<Cloud> kCloudOut{
      "cloud", "the input with normal_x, normal_y, normal_z and curvature (NaN where too few neighbours)"};
  enum class Search { kRadius, kNearest };
  static inline const apex::ChoiceDecl<Search> kSearch =
      param::choice<Search>("search",
                            {{"radius", Search::kRadius, "those within radius"}, {"k", Search::kNearest, "the k nearest"}})
          .describe("neighbours");
  static inline const apex::ParamDecl<double> kRadius =
      param::number("radius").range(0.001, 10.0).step(0.001).init(0.03).describe("metres (search: radius)");
  static inline const apex::ParamDecl<int> kK = param::integer("k").range(3, 1000).step(1).init(20).describe("search: k");
  static inline const apex::ParamDecl<int> kThreads =
      param::integer("threads").range(0, 256).step(1).init(0).describe("0: every core");
  static inline const apex::ParamDecl<std::vector<double>> kViewpoint =
      param::list("viewpoint").init({0, 0, 0}).describe("x, y, z the normals turn towards (the sensor's origin)");
  static apex::Manifest manifest() {
    return apex::Manifest("Estimates each point's normal and curvature from its neighbours")
        .inCategory("cloud segmentation")
        .input(kCloudIn)
        .output(kCloudOut)
        .param(kSearch)
        .param(kRadius)
        .param(kK)
        .param(kThreads)
        .param(kViewpoint);
  }
  void process() override {
    const auto in = cloud_in_.get();
    const auto xyz = xyzOf(*in);
    const Eigen::Vector3f viewpoint = threeNumbers(viewpoint_.get(), "viewpoint");
    pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> estimation(static_cast<unsigned>(threads_.get()));
    estimation.setInputCloud(xyz);
    if (search_.get() == Search::kNearest) estimation.setKSearch(k_.get());
    else estimation.setRadiusSearch(radius_.get());
    estimation.setViewPoint(viewpoint.x(), viewpoint.y(), viewpoint.z());
    pcl::PointCloud<pcl::Normal> normals;
    estimation.compute(normals);
    if (normals.size() != xyz->size())
      throw std::invalid_argument("PCL estimated no normals for " + std::to_string(xyz->size()) + " points");
    cloud_out_.publish(cloudResult(*in, withNormals(*in->points, normals)));
  }

 private:
  apex::Input<Cloud> cloud_in_{this, kCloudIn};
  apex::Output<Cloud> cloud_out_{this, kCloudOut};
  apex::Choice<Search> search_{this, kSearch};
  apex::Param<double> radius_{this, kRadius};
  apex::Param<int> k_{this, kK};
  apex::Param<int> threads_{this, kThreads};
  apex::Param<std::vector<double>> viewpoint_{this, kViewpoint};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::NormalEstimation, "apex_nodes/NormalEstimation");
