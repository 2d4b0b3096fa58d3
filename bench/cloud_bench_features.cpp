// apex_bench_clouds' node table, continued: sampling, keypoints, region growing, conditional
// clustering and the concave hull, each node against its PCL call on the typed table scene
// (cloud_bench_nodes.cpp), the call copying what the node sends (kept points, clusters) as a
// pcl_conversions user would.
#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/random_sample.h>
#include <pcl/filters/uniform_sampling.h>
#include <pcl/keypoints/harris_3d.h>
#include <pcl/keypoints/iss_3d.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/conditional_euclidean_clustering.h>
#include <pcl/segmentation/region_growing.h>
#include <pcl/segmentation/region_growing_rgb.h>
#include <pcl/surface/concave_hull.h>
#include <pcl/surface/mls.h>

#include <cmath>
#include <limits>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/maps.hpp"
#include "node_vs_call.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Cloud;
using apex_nodes::Clusters;
using Point = pcl::PointXYZRGB;
using Typed = pcl::PointCloud<Point>;
using TypedPtr = Typed::ConstPtr;

struct Scene {
  TypedPtr points;
  std::shared_ptr<const Cloud> cloud;
  std::string words;
  /** A node of the scene in, against `call` on its typed points. */
  NodeCase node(std::string type, Params params, std::string out_port, std::string sink, std::string call_text,
                std::function<void(const TypedPtr&)> call) const {
    return fixedCase(type, "apex_nodes/" + type, words, feedType<Cloud>(), {"cloud"}, {apex::Message::share<Cloud>(cloud)},
                     std::move(params), std::move(out_port), std::move(sink), std::move(call_text),
                     [points = points, call = std::move(call)] { call(points); });
  }
};

/** Each cluster's points copied, as the node sends them whole. */
void copyClusters(const Typed& in, const std::vector<pcl::PointIndices>& found, std::vector<Typed>& out) {
  out.resize(found.size());
  for (std::size_t i = 0; i < found.size(); ++i) pcl::copyPointCloud(in, found[i], out[i]);
}

}  // namespace

