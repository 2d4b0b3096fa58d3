// ClusterFeatures: each cluster's centroid, axis-aligned box and oriented box (cluster_features.hpp).
// The oriented box comes from PCA of the points' covariance (Eigen), as
// pcl::MomentOfInertiaEstimation::getOBB makes it (its axes, its box), without what that class
// computes besides (moments of inertia and eccentricities at 370 angles, each a pass over the
// points) and without pcl_features, which the node libraries do not link.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "apex/core/registry.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/cluster_features.hpp"

namespace apex_nodes {
namespace {

bool finite(const pcl::PointXYZ& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
Eigen::Vector3d at(const pcl::PointXYZ& p) { return {p.x, p.y, p.z}; }

/** `v` or -v, whichever has its largest component positive: the same axis comes out the same way. */
Eigen::Vector3d canonical(const Eigen::Vector3d& v) {
  Eigen::Index i = 0;
  v.cwiseAbs().maxCoeff(&i);
  return v[i] < 0 ? Eigen::Vector3d(-v) : v;
}

/** The features of one cluster's finite points (in double: clouds far from their origin keep their
 *  millimetres). Two passes over the points: the count, the box and the moments, then the extent
 *  along the principal axes. */
ClusterFeature measure(const XyzCloud& points, int label) {
  ClusterFeature f;
  f.label = label;
  f.min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  f.max = -f.min;
  // The sums are of each point less the first finite one: so shifted, the covariance from them
  // (E[dd'] - E[d]E[d]') keeps its precision far from the origin, as a second pass over the
  // points less their mean would, without that pass.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), sum = Eigen::Vector3d::Zero();
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (const auto& p : points) {
    if (!finite(p)) continue;
    const Eigen::Vector3d q = at(p);
    if (f.points++ == 0) origin = q;
    f.min = f.min.cwiseMin(q), f.max = f.max.cwiseMax(q);
    const Eigen::Vector3d d = q - origin;
    sum += d;
    xx += d.x() * d.x(), xy += d.x() * d.y(), xz += d.x() * d.z();
    yy += d.y() * d.y(), yz += d.y() * d.z(), zz += d.z() * d.z();
  }
  if (f.points == 0) {
    f.min = f.max = Eigen::Vector3d::Zero();
    return f;
  }
  const double n = double(f.points);
  const Eigen::Vector3d mean = sum / n;
  f.centroid = origin + mean;
  f.extent = f.max - f.min;
  Eigen::Matrix3d covariance;
  covariance << xx / n, xy / n, xz / n, xy / n, yy / n, yz / n, xz / n, yz / n, zz / n;
  covariance -= mean * mean.transpose();
  // Eigenvalues ascending: the last vector spreads the points most. z = x × y, so the axes are a
  // rotation (not a reflection) and make a valid quaternion.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(covariance);
  Eigen::Matrix3d axes;
  axes.col(0) = canonical(pca.eigenvectors().col(2)).normalized();
  axes.col(1) = canonical(pca.eigenvectors().col(1)).normalized();
  axes.col(2) = axes.col(0).cross(axes.col(1));

  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const auto& p : points) {
    if (!finite(p)) continue;
    const Eigen::Vector3d local = axes.transpose() * (at(p) - f.centroid);
    low = low.cwiseMin(local), high = high.cwiseMax(local);
  }
  f.oriented.extent = high - low;
  f.oriented.centre = f.centroid + axes * (0.5 * (low + high));
  f.oriented.orientation = Eigen::Quaterniond(axes).normalized();
  return f;
}

}  // namespace

/** The node type apex_nodes/ClusterFeatures (the C++ name ClusterFeatures is its output's type). */
class ClusterFeaturesNode : public apex::Node {
 public:
  static inline const apex::InputPort<Clusters> kClusters{"clusters"};
  static inline const apex::OutputPort<ClusterFeatures> kFeatures{
      "features", "per cluster, in its order: centroid, axis-aligned and oriented box, point count"};
  static inline const apex::OutputPort<int> kCount{"count", "clusters"};
  static inline const apex::OutputPort<geometry_msgs::PoseArray> kPoses{
      "poses", "each cluster's oriented box as a pose (centre, PCA axes): rviz shows them as arrows"};
  static apex::Manifest manifest() {
    return apex::Manifest("Measures each cluster: centroid, axis-aligned box, oriented box (PCA), point count")
        .inCategory("cloud segmentation")
        .input(kClusters)
        .output(kFeatures)
        .output(kCount)
        .output(kPoses);
  }
  void process() override {
    const auto in = clusters_.get();
    auto out = std::make_shared<ClusterFeatures>();
    out->header = in->header;
    out->clusters.reserve(in->clusters.size());
    for (std::size_t i = 0; i < in->clusters.size(); ++i) {
      const Cloud cluster{in->header, in->clusters[i]};
      try {
        for (const char* xyz : {"x", "y", "z"}) requireField(cluster, xyz);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("cluster " + std::to_string(i) + ": " + e.what());
      }
      copyXyz(*cluster.points, xyz_);  // into the same memory each time
      out->clusters.push_back(measure(xyz_, static_cast<int>(i)));
    }
    auto poses = std::make_shared<geometry_msgs::PoseArray>();
    poses->header = in->header;
    for (const auto& c : out->clusters) {
      geometry_msgs::Pose p;
      p.position.x = c.oriented.centre.x(), p.position.y = c.oriented.centre.y(), p.position.z = c.oriented.centre.z();
      const Eigen::Quaterniond& q = c.oriented.orientation;
      p.orientation.x = q.x(), p.orientation.y = q.y(), p.orientation.z = q.z(), p.orientation.w = q.w();
      poses->poses.push_back(p);
    }
    count_.publish(static_cast<int>(out->clusters.size()));
    poses_.publish(std::move(poses));
    features_.publish(out);
  }

 private:
  apex::Input<Clusters> clusters_{this, kClusters};
  apex::Output<ClusterFeatures> features_{this, kFeatures};
  apex::Output<int> count_{this, kCount};
  apex::Output<geometry_msgs::PoseArray> poses_{this, kPoses};
  XyzCloud xyz_;  // one cluster's x, y, z at a time
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ClusterFeaturesNode, "apex_nodes/ClusterFeatures");
