// MovingLeastSquares and FPFHEstimation, on a cloud's finite points. MovingLeastSquares smooths a
// noisy surface: each point moves onto a polynomial fitted to its neighbours, and can take that
// surface's normal and curvature along. FPFHEstimation describes the shape around each point by a
// 33-bin histogram (fast point feature histogram), e.g. to match two views of an object. Both make
// new points (x, y, z and what they compute), so the input's other fields do not pass; both run on
// one thread, so a cloud gives the same result, in the same order, every time.
#include <pcl/common/io.h>
#include <pcl/common/point_tests.h>
#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/surface/mls.h>

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** The cloud's finite points, in their order, as one row: PCL's searches must not be asked about a
 *  NaN point, and a row makes PCL search with its k-d tree, as for any unorganised cloud. */
std::shared_ptr<XyzCloud> finitePoints(const Cloud& cloud) {
  const auto xyz = xyzOf(cloud);  // checks x, y, z and that some point is finite
  auto out = std::make_shared<XyzCloud>();
  out->reserve(xyz->size());
  for (const pcl::PointXYZ& p : *xyz)
    if (pcl::isFinite(p)) out->push_back(p);  // width follows, height 1, dense
  return out;
}

/** x, y, z and each point's histogram as the field "fpfh" (33 float32, as pcl::toPCLPointCloud2
 *  names FPFHSignature33's), one row, unpadded. */
std::shared_ptr<Blob> withHistograms(const XyzCloud& xyz, const pcl::PointCloud<pcl::FPFHSignature33>& features) {
  constexpr std::uint32_t kBins = 33, kXyz = 3 * sizeof(float), kHistogram = kBins * sizeof(float);
  static_assert(sizeof(pcl::FPFHSignature33::histogram) == kHistogram, "FPFHSignature33 has 33 bins");
  auto field = [](const char* name, std::uint32_t offset, std::uint32_t count) {
    pcl::PCLPointField f;
    f.name = name, f.offset = offset, f.datatype = pcl::PCLPointField::FLOAT32, f.count = count;
    return f;
  };
  auto out = std::make_shared<Blob>();
  out->fields = {field("x", 0, 1), field("y", 4, 1), field("z", 8, 1), field("fpfh", kXyz, kBins)};
  out->point_step = kXyz + kHistogram;
  out->height = 1;
  out->width = static_cast<pcl::uindex_t>(xyz.size());
  out->row_step = out->point_step * out->width;
  out->is_dense = features.is_dense;  // PCL's: false if some histogram is NaN
  out->data.resize(std::size_t(out->row_step));
  std::uint8_t* to = out->data.data();
  for (std::size_t i = 0; i < xyz.size(); ++i, to += out->point_step) {
    std::memcpy(to, xyz[i].data, kXyz);
    std::memcpy(to + kXyz, features[i].histogram, kHistogram);
  }
  return out;
}

}  // namespace

/** PCL leaves the normal of a point whose fit failed (its neighbours on a line: no plane) as
 *  whatever its memory held; such a point keeps its place, and gets NaN for a normal here. */
inline void noNormalWhereTheFitFailed(const pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal>& mls,
                                      pcl::PointCloud<pcl::PointNormal>& smoothed) {
  const auto& fits = mls.getMLSResults();
  const auto& from = mls.getCorrespondingIndices()->indices;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < smoothed.size() && i < from.size(); ++i)
    if (!fits.at(from[i]).valid) smoothed[i].normal_x = smoothed[i].normal_y = smoothed[i].normal_z = smoothed[i].curvature = nan;
}

