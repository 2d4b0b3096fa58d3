// apex_bench_clouds' second table: each cloud node type alone against its PCL call on a typed
// cloud (pcl::PointCloud<pcl::PointXYZRGB>, as a pcl_conversions user holds it), measured as the
// image nodes are (node_vs_call.hpp): what keeping every field and the message costs a node.
#include <pcl/common/transforms.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/crop_box.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/project_inliers.h>
#include <pcl/filters/radius_outlier_removal.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/extract_polygonal_prism_data.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <pcl/surface/convex_hull.h>

#include <random>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/stamp.hpp"
#include "node_vs_call.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Cloud;
using Point = pcl::PointXYZRGB;
using Typed = pcl::PointCloud<Point>;
using TypedPtr = Typed::ConstPtr;

/** A table top seen from above: a 2 x 2 m plane of 24k points (1 cm noise) and three boxes of 2k
 *  points on it, coloured. What segmentation, clustering and hulls are made for. */
Typed tableScene() {
  Typed c;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.f, 1.f), box(-0.08f, 0.08f);
  std::normal_distribution<float> noise(0.f, 0.003f);
  for (int i = 0; i < 24000; ++i) {
    Point p(std::uint8_t(100), std::uint8_t(120), std::uint8_t(140));
    p.x = u(rng), p.y = u(rng), p.z = 1.5f + noise(rng);
    c.push_back(p);
  }
  for (const float cx : {-0.5f, 0.f, 0.5f})
    for (int i = 0; i < 2000; ++i) {
      Point p(std::uint8_t(200), std::uint8_t(40), std::uint8_t(40));
      p.x = cx + box(rng), p.y = 0.3f + box(rng), p.z = 1.4f + box(rng) / 2;
      c.push_back(p);
    }
  return c;
}

struct Shared {
  TypedPtr scene;
  std::shared_ptr<const Cloud> cloud;
};

/** A node of one cloud input ("cloud") fed the scene, against `call` on the typed scene. */
NodeCase cloudCase(const Shared& s, std::string type, Params params, std::string out_port, std::string call_text,
                   std::function<void(const TypedPtr&)> call, std::string label = "") {
  NodeCase c;
  c.label = label.empty() ? type : label;
  c.type = "apex_nodes/" + type;
  c.input = "table scene, " + std::to_string(s.scene->size()) + " points";
  c.feed = feedType<Cloud>();
  c.in_ports = {"cloud"};
  c.frames = {{apex::Message::share<Cloud>(s.cloud)}};
  c.params = std::move(params);
  c.out_port = std::move(out_port);
  c.sink = sinkType<Cloud>();
  c.call_text = std::move(call_text);
  c.call = [scene = s.scene, call = std::move(call)](std::size_t) { call(scene); };
  return c;
}

template <class Filter>
std::function<void(const TypedPtr&)> filtered(std::function<void(Filter&)> configure) {
  return [configure, out = Typed()](const TypedPtr& in) mutable {
    Filter f;
    f.setInputCloud(in);
    configure(f);
    f.filter(out);
  };
}

