#include "apex_nodes/cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace apex_nodes {
namespace {

using Size = std::uint64_t;  // sizes from outside are checked in 64 bits: no product overflows

std::string cloudName(const Cloud& c) {
  const Blob* p = c.points.get();
  return "point cloud " + (p ? std::to_string(p->width) + "x" + std::to_string(p->height) : std::string("(none)")) +
         " on frame '" + c.header.frame_id + "'";
}

const pcl::PCLPointField* findField(const Blob& points, const std::string& name) {
  for (const auto& f : points.fields)
    if (f.name == name) return &f;
  return nullptr;
}

/** The points at `indices` of unpadded rows of `Step` bytes a point, one after another at `to`. */
template <std::size_t Step>
void gather(const Blob& points, const pcl::Indices& indices, std::uint8_t* to) {
  const std::uint8_t* from = points.data.data();
  for (std::size_t k = 0; k < indices.size(); ++k, to += Step)
    std::memcpy(to, from + static_cast<std::size_t>(indices[k]) * Step, Step);
}

}  // namespace

std::uint32_t valueBytes(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8:
    case pcl::PCLPointField::UINT8:
      return 1;
    case pcl::PCLPointField::INT16:
    case pcl::PCLPointField::UINT16:
      return 2;
    case pcl::PCLPointField::INT32:
    case pcl::PCLPointField::UINT32:
    case pcl::PCLPointField::FLOAT32:
      return 4;
    case pcl::PCLPointField::FLOAT64:
      return 8;
    default:
      return 0;
  }
}

std::size_t pointCount(const Cloud& cloud) { return cloud.points ? std::size_t(cloud.points->width) * cloud.points->height : 0; }

std::string fieldNames(const Blob& points) {
  std::string out;
  for (const auto& f : points.fields) out += (out.empty() ? "" : ", ") + f.name;
  return out.empty() ? "none" : out;
}

bool hasField(const Blob& points, const std::string& name) { return findField(points, name) != nullptr; }

void requireField(const Cloud& cloud, const std::string& field) {
  const pcl::PCLPointField* f = cloud.points ? findField(*cloud.points, field) : nullptr;
  if (!f)
    throw std::invalid_argument(cloudName(cloud) + " has no field '" + field +
                                "' (its fields: " + (cloud.points ? fieldNames(*cloud.points) : "none") + ")");
  if ((field == "x" || field == "y" || field == "z") && f->datatype != pcl::PCLPointField::FLOAT32)
    throw std::invalid_argument(cloudName(cloud) + ": field '" + field + "' is not float32");
}

void checkCloud(const Cloud& cloud) {
  auto bad = [&](const std::string& why) { throw std::invalid_argument(cloudName(cloud) + ": " + why); };
  if (!cloud.points) bad("it has no points");
  const Blob& m = *cloud.points;
  if (Size(m.width) * Size(m.height) > (Size(1) << 28)) bad("absurd size: over 2^28 points");
  if (m.is_bigendian) bad("it is big-endian");
  if (m.point_step == 0) bad("point_step is 0");
  for (const auto& f : m.fields) {
    const Size size = valueBytes(f.datatype);
    if (size == 0) bad("field '" + f.name + "' has the unknown datatype " + std::to_string(f.datatype));
    if (Size(f.offset) + size * std::max<Size>(1, f.count) > Size(m.point_step))
      bad("field '" + f.name + "' (offset " + std::to_string(f.offset) + ") does not fit in point_step " +
          std::to_string(m.point_step));
  }
  for (const char* xyz : {"x", "y", "z"}) requireField(cloud, xyz);
  if (Size(m.row_step) < Size(m.width) * Size(m.point_step))
    bad("row_step " + std::to_string(m.row_step) + " is shorter than width x point_step");
  if (Size(m.row_step) * Size(m.height) > Size(m.data.size()))
    bad("data has " + std::to_string(m.data.size()) + " bytes, row_step x height needs " +
        std::to_string(Size(m.row_step) * Size(m.height)));
}

void requirePoints(const Cloud& cloud) {
  if (pointCount(cloud) == 0) throw std::invalid_argument("received an empty point cloud");
  for (const char* xyz : {"x", "y", "z"}) requireField(cloud, xyz);
  const Blob& p = *cloud.points;
  const std::uint32_t offsets[] = {findField(p, "x")->offset, findField(p, "y")->offset, findField(p, "z")->offset};
  for (std::size_t i = 0, n = pointCount(cloud); i < n; ++i) {  // the first finite point ends it
    const std::uint8_t* point = &p.data[(i / p.width) * p.row_step + (i % p.width) * p.point_step];
    bool finite = true;
    for (std::uint32_t offset : offsets) {
      float v;
      std::memcpy(&v, point + offset, sizeof v);
      finite = finite && std::isfinite(v);
    }
    if (finite) return;
  }
  throw std::invalid_argument("received a cloud of " + std::to_string(pointCount(cloud)) + " points, none of them finite");
}