class MovingLeastSquares : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud"};
  static inline const apex::OutputPort<Cloud> kCloudOut{
      "cloud",
      "x, y, z smoothed (and normal_x, normal_y, normal_z, curvature with compute_normals), one row; a point with "
      "fewer than 2 others within search_radius is left out"};
  static inline const apex::ParamDecl<double> kSearchRadius =
      param::number("search_radius")
          .range(0.001, 10.0)
          .step(0.001)
          .init(0.03)
          .describe("metres: the neighbours each point's surface is fitted to (weighted by a Gaussian of this width)");
  static inline const apex::ParamDecl<int> kPolynomialOrder =
      param::integer("polynomial_order").range(0, 5).step(1).init(2).describe("of the surface fitted; 0 or 1: a plane");
  static inline const apex::ParamDecl<bool> kComputeNormals =
      param::flag("compute_normals").init(true).describe("also send the fitted surface's normal and curvature at each point");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Smooths a cloud (PCL's MovingLeastSquares): each point moved onto a polynomial surface fitted to its "
               "neighbours")
        .inCategory("clouds")
        .input(kCloudIn)
        .output(kCloudOut)
        .param(kSearchRadius)
        .param(kPolynomialOrder)
        .param(kComputeNormals);
  }
  void process() override {
    const auto in = in_.get();
    const auto points = finitePoints(*in);
    pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
    mls.setInputCloud(points);
    mls.setSearchRadius(radius_.get());
    mls.setPolynomialOrder(order_.get());
    mls.setComputeNormals(normals_.get());
    mls.setNumberOfThreads(1);  // the graph's thread groups are the parallelism; one thread keeps the order
    mls.setCacheMLSResults(true);  // to tell the fits that failed
    pcl::PointCloud<pcl::PointNormal> smoothed;
    mls.process(smoothed);
    noNormalWhereTheFitFailed(mls, smoothed);
    if (smoothed.empty())
      throw std::invalid_argument("none of the cloud's " + std::to_string(points->size()) +
                                  " finite points has 2 others within search_radius " + std::to_string(radius_.get()) + " m");
    if (normals_.get()) {
      out_.publish(cloudResult(*in, toBlob(smoothed)));
    } else {
      XyzCloud xyz;
      pcl::copyPointCloud(smoothed, xyz);
      out_.publish(cloudResult(*in, toBlob(xyz)));
    }
  }

 private:
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kCloudOut};
  apex::Param<double> radius_{this, kSearchRadius};
  apex::Param<int> order_{this, kPolynomialOrder};
  apex::Param<bool> normals_{this, kComputeNormals};
};

class FPFHEstimation : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud"};
  static inline const apex::OutputPort<Cloud> kFeatures{
      "features",
      "the finite points' x, y, z, one row, each with its histogram as the field fpfh (33 float32; NaN where the "
      "neighbourhood is too small)"};
  enum class Search { kRadius, kNearest };
  static inline const apex::ChoiceDecl<Search> kNormalSearch =
      param::choice<Search>("normal_search", {{"radius", Search::kRadius, "those within normal_radius"},
                                              {"k", Search::kNearest, "the normal_k nearest"}})
          .describe("the neighbours each point's normal is estimated from");
  static inline const apex::ParamDecl<double> kNormalRadius =
      param::number("normal_radius").range(0.001, 10.0).step(0.001).init(0.03).describe("metres (normal_search: radius)");
  static inline const apex::ParamDecl<int> kNormalK =
      param::integer("normal_k").range(3, 1000).step(1).init(20).describe("normal_search: k");
  static inline const apex::ParamDecl<double> kFeatureRadius =
      param::number("feature_radius")
          .range(0.001, 10.0)
          .step(0.001)
          .init(0.05)
          .describe("metres: the neighbourhood each histogram describes; larger than the normals' neighbourhood");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Fast point feature histograms (PCL's FPFHEstimation): the shape around each point in 33 bins, from "
               "normals it estimates first (PCL's NormalEstimation)")
        .inCategory("cloud features")
        .input(kCloudIn)
        .output(kFeatures)
        .param(kNormalSearch)
        .param(kNormalRadius)
        .param(kNormalK)
        .param(kFeatureRadius);
  }
  void process() override {
    const auto in = in_.get();
    const auto points = finitePoints(*in);
    auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
    pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
    estimation.setInputCloud(points);
    if (normal_search_.get() == Search::kNearest) estimation.setKSearch(normal_k_.get());
    else estimation.setRadiusSearch(normal_radius_.get());
    estimation.compute(*normals);
    pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> fpfh;
    fpfh.setInputCloud(points);
    fpfh.setInputNormals(normals);
    fpfh.setRadiusSearch(feature_radius_.get());
    pcl::PointCloud<pcl::FPFHSignature33> features;
    fpfh.compute(features);
    if (normals->size() != points->size() || features.size() != points->size())
      throw std::invalid_argument("PCL computed no histograms for the cloud's " + std::to_string(points->size()) +
                                  " finite points");
    out_.publish(cloudResult(*in, withHistograms(*points, features)));
  }

 private:
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kFeatures};
  apex::Choice<Search> normal_search_{this, kNormalSearch};
  apex::Param<double> normal_radius_{this, kNormalRadius};
  apex::Param<int> normal_k_{this, kNormalK};
  apex::Param<double> feature_radius_{this, kFeatureRadius};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::MovingLeastSquares, "apex_nodes/MovingLeastSquares");
APEX_REGISTER_NODE(apex_nodes::FPFHEstimation, "apex_nodes/FPFHEstimation");