std::vector<NodeCase> filterCases(const Shared& s) {
  std::vector<NodeCase> c;
  c.push_back(over(cloudCase(s, "VoxelGrid", {{"leaf_size", "0.05"}}, "cloud", "VoxelGrid 5 cm",
                             filtered<pcl::VoxelGrid<Point>>([](auto& f) { f.setLeafSize(0.05f, 0.05f, 0.05f); })),
                   "every field kept: the points go to a typed XYZRGB cloud and back, which PCL copies field by field"));
  c.push_back(over(cloudCase(s, "PassThrough", {{"field", "z"}, {"limits", "[1.45, 2.0]"}}, "cloud", "PassThrough z 1.45..2",
                             filtered<pcl::PassThrough<Point>>([](auto& f) {
                               f.setFilterFieldName("z");
                               f.setFilterLimits(1.45f, 2.f);
                             })),
                   "every field kept: an x, y, z view of every point, then the kept points copied whole"));
  c.push_back(over(cloudCase(s, "CropBox", {{"x", "[-0.5, 0.5]"}, {"y", "[-0.5, 0.5]"}, {"z", "[1, 2]"}}, "cloud",
                             "CropBox 1 x 1 x 1 m", filtered<pcl::CropBox<Point>>([](auto& f) {
                               f.setMin(Eigen::Vector4f(-0.5, -0.5, 1, 1));
                               f.setMax(Eigen::Vector4f(0.5, 0.5, 2, 1));
                             })),
                   "every field kept: an x, y, z view of every point, then the kept points copied whole"));
  c.push_back(cloudCase(s, "StatisticalOutlierRemoval", {{"mean_k", "20"}, {"stddev", "1"}}, "cloud",
                        "StatisticalOutlierRemoval 20, 1", filtered<pcl::StatisticalOutlierRemoval<Point>>([](auto& f) {
                          f.setMeanK(20);
                          f.setStddevMulThresh(1.0);
                        })));
  c.push_back(cloudCase(s, "RadiusOutlierRemoval", {{"radius", "0.05"}, {"min_neighbours", "5"}}, "cloud",
                        "RadiusOutlierRemoval 5 cm, 5", filtered<pcl::RadiusOutlierRemoval<Point>>([](auto& f) {
                          f.setRadiusSearch(0.05);
                          f.setMinNeighborsInRadius(5);
                        })));
  auto t = std::make_shared<geometry_msgs::TransformStamped>();
  t->header.frame_id = "base", t->child_frame_id = "camera";
  t->transform.translation.x = 0.1, t->transform.translation.z = 0.5;
  t->transform.rotation.z = std::sin(0.1), t->transform.rotation.w = std::cos(0.1);
  NodeCase transform = cloudCase(s, "TransformCloud", {}, "cloud", "transformPointCloud",
                                 [out = Typed(), a = Eigen::Affine3f(Eigen::Translation3f(0.1f, 0.f, 0.5f) *
                                                                     Eigen::AngleAxisf(0.2f, Eigen::Vector3f::UnitZ()))](
                                     const TypedPtr& in) mutable { pcl::transformPointCloud(*in, out, a); });
  transform.feed = feedType<Cloud, geometry_msgs::TransformStamped>();
  transform.in_ports = {"cloud", "transform"};
  transform.frames[0].push_back(apex::Message::share<geometry_msgs::TransformStamped>(t));
  c.push_back(std::move(transform));
  return c;
}

/** SACSegmentation of a plane, RANSAC 2 cm, 200 iterations, refined: inliers and the rest copied. */
void planeCall(const TypedPtr& in, pcl::PointIndices& inliers, pcl::ModelCoefficients& m, Typed& plane, Typed& rest) {
  pcl::SACSegmentation<Point> seg;
  seg.setOptimizeCoefficients(true);
  seg.setModelType(pcl::SACMODEL_PLANE);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(0.02);
  seg.setMaxIterations(200);
  seg.setInputCloud(in);
  seg.segment(inliers, m);
  pcl::copyPointCloud(*in, inliers, plane);
  pcl::ExtractIndices<Point> extract;
  extract.setInputCloud(in);
  extract.setIndices(pcl::make_shared<pcl::PointIndices>(inliers));
  extract.setNegative(true);
  extract.filter(rest);
}

