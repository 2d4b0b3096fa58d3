#include "apex_nodes/cloud_transform.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <stdexcept>

namespace apex_nodes {
namespace {

using Offsets = std::array<std::uint32_t, 3>;

/** The float32 triple at `offsets` of points [begin, end) through `f`, in place (memcpy: fields may
 *  be unaligned). */
template <class F>
void eachTriple(Blob& points, const Offsets& offsets, std::size_t begin, std::size_t end, F f) {
  const std::size_t step = points.point_step;
  const bool unpadded = points.height == 1 || std::size_t(points.row_step) == points.width * step;
  for (std::size_t i = begin; i < end; ++i) {  // organised clouds: rows may be padded
    std::uint8_t* p = &points.data[unpadded ? i * step : (i / points.width) * points.row_step + (i % points.width) * step];
    Eigen::Vector3f v;
    for (int k = 0; k < 3; ++k) std::memcpy(&v[k], p + offsets[k], sizeof(float));
    v = f(v);
    for (int k = 0; k < 3; ++k) std::memcpy(p + offsets[k], &v[k], sizeof(float));
  }
}

/** The offsets of three float32 fields, if the cloud has all three. */
std::optional<Offsets> triple(const Blob& points, const std::array<const char*, 3>& names) {
  Offsets out{};
  for (int k = 0; k < 3; ++k) {
    auto f = std::find_if(points.fields.begin(), points.fields.end(), [&](const auto& f) { return f.name == names[k]; });
    if (f == points.fields.end() || f->datatype != pcl::PCLPointField::FLOAT32) return std::nullopt;
    out[k] = f->offset;
  }
  return out;
}

/** x, y, z moved and the normals turned, of points [begin, end). */
void moveRange(Blob& points, const Eigen::Affine3f& m, std::size_t begin, std::size_t end) {
  const auto xyz = triple(points, {"x", "y", "z"});
  if (!xyz) throw std::invalid_argument("a cloud to move has no float32 x, y, z (its fields: " + fieldNames(points) + ")");
  eachTriple(points, *xyz, begin, end, [&](const Eigen::Vector3f& v) { return m * v; });
  if (auto normals = triple(points, {"normal_x", "normal_y", "normal_z"}))
    eachTriple(points, *normals, begin, end, [&](const Eigen::Vector3f& v) { return m.linear() * v; });
}

/** Bytes of one value (checkCloud refused unknown datatypes; 4 stands for one here). */
std::uint32_t valueSize(std::uint8_t datatype) {
  const std::uint32_t n = valueBytes(datatype);
  return n ? n : 4;
}
std::uint32_t fieldBytes(const pcl::PCLPointField& f) { return valueSize(f.datatype) * std::max<std::uint32_t>(1, f.count); }

bool sameLayout(const Blob& a, const Blob& b) {
  if (a.point_step != b.point_step || a.fields.size() != b.fields.size()) return false;
  for (std::size_t i = 0; i < a.fields.size(); ++i) {
    const auto &f = a.fields[i], &g = b.fields[i];
    if (f.name != g.name || f.offset != g.offset || f.datatype != g.datatype || f.count != g.count) return false;
  }
  return true;
}

/** The field of `points` named as `f`, with its datatype and count; nullptr if none. */
const pcl::PCLPointField* sameField(const Blob& points, const pcl::PCLPointField& f) {
  for (const auto& g : points.fields)
    if (g.name == f.name && g.datatype == f.datatype &&
        std::max<std::uint32_t>(1, g.count) == std::max<std::uint32_t>(1, f.count))
      return &g;
  return nullptr;
}

}  // namespace

Eigen::Affine3f toEigen(const geometry_msgs::Transform& t) {
  const Eigen::Quaternionf q(static_cast<float>(t.rotation.w), static_cast<float>(t.rotation.x), static_cast<float>(t.rotation.y),
                             static_cast<float>(t.rotation.z));
  Eigen::Affine3f m = Eigen::Affine3f::Identity();
  m.translate(Eigen::Vector3f(static_cast<float>(t.translation.x), static_cast<float>(t.translation.y),
                              static_cast<float>(t.translation.z)));
  m.rotate(q.normalized());
  return m;
}

geometry_msgs::Transform toTransform(const Eigen::Matrix4f& m) {
  const Eigen::Matrix4d d = m.cast<double>();
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::Matrix3d(d.topLeftCorner<3, 3>())).normalized();
  geometry_msgs::Transform t;
  t.translation.x = d(0, 3), t.translation.y = d(1, 3), t.translation.z = d(2, 3);
  t.rotation.x = q.x(), t.rotation.y = q.y(), t.rotation.z = q.z(), t.rotation.w = q.w();
  return t;
}

std::shared_ptr<Blob> transformPoints(const Blob& in, const Eigen::Affine3f& m, std::shared_ptr<Blob> into) {
  auto out = into ? std::move(into) : std::make_shared<Blob>();
  *out = in;  // into reused points: their bytes' memory too
  moveRange(*out, m, 0, std::size_t(in.width) * in.height);
  return out;
}