std::shared_ptr<const XyzCloud> xyzOf(const Cloud& cloud, std::shared_ptr<XyzCloud> into) {
  requirePoints(cloud);
  auto out = into ? std::move(into) : std::make_shared<XyzCloud>();
  copyXyz(*cloud.points, *out);
  return out;
}

XyzOffsets xyzOffsets(const Blob& points) {
  return {findField(points, "x")->offset, findField(points, "y")->offset, findField(points, "z")->offset};
}

void copyXyz(const Blob& p, XyzCloud& out) {
  // What pcl::fromPCLPointCloud2 gives (header, size, density; each point's fourth float 1), read
  // here with one copy per point: its loop over a field map per point is the slower one.
  out.header = p.header;
  out.width = p.width;
  out.height = p.height;
  out.is_dense = p.is_dense == 1;
  out.sensor_origin_ = Eigen::Vector4f::Zero();
  out.sensor_orientation_ = Eigen::Quaternionf::Identity();
  out.points.resize(std::size_t(p.width) * p.height);
  const std::uint32_t x = findField(p, "x")->offset, y = findField(p, "y")->offset, z = findField(p, "z")->offset;
  const bool packed = y == x + 4 && z == x + 8;  // as nearly every sensor and PCL lay them out
  if (out.points.empty()) return;
  pcl::PointXYZ* to = out.points.data();
  for (std::size_t row = 0; row < p.height; ++row) {
    const std::uint8_t* from = &p.data[row * p.row_step];
    for (std::size_t col = 0; col < p.width; ++col, from += p.point_step, ++to) {
      if (packed) {
        std::memcpy(to->data, from + x, 3 * sizeof(float));
      } else {
        std::memcpy(&to->x, from + x, sizeof(float));
        std::memcpy(&to->y, from + y, sizeof(float));
        std::memcpy(&to->z, from + z, sizeof(float));
      }
      to->data[3] = 1.f;
    }
  }
}

std::shared_ptr<Blob> selectPoints(const Blob& points, const pcl::Indices& indices, std::shared_ptr<Blob> into) {
  auto out = into ? std::move(into) : std::make_shared<Blob>();
  out->header = points.header;
  out->fields = points.fields;
  out->is_bigendian = points.is_bigendian;
  out->point_step = points.point_step;
  out->height = 1;
  out->width = static_cast<pcl::uindex_t>(indices.size());
  out->row_step = out->point_step * out->width;
  out->is_dense = points.is_dense;
  out->data.resize(std::size_t(out->row_step));
  const std::size_t step = points.point_step;
  std::uint8_t* to = out->data.data();
  if (std::size_t(points.row_step) == points.width * step || points.height == 1) {  // rows unpadded: no division
    switch (step) {  // PCL's point sizes: each copy inlined, not a call to memcpy per point
      case 16:
        gather<16>(points, indices, to);
        break;
      case 32:
        gather<32>(points, indices, to);
        break;
      case 48:
        gather<48>(points, indices, to);
        break;
      case 64:
        gather<64>(points, indices, to);
        break;
      default:
        for (std::size_t k = 0; k < indices.size(); ++k, to += step)
          std::memcpy(to, &points.data[static_cast<std::size_t>(indices[k]) * step], step);
    }
    return out;
  }
  for (std::size_t k = 0; k < indices.size(); ++k, to += step) {  // organised clouds: rows may be padded
    const std::size_t i = static_cast<std::size_t>(indices[k]);
    const std::size_t row = i / points.width, column = i % points.width;
    std::memcpy(to, &points.data[row * points.row_step + column * step], step);
  }
  return out;
}

pcl::Indices complement(const pcl::Indices& indices, std::size_t count) {
  pcl::Indices out;
  out.reserve(count - std::min(count, indices.size()));
  std::size_t k = 0;
  for (std::size_t i = 0; i < count; ++i) {
    while (k < indices.size() && static_cast<std::size_t>(indices[k]) < i) ++k;
    if (k == indices.size() || static_cast<std::size_t>(indices[k]) != i) out.push_back(static_cast<pcl::index_t>(i));
  }
  return out;
}

std::shared_ptr<Clusters> clustersOf(const Cloud& in, std::vector<pcl::PointIndices> found) {
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.indices.size() > b.indices.size(); });
  auto out = std::make_shared<Clusters>();
  out->header = in.header;
  for (const auto& c : found) out->clusters.push_back(selectPoints(*in.points, c.indices));
  return out;
}

std::shared_ptr<Cloud> cloudResult(const Cloud& in, std::shared_ptr<const Blob> points) {
  auto out = std::make_shared<Cloud>();
  out->header = in.header;
  out->points = std::move(points);
  return out;
}

}  // namespace apex_nodes