std::vector<NodeCase> segmentationCases(const Shared& s) {
  std::vector<NodeCase> c;
  const std::string plane_text = "SACSegmentation plane RANSAC 2 cm, 200; copy inliers, ExtractIndices the rest";
  auto plane = [i = pcl::PointIndices(), m = pcl::ModelCoefficients(), a = Typed(), b = Typed()](const TypedPtr& in) mutable {
    planeCall(in, i, m, a, b);
  };
  c.push_back(cloudCase(s, "PlaneSegmentation", {{"distance_threshold", "0.02"}, {"max_iterations", "200"}}, "inliers",
                        plane_text, plane));
  c.push_back(cloudCase(s, "SACSegmentation",
                        {{"model", "plane"}, {"method", "ransac"}, {"distance_threshold", "0.02"}, {"max_iterations", "200"}},
                        "inliers", plane_text, plane, "SACSegmentation (plane)"));
  c.push_back(cloudCase(s, "EuclideanClustering", {{"tolerance", "0.05"}, {"min_size", "50"}, {"max_size", "1000000"}},
                        "clusters", "KdTree, EuclideanClusterExtraction 5 cm; copy each cluster",
                        [found = std::vector<pcl::PointIndices>(), clusters = std::vector<Typed>()](const TypedPtr& in) mutable {
                          auto tree = pcl::make_shared<pcl::search::KdTree<Point>>();
                          tree->setInputCloud(in);
                          pcl::EuclideanClusterExtraction<Point> ec;
                          ec.setClusterTolerance(0.05), ec.setMinClusterSize(50), ec.setMaxClusterSize(1000000);
                          ec.setSearchMethod(tree), ec.setInputCloud(in);
                          found.clear();
                          ec.extract(found);
                          clusters.resize(found.size());
                          for (std::size_t i = 0; i < found.size(); ++i) pcl::copyPointCloud(*in, found[i], clusters[i]);
                        }));
  c.back().sink = sinkType<apex_nodes::Clusters>();
  c.push_back(cloudCase(
      s, "NormalEstimation", {{"search", "radius"}, {"radius", "0.03"}, {"threads", "1"}}, "cloud",
      "NormalEstimationOMP radius 3 cm, 1 thread; concatenateFields",
      [normals = pcl::PointCloud<pcl::Normal>(), out = pcl::PointCloud<pcl::PointXYZRGBNormal>()](const TypedPtr& in) mutable {
        pcl::NormalEstimationOMP<Point, pcl::Normal> ne(1);
        ne.setInputCloud(in);
        ne.setRadiusSearch(0.03);
        ne.compute(normals);
        pcl::concatenateFields(*in, normals, out);
      }));
  return c;
}

/** The scene's plane (its inliers) and its coefficients, as SACSegmentation sends them. */
struct Plane {
  TypedPtr points;
  std::vector<double> coefficients;
};

Plane planeOf(const TypedPtr& scene) {
  pcl::PointIndices i;
  pcl::ModelCoefficients m;
  auto plane = pcl::make_shared<Typed>();
  Typed rest;
  planeCall(scene, i, m, *plane, rest);
  return {plane, std::vector<double>(m.values.begin(), m.values.end())};
}

std::vector<NodeCase> surfaceCases(const Shared& s) {
  std::vector<NodeCase> c;
  const Plane plane = planeOf(s.scene);
  const auto plane_cloud = apex_nodes::makeCloud(s.cloud->header, *plane.points);
  NodeCase hull =
      cloudCase(s, "ConvexHull", {{"dimension", "2"}}, "hull", "ConvexHull 2D", [out = Typed()](const TypedPtr& in) mutable {
        pcl::ConvexHull<Point> h;
        h.setInputCloud(in);
        h.setDimension(2);
        h.reconstruct(out);
      });
  hull.input = "the scene's plane, " + std::to_string(plane.points->size()) + " points";
  hull.frames = {{apex::Message::share<Cloud>(plane_cloud)}};
  hull.call = [points = plane.points, out = Typed()](std::size_t) mutable {
    pcl::ConvexHull<Point> h;
    h.setInputCloud(points);
    h.setDimension(2);
    h.reconstruct(out);
  };
  c.push_back(over(std::move(hull),
                   "every field kept: an x, y, z view of every point and their finite ones' indices, the "
                   "hull's points copied whole; and the area and volume it also sends"));

  auto polygon = pcl::make_shared<Typed>();
  {
    pcl::ConvexHull<Point> h;
    h.setInputCloud(plane.points);
    h.setDimension(2);
    h.reconstruct(*polygon);
  }
  NodeCase prism = cloudCase(s, "ExtractPolygonalPrism", {{"height", "[0.01, 0.5]"}, {"viewpoint", "[0, 0, 0]"}}, "cloud",
                             "ExtractPolygonalPrismData 1..50 cm; copy the points",
                             [polygon, inside = pcl::PointIndices(), out = Typed()](const TypedPtr& in) mutable {
                               pcl::ExtractPolygonalPrismData<Point> p;
                               p.setInputCloud(in);
                               p.setInputPlanarHull(polygon);
                               p.setHeightLimits(0.01, 0.5);
                               p.setViewPoint(0, 0, 0);
                               p.segment(inside);
                               pcl::copyPointCloud(*in, inside, out);
                             });
  prism.feed = feedType<Cloud, Cloud>();
  prism.in_ports = {"cloud", "hull"};
  prism.input += ", its plane's hull";
  prism.frames[0].push_back(apex::Message::share<Cloud>(apex_nodes::makeCloud(s.cloud->header, *polygon)));
  c.push_back(over(std::move(prism), "every field kept: an x, y, z view of every point, then the kept points copied whole"));

  auto coefficients = pcl::make_shared<pcl::ModelCoefficients>();
  coefficients->values.assign(plane.coefficients.begin(), plane.coefficients.end());
  NodeCase project = cloudCase(s, "ProjectInliers", {{"model", "plane"}}, "cloud", "ProjectInliers plane",
                               filtered<pcl::ProjectInliers<Point>>([coefficients](auto& f) {
                                 f.setModelType(pcl::SACMODEL_PLANE);
                                 f.setModelCoefficients(coefficients);
                               }));
  project.feed = feedType<Cloud, std::vector<double>>();
  project.in_ports = {"cloud", "coefficients"};
  project.input += ", its plane's coefficients";
  project.frames[0].push_back(apex::Message::make<std::vector<double>>(plane.coefficients));
  c.push_back(over(std::move(project), "every field kept: all the points copied, the x, y, z view projected into them"));
  return c;
}

}  // namespace