std::shared_ptr<Blob> mergePoints(const std::vector<PlacedPoints>& clouds, std::shared_ptr<Blob> into) {
  if (clouds.empty()) throw std::invalid_argument("no clouds to merge");
  for (std::size_t i = 0; i < clouds.size(); ++i)
    if (!clouds[i].points || !triple(*clouds[i].points, {"x", "y", "z"}))
      throw std::invalid_argument("cloud " + std::to_string(i) + " to merge has no float32 x, y, z (its fields: " +
                                  (clouds[i].points ? fieldNames(*clouds[i].points) : std::string("none")) + ")");
  const Blob& first = *clouds.front().points;
  const bool same =
      std::all_of(clouds.begin(), clouds.end(), [&](const PlacedPoints& c) { return sameLayout(*c.points, first); });
  auto out = into ? std::move(into) : std::make_shared<Blob>();
  out->header = first.header;
  out->is_bigendian = first.is_bigendian;
  out->is_dense = true;
  out->fields.clear();
  if (same) {
    out->fields = first.fields;
    out->point_step = first.point_step;
  } else {  // the fields every cloud has, packed (not PCL's padding, "_")
    out->point_step = 0;
    for (const auto& f : first.fields) {
      if (f.name == "_" ||
          !std::all_of(clouds.begin(), clouds.end(), [&](const PlacedPoints& c) { return sameField(*c.points, f); }))
        continue;
      pcl::PCLPointField kept = f;
      kept.offset = out->point_step;
      out->point_step += fieldBytes(f);
      out->fields.push_back(kept);
    }
  }
  std::size_t total = 0;
  for (const auto& c : clouds) total += std::size_t(c.points->width) * c.points->height;
  out->height = 1;
  out->width = static_cast<pcl::uindex_t>(total);
  out->row_step = out->point_step * out->width;
  out->data.resize(std::size_t(out->row_step));

  const std::size_t step = out->point_step;
  std::size_t at = 0;
  for (const auto& c : clouds) {
    const Blob& p = *c.points;
    struct Copy {
      std::uint32_t from, to, bytes;
    };
    std::vector<Copy> copies;
    if (same) copies.push_back({0, 0, p.point_step});
    else
      for (const auto& f : out->fields) copies.push_back({sameField(p, f)->offset, f.offset, fieldBytes(f)});
    const std::size_t n = std::size_t(p.width) * p.height;
    if (same && std::size_t(p.row_step) == p.width * step) {  // whole points, rows unpadded: one block
      if (n) std::memcpy(&out->data[at * step], p.data.data(), n * step);
    } else {
      for (std::size_t i = 0; i < n; ++i) {  // organised clouds: rows may be padded
        const std::uint8_t* from = &p.data[(i / p.width) * p.row_step + (i % p.width) * p.point_step];
        std::uint8_t* to = &out->data[(at + i) * step];
        for (const auto& k : copies) std::memcpy(to + k.to, from + k.from, k.bytes);
      }
    }
    if (c.pose.matrix() != Eigen::Matrix4f::Identity()) moveRange(*out, c.pose, at, at + n);
    out->is_dense = out->is_dense && p.is_dense;
    at += n;
  }
  return out;
}

std::shared_ptr<Cloud> mergeClouds(const std::vector<std::shared_ptr<const Cloud>>& clouds, const std::string& frame,
                                   const TransformLookup& lookup, std::shared_ptr<Blob> into) {
  if (clouds.empty()) throw std::invalid_argument("no clouds to merge");
  auto name = [](std::size_t i) { return "cloud_" + std::to_string(i); };
  auto out = std::make_shared<Cloud>();
  out->header.frame_id = frame.empty() ? clouds.front()->header.frame_id : frame;
  const std::string& target = out->header.frame_id;
  if (frame.empty())
    for (std::size_t i = 1; i < clouds.size(); ++i)
      if (clouds[i]->header.frame_id != target)
        throw std::invalid_argument(name(i) + " is in frame '" + clouds[i]->header.frame_id + "', cloud_0 in '" + target +
                                    "': set `frame` to merge clouds of different frames");
  std::vector<PlacedPoints> placed;
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    const Cloud& c = *clouds[i];
    if (i == 0 || c.header.stamp > out->header.stamp) out->header.stamp = c.header.stamp;
    if (pointCount(c) == 0) continue;
    for (const char* xyz : {"x", "y", "z"}) requireField(c, xyz);
    PlacedPoints p{c.points, Eigen::Affine3f::Identity()};
    if (c.header.frame_id != target) {
      try {
        p.pose = lookup(target, c.header.frame_id, c.header.stamp);
      } catch (const std::exception& e) {
        throw std::runtime_error("no transform " + c.header.frame_id + " -> " + target + " at " +
                                 std::to_string(c.header.stamp.toSec()) + " for " + name(i) + ": " + e.what());
      }
    }
    placed.push_back(std::move(p));
  }
  if (placed.empty()) throw std::invalid_argument("all " + std::to_string(clouds.size()) + " clouds are empty");
  out->points = mergePoints(placed, std::move(into));
  return out;
}

}  // namespace apex_nodes