std::vector<NodeCase> cloudFeatureCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud) {
  const Scene s{scene, cloud, "table scene, " + std::to_string(scene->size()) + " points"};
  std::vector<NodeCase> c;
  c.push_back(s.node("RandomSample", {{"sample", "3000"}, {"seed", "1"}}, "cloud", sinkType<Cloud>(), "RandomSample 3000",
                     [out = Typed()](const TypedPtr& in) mutable {
                       pcl::RandomSample<Point> f;
                       f.setInputCloud(in), f.setSample(3000), f.setSeed(1);
                       f.filter(out);
                     }));
  c.push_back(over(s.node("UniformSampling", {{"radius", "0.05"}}, "cloud", sinkType<Cloud>(), "UniformSampling 5 cm",
                          [out = Typed()](const TypedPtr& in) mutable {
                            pcl::UniformSampling<Point> f;
                            f.setInputCloud(in), f.setRadiusSearch(0.05);
                            f.filter(out);
                          }),
                   "every field kept: an x, y, z view of every point, then the kept points copied whole"));
  c.push_back(s.node("ISSKeypoints", {{"salient_radius", "0.06"}, {"non_max_radius", "0.04"}}, "keypoints", sinkType<Cloud>(),
                     "ISSKeypoint3D 6 cm, 4 cm, 1 thread", [out = Typed()](const TypedPtr& in) mutable {
                       pcl::ISSKeypoint3D<Point, Point> iss;
                       iss.setSearchMethod(pcl::make_shared<pcl::search::KdTree<Point>>());
                       iss.setSalientRadius(0.06), iss.setNonMaxRadius(0.04), iss.setThreshold21(0.975);
                       iss.setThreshold32(0.975), iss.setMinNeighbors(5), iss.setNumberOfThreads(1);
                       iss.setInputCloud(in);
                       iss.compute(out);
                     }));
  c.push_back(s.node("HarrisKeypoints3D", {{"radius", "0.05"}, {"threshold", "0.0001"}}, "keypoints", sinkType<Cloud>(),
                     "HarrisKeypoint3D 5 cm, 1 thread", [out = pcl::PointCloud<pcl::PointXYZI>()](const TypedPtr& in) mutable {
                       using Harris = pcl::HarrisKeypoint3D<Point, pcl::PointXYZI>;
                       Harris h(Harris::HARRIS, 0.05f, 0.0001f);
                       h.setNonMaxSupression(true), h.setRefine(true), h.setNumberOfThreads(1);
                       h.setSearchMethod(pcl::make_shared<pcl::search::KdTree<Point>>());
                       h.setInputCloud(in);
                       h.compute(out);
                     }));
  c.push_back(s.node("RegionGrowing", {}, "clusters", sinkType<Clusters>(),
                     "NormalEstimation k 30; RegionGrowing 3°, 30 neighbours; copy each region",
                     [normals = pcl::make_shared<pcl::PointCloud<pcl::Normal>>(), found = std::vector<pcl::PointIndices>(),
                      out = std::vector<Typed>()](const TypedPtr& in) mutable {
                       auto tree = pcl::make_shared<pcl::search::KdTree<Point>>();
                       pcl::NormalEstimation<Point, pcl::Normal> ne;
                       ne.setSearchMethod(tree), ne.setInputCloud(in), ne.setKSearch(30);
                       ne.compute(*normals);
                       pcl::RegionGrowing<Point, pcl::Normal> grow;
                       grow.setMinClusterSize(50), grow.setMaxClusterSize(1000000), grow.setSearchMethod(tree);
                       grow.setNumberOfNeighbours(30), grow.setInputCloud(in), grow.setInputNormals(normals);
                       grow.setSmoothnessThreshold(3.0 / 180.0 * M_PI), grow.setCurvatureThreshold(1.0);
                       found.clear();
                       grow.extract(found);
                       copyClusters(*in, found, out);
                     }));
  c.push_back(s.node("RegionGrowingRGB", {}, "clusters", sinkType<Clusters>(), "RegionGrowingRGB 5 cm, 6, 5; copy each region",
                     [found = std::vector<pcl::PointIndices>(), out = std::vector<Typed>()](const TypedPtr& in) mutable {
                       pcl::RegionGrowingRGB<Point> grow;
                       grow.setInputCloud(in), grow.setSearchMethod(pcl::make_shared<pcl::search::KdTree<Point>>());
                       grow.setDistanceThreshold(0.05f), grow.setPointColorThreshold(6), grow.setRegionColorThreshold(5);
                       grow.setMinClusterSize(50), grow.setMaxClusterSize(1000000);
                       found.clear();
                       grow.extract(found);
                       copyClusters(*in, found, out);
                     }));
  c.push_back(s.node("ConditionalEuclideanClustering", {}, "clusters", sinkType<Clusters>(),
                     "ConditionalEuclideanClustering 5 cm, colour 30; copy each cluster",
                     [found = pcl::IndicesClusters(), out = std::vector<Typed>()](const TypedPtr& in) mutable {
                       pcl::ConditionalEuclideanClustering<Point> cec;
                       cec.setInputCloud(in);
                       cec.setConditionFunction(
                           std::function<bool(const Point&, const Point&, float)>([](const Point& a, const Point& b, float) {
                             const float r = float(a.r) - b.r, g = float(a.g) - b.g, bl = float(a.b) - b.b;
                             return r * r + g * g + bl * bl <= 30.f * 30.f;
                           }));
                       cec.setClusterTolerance(0.05f), cec.setMinClusterSize(50), cec.setMaxClusterSize(1000000);
                       found.clear();
                       cec.segment(found);
                       copyClusters(*in, found, out);
                     }));
  auto plane = pcl::make_shared<Typed>();  // the table top: the points below the boxes
  for (const Point& p : *scene)
    if (p.z > 1.45f) plane->push_back(p);
  const Scene top{plane, apex_nodes::makeCloud(cloud->header, *plane),
                  "the scene's table top, " + std::to_string(plane->size()) + " points"};
  c.push_back(top.node("ConcaveHull", {{"alpha", "0.1"}, {"dimension", "2"}}, "hull", sinkType<Cloud>(),
                       "ConcaveHull 2D, alpha 10 cm, keeping information", [out = Typed()](const TypedPtr& in) mutable {
                         pcl::ConcaveHull<Point> h;
                         h.setInputCloud(in), h.setAlpha(0.1), h.setDimension(2), h.setKeepInformation(true);
                         h.reconstruct(out);
                       }));
  c.push_back(
      over(s.node("MovingLeastSquares", {{"search_radius", "0.03"}, {"polynomial_order", "2"}, {"compute_normals", "true"}},
                  "cloud", sinkType<Cloud>(), "MovingLeastSquares 3 cm, order 2, normals, 1 thread",
                  [out = pcl::PointCloud<pcl::PointNormal>()](const TypedPtr& in) mutable {
                    pcl::MovingLeastSquares<Point, pcl::PointNormal> mls;
                    mls.setInputCloud(in), mls.setSearchRadius(0.03), mls.setPolynomialOrder(2);
                    mls.setComputeNormals(true), mls.setNumberOfThreads(1);
                    mls.process(out);
                  }),
           "the finite points' x, y, z copied out first; the smoothed points made the cloud it sends"));
  c.push_back(
      over(s.node("FPFHEstimation", {{"normal_radius", "0.03"}, {"feature_radius", "0.05"}}, "features", sinkType<Cloud>(),
                  "NormalEstimation 3 cm; FPFHEstimation 5 cm",
                  [normals = pcl::make_shared<pcl::PointCloud<pcl::Normal>>(),
                   out = pcl::PointCloud<pcl::FPFHSignature33>()](const TypedPtr& in) mutable {
                    pcl::NormalEstimation<Point, pcl::Normal> ne;
                    ne.setInputCloud(in), ne.setRadiusSearch(0.03);
                    ne.compute(*normals);
                    pcl::FPFHEstimation<Point, pcl::Normal, pcl::FPFHSignature33> fpfh;
                    fpfh.setInputCloud(in), fpfh.setInputNormals(normals), fpfh.setRadiusSearch(0.05);
                    fpfh.compute(out);
                  }),
           "the finite points' x, y, z copied out first; each one's x, y, z and histogram copied into the cloud it sends"));
  // The map nodes' binning by hand: the points with z in [1, 2] m on the grid of 2 cm cells (as a
  // float, as the message holds it) just covering them, each one's cell and z.
  const auto binByHand = [](const Typed& in, std::vector<std::pair<long, float>>& binned) {
    const double resolution = 0.02f;
    const auto kept = [](const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && p.z >= 1.0 && p.z <= 2.0; };
    float x1 = std::numeric_limits<float>::max(), y1 = x1, x2 = -x1, y2 = -x1;
    for (const Point& p : in)
      if (kept(p)) x1 = std::min(x1, p.x), y1 = std::min(y1, p.y), x2 = std::max(x2, p.x), y2 = std::max(y2, p.y);
    const int w = int(std::floor((x2 - double(x1)) / resolution)) + 1, h = int(std::floor((y2 - double(y1)) / resolution)) + 1;
    binned.clear();
    for (const Point& p : in)
      if (kept(p)) binned.push_back({long((p.y - double(y1)) / resolution) * w + long((p.x - double(x1)) / resolution), p.z});
    return std::make_pair(w, h);
  };
  const Params band{{"z_band", "[1.0, 2.0]"}, {"resolution", "0.02"}};
  Params occupancy = band;
  occupancy.push_back({"min_points", "3"});
  c.push_back(over(s.node("CloudToOccupancyGrid", occupancy, "grid", sinkType<nav_msgs::OccupancyGrid>(),
                          "by hand: z in [1, 2] m, bounds, counts per 2 cm cell, the grid's data (3 points: occupied)",
                          [binByHand, binned = std::vector<std::pair<long, float>>(), counts = std::vector<int>(),
                           data = std::vector<std::int8_t>()](const TypedPtr& in) mutable {
                            const auto [w, h] = binByHand(*in, binned);
                            counts.assign(std::size_t(w) * h, 0);
                            for (const auto& b : binned) ++counts[b.first];
                            data.resize(counts.size());
                            for (std::size_t k = 0; k < counts.size(); ++k)
                              data[k] = counts[k] == 0 ? -1 : counts[k] >= 3 ? 100 : 0;
                          }),
                   "the x, y, z copied out first; a new grid message each frame"));
  c.push_back(
      over(s.node("HeightMap", band, "heights", sinkType<apex_nodes::Image>(),
                  "by hand: z in [1, 2] m, bounds, the highest z per 2 cm cell (NaN where none)",
                  [binByHand, binned = std::vector<std::pair<long, float>>(), heights = cv::Mat()](const TypedPtr& in) mutable {
                    const auto [w, h] = binByHand(*in, binned);
                    heights.create(h, w, CV_32F);
                    heights.setTo(std::numeric_limits<float>::quiet_NaN());
                    float* top = heights.ptr<float>();
                    for (const auto& b : binned)
                      if (!(top[b.first] >= b.second)) top[b.first] = b.second;
                  }),
           "the x, y, z copied out first; a new image each frame"));
  return c;
}

}  // namespace apex_bench