std::vector<NodeCase> cloudClusterCases(const TypedPtr& scene,
                                        const std::shared_ptr<const Cloud>& cloud);  // cloud_bench_more.cpp
std::vector<NodeCase> cloudOtherCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud);  // cloud_bench_more.cpp
std::vector<NodeCase> cloudFeatureCases(const TypedPtr& scene,
                                        const std::shared_ptr<const Cloud>& cloud);  // cloud_bench_features.cpp

/** The table of the cloud nodes against their PCL calls, on the table scene. */
void cloudNodeTable(bool quick) {
  const TypedPtr scene = pcl::make_shared<Typed>(tableScene());
  std_msgs::Header header;
  header.frame_id = "camera";
  const Shared s{scene, apex_nodes::makeCloud(header, *scene)};
  std::vector<NodeCase> all;
  for (auto* part : {filterCases, segmentationCases, surfaceCases})
    for (auto& c : part(s)) all.push_back(std::move(c));
  for (auto& c : cloudClusterCases(scene, s.cloud)) all.push_back(std::move(c));
  for (auto& c : cloudOtherCases(scene, s.cloud)) all.push_back(std::move(c));
  for (auto& c : cloudFeatureCases(scene, s.cloud)) all.push_back(std::move(c));
  const Budget b = Budget::of(quick);
  std::printf("## Cloud nodes against their PCL call\n\n");
  std::printf("Each cloud node type alone (a source → the node → a sink, one thread group, loaded through\n");
  std::printf("pluginlib), its firing as the runtime clocks it (`NodeStats::last_ns`), against its PCL call on a\n");
  std::printf("typed cloud (pcl::PointCloud<pcl::PointXYZRGB>, as a pcl_conversions user holds it) with the same\n");
  std::printf("parameters, written by hand, steady_clock around each call. The node computes on x, y, z and keeps\n");
  std::printf("every field of the points it sends; the difference is what that and the message cost. Input: a\n");
  std::printf("generated table top, a 2 x 2 m plane of 24000 points and three boxes of 2000 points on it, x, y, z,\n");
  std::printf("rgb; what else a node takes is made of it and said in its row. Measured as the image nodes:\n");
  std::printf("interleaved in %d rounds of N clouds per side (N from the call's time, %d to %d), medians of the\n", b.rounds,
              b.min_frames, b.max_frames);
  std::printf("rounds' medians (min–max), µs. Goal: node ≤ call × 1.05 + 20 µs.\n\n");
  measureTable(all, b);
}

}  // namespace apex_bench
