// TransformCloud: moves a cloud into another frame with a tf2 transform: x, y, z and the normals,
// if it has them; every other field as it was.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstring>
#include <optional>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {

/** @brief The transform as a matrix that maps points of its child frame into its frame. */
inline Eigen::Affine3f toEigen(const geometry_msgs::Transform& t) {
  const Eigen::Quaternionf q(static_cast<float>(t.rotation.w), static_cast<float>(t.rotation.x),
                             static_cast<float>(t.rotation.y), static_cast<float>(t.rotation.z));
  Eigen::Affine3f m = Eigen::Affine3f::Identity();
  m.translate(Eigen::Vector3f(static_cast<float>(t.translation.x), static_cast<float>(t.translation.y),
                              static_cast<float>(t.translation.z)));
  m.rotate(q.normalized());
  return m;
}

namespace {

/** Each point's float32 triple at `offsets` through `f`, in place (memcpy: fields may be unaligned). */
template <class F>
void eachTriple(Blob& points, const std::array<std::uint32_t, 3>& offsets, F f) {
  const std::size_t count = std::size_t(points.width) * points.height;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint8_t* p = &points.data[(i / points.width) * points.row_step + (i % points.width) * points.point_step];
    Eigen::Vector3f v;
    for (int k = 0; k < 3; ++k) std::memcpy(&v[k], p + offsets[k], sizeof(float));
    v = f(v);
    for (int k = 0; k < 3; ++k) std::memcpy(p + offsets[k], &v[k], sizeof(float));
  }
}

/** The offsets of three float32 fields, if the cloud has all three. */
std::optional<std::array<std::uint32_t, 3>> triple(const Blob& points, const std::array<const char*, 3>& names) {
  std::array<std::uint32_t, 3> out{};
  for (int k = 0; k < 3; ++k) {
    auto f = std::find_if(points.fields.begin(), points.fields.end(), [&](const auto& f) { return f.name == names[k]; });
    if (f == points.fields.end() || f->datatype != pcl::PCLPointField::FLOAT32) return std::nullopt;
    out[k] = f->offset;
  }
  return out;
}

}  // namespace

/** @brief The points moved by `m`: x, y, z, and the normals turned; every other field kept. */
inline std::shared_ptr<Blob> transformPoints(const Blob& in, const Eigen::Affine3f& m) {
  auto out = std::make_shared<Blob>(in);
  eachTriple(*out, *triple(in, {"x", "y", "z"}), [&](const Eigen::Vector3f& v) { return m * v; });
  if (auto normals = triple(in, {"normal_x", "normal_y", "normal_z"}))
    eachTriple(*out, *normals, [&](const Eigen::Vector3f& v) { return m.linear() * v; });
  return out;
}

class TransformCloud : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud"};
  static inline const apex::InputPort<geometry_msgs::TransformStamped> kTransform{"transform"};
  static inline const apex::OutputPort<Cloud> kCloudOut{"cloud"};
  static apex::Manifest manifest() {
    return apex::Manifest("Transforms a cloud into the transform's frame (e.g. from TfLookup)")
        .input(kCloudIn)
        .input(kTransform)
        .output(kCloudOut);
  }
  void process() override {
    auto in = cloud_in_.get();
    const auto& t = *transform_.get();
    requirePoints(*in);
    if (!t.child_frame_id.empty() && t.child_frame_id != in->header.frame_id)
      throw std::invalid_argument("the transform maps frame '" + t.child_frame_id + "', the cloud is in '" +
                                  in->header.frame_id + "'");
    auto out = cloudResult(*in, transformPoints(*in->points, toEigen(t.transform)));
    out->header.frame_id = t.header.frame_id;
    cloud_out_.publish(out);
  }

 private:
  apex::Input<Cloud> cloud_in_{this, kCloudIn};
  apex::Input<geometry_msgs::TransformStamped> transform_{this, kTransform};
  apex::Output<Cloud> cloud_out_{this, kCloudOut};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TransformCloud, "apex_nodes/TransformCloud");
