// apex_bench_clouds' node table, continued (cloud_bench_nodes.cpp has the table and the scene):
// clusters, registration, depth and merging, each node against its PCL call on typed clouds.
#include <pcl/common/centroid.h>
#include <pcl/common/common.h>
#include <pcl/common/transforms.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>
#include <pcl/segmentation/extract_clusters.h>

#include <Eigen/Eigenvalues>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/cluster_features.hpp"
#include "node_vs_call.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Cloud;
using apex_nodes::Clusters;
using Point = pcl::PointXYZRGB;
using Typed = pcl::PointCloud<Point>;
using TypedPtr = Typed::ConstPtr;

/** A node fed the same messages each time, against `call`. */
NodeCase fixed(std::string type, std::string input, std::string feed, std::vector<std::string> ports,
               std::vector<apex::Message> messages, Params params, std::string out_port, std::string sink, std::string call_text,
               std::function<void()> call, std::string label = "") {
  return fixedCase(label.empty() ? type : label, "apex_nodes/" + type, std::move(input), std::move(feed), std::move(ports),
                   std::move(messages), std::move(params), std::move(out_port), std::move(sink), std::move(call_text),
                   std::move(call));
}

/** The scene's boxes: its points above the plane (z < 1.45), clustered at 5 cm, typed. */
std::vector<Typed> boxesOf(const TypedPtr& scene) {
  auto above = pcl::make_shared<Typed>();
  for (const Point& p : *scene)
    if (p.z < 1.45f) above->push_back(p);
  auto tree = pcl::make_shared<pcl::search::KdTree<Point>>();
  tree->setInputCloud(above);
  std::vector<pcl::PointIndices> found;
  pcl::EuclideanClusterExtraction<Point> ec;
  ec.setClusterTolerance(0.05), ec.setMinClusterSize(50), ec.setSearchMethod(tree), ec.setInputCloud(above);
  ec.extract(found);
  std::vector<Typed> out(found.size());
  for (std::size_t i = 0; i < found.size(); ++i) pcl::copyPointCloud(*above, found[i], out[i]);
  return out;
}

std::vector<NodeCase> clusterCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud) {
  std::vector<NodeCase> c;
  const auto boxes = std::make_shared<const std::vector<Typed>>(boxesOf(scene));
  auto clusters = std::make_shared<Clusters>();
  clusters->header = cloud->header;
  for (const Typed& b : *boxes) clusters->clusters.push_back(apex_nodes::toBlob(b));
  const std::string words = std::to_string(boxes->size()) + " clusters, the scene's boxes";
  c.push_back(fixed("ClusterFeatures", words, feedType<Clusters>(), {"clusters"}, {apex::Message::share<Clusters>(clusters)}, {},
                    "features", sinkType<apex_nodes::ClusterFeatures>(),
                    "per cluster: compute3DCentroid, covariance, its eigenvectors, getMinMax3D, the oriented extent", [boxes] {
                      for (const Typed& b : *boxes) {
                        Eigen::Vector4f centroid;
                        Eigen::Matrix3f covariance;
                        pcl::compute3DCentroid(b, centroid);
                        pcl::computeCovarianceMatrixNormalized(b, centroid, covariance);
                        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> pca(covariance);
                        Point lo, hi;
                        pcl::getMinMax3D(b, lo, hi);
                        Eigen::Vector3f low = Eigen::Vector3f::Constant(1e9f), high = -low;
                        for (const Point& p : b) {
                          const Eigen::Vector3f local =
                              pca.eigenvectors().transpose() * (p.getVector3fMap() - centroid.head<3>());
                          low = low.cwiseMin(local), high = high.cwiseMax(local);
                        }
                      }
                    }));
  c.push_back(fixed("ClustersToCloud", words, feedType<Clusters>(), {"clusters"}, {apex::Message::share<Clusters>(clusters)}, {},
                    "cloud", sinkType<Cloud>(), "each cluster's points into one PointXYZRGBL cloud, labelled",
                    [boxes, out = pcl::PointCloud<pcl::PointXYZRGBL>()]() mutable {
                      out.clear();
                      for (std::size_t i = 0; i < boxes->size(); ++i)
                        for (const Point& p : (*boxes)[i]) {
                          pcl::PointXYZRGBL q;
                          q.x = p.x, q.y = p.y, q.z = p.z, q.rgba = p.rgba, q.label = std::uint32_t(i);
                          out.push_back(q);
                        }
                    }));
  return c;
}

std::vector<NodeCase> registrationCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud) {
  std::vector<NodeCase> c;
  auto source = pcl::make_shared<Typed>(), target = pcl::make_shared<Typed>();
  pcl::VoxelGrid<Point> grid;
  grid.setInputCloud(scene);
  grid.setLeafSize(0.05f, 0.05f, 0.05f);
  grid.filter(*source);
  const Eigen::Affine3f moved(Eigen::Translation3f(0.05f, 0.02f, 0.f) * Eigen::AngleAxisf(0.05f, Eigen::Vector3f::UnitZ()));
  pcl::transformPointCloud(*source, *target, moved);
  const std::vector<apex::Message> pair{apex::Message::share<Cloud>(apex_nodes::makeCloud(cloud->header, *source)),
                                        apex::Message::share<Cloud>(apex_nodes::makeCloud(cloud->header, *target))};
  const std::string words = "the scene at 5 cm (" + std::to_string(source->size()) + " points), moved 5 cm, 0.05 rad";
  c.push_back(fixed("ICP", words, feedType<Cloud, Cloud>(), {"source", "target"}, pair,
                    {{"max_iterations", "50"},
                     {"max_correspondence_distance", "0.5"},
                     {"transformation_epsilon", "1e-08"},
                     {"euclidean_fitness_epsilon", "0"}},
                    "aligned", sinkType<Cloud>(), "IterativeClosestPoint 50, 0.5 m, 1e-8: align",
                    [source, target, out = Typed()]() mutable {
                      pcl::IterativeClosestPoint<Point, Point> icp;
                      icp.setMaximumIterations(50);
                      icp.setMaxCorrespondenceDistance(0.5);
                      icp.setTransformationEpsilon(1e-8);
                      icp.setEuclideanFitnessEpsilon(0);
                      icp.setInputSource(source);
                      icp.setInputTarget(target);
                      icp.align(out);
                    }));
  c.push_back(
      over(fixed("NDT", words, feedType<Cloud, Cloud>(), {"source", "target"}, pair,
                 {{"resolution", "1.0"}, {"step_size", "0.1"}, {"transformation_epsilon", "0.01"}, {"max_iterations", "35"}},
                 "aligned", sinkType<Cloud>(), "NormalDistributionsTransform 1 m, 0.1, 0.01, 35: align",
                 [source, target, out = Typed()]() mutable {
                   pcl::NormalDistributionsTransform<Point, Point> ndt;
                   ndt.setResolution(1.0f);
                   ndt.setStepSize(0.1);
                   ndt.setTransformationEpsilon(0.01);
                   ndt.setMaximumIterations(35);
                   ndt.setInputSource(source);
                   ndt.setInputTarget(target);
                   ndt.align(out);
                 }),
           "probably the fitness score it sends (a nearest-neighbour search of every point), which the call "
           "does not compute; not timed apart"));
  return c;
}

/** A 640x480 depth image (16UC1, mm) of a tilted plane about 1.5 m away, and its camera. */
std::vector<apex::Message> depthFrame() {
  cv::Mat depth(480, 640, CV_16UC1);
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) depth.at<std::uint16_t>(v, u) = std::uint16_t(1300 + v / 2 + (u % 97 == 0 ? 0 : u / 8));
  auto image = std::make_shared<apex_nodes::Image>();
  image->header.frame_id = "camera";
  image->encoding = "16UC1";
  image->mat = depth;
  auto info = std::make_shared<sensor_msgs::CameraInfo>();
  info->header.frame_id = "camera";
  info->width = 640, info->height = 480;
  info->distortion_model = "plumb_bob";
  info->D.assign(5, 0.0);
  info->K = {525, 0, 319.5, 0, 525, 239.5, 0, 0, 1};
  info->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info->P = {525, 0, 319.5, 0, 0, 525, 239.5, 0, 0, 0, 1, 0};
  return {apex::Message::share<apex_nodes::Image>(image), apex::Message::share<sensor_msgs::CameraInfo>(info)};
}

std::vector<NodeCase> depthCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud) {
  std::vector<NodeCase> c;
  const auto frame = depthFrame();
  const cv::Mat depth = frame[0].as<apex_nodes::Image>()->mat;
  c.push_back(fixed("DepthToCloud", "640x480 16UC1 (mm), its camera", feedType<apex_nodes::Image, sensor_msgs::CameraInfo>(),
                    {"depth", "camera_info"}, frame, {}, "cloud", sinkType<Cloud>(),
                    "depth_image_proc's loop into an organised PointXYZ cloud",
                    [depth, out = pcl::PointCloud<pcl::PointXYZ>(640, 480)]() mutable {
                      const float k = 0.001f / 525;
                      for (int v = 0; v < depth.rows; ++v) {
                        const std::uint16_t* row = depth.ptr<std::uint16_t>(v);
                        for (int u = 0; u < depth.cols; ++u) {
                          pcl::PointXYZ& p = out.at(u, v);
                          const float d = row[u];
                          p.x = (u - 319.5f) * d * k, p.y = (v - 239.5f) * d * k, p.z = d * 0.001f;
                        }
                      }
                    }));
  for (const char* t : {"DepthColorToCloud", "CloudToDepth", "DisparityToCloud"})
    c.push_back(notMeasured(t, "", "—",
                            "no library call: the conversion is the per-pixel loop the node is (depth_image_proc's, "
                            "stereo_image_proc's); DepthToCloud's row holds that family against the loop written by hand"));
  c.push_back(notMeasured("LaserScanToCloud", "", "laser_geometry projectLaser",
                          "its bare counterpart is laser_geometry's projectLaser, which apex_bench_clouds does not "
                          "link (package laser_geometry)"));
  const auto& scene_cloud = cloud;
  c.push_back(fixed("MergeClouds", "the table scene twice, one frame", feedType<Cloud, Cloud>(), {"cloud_0", "cloud_1"},
                    {apex::Message::share<Cloud>(scene_cloud), apex::Message::share<Cloud>(scene_cloud)}, {{"inputs", "2"}},
                    "cloud", sinkType<Cloud>(), "concatenate two typed clouds", [scene, out = Typed()]() mutable {
                      out = *scene;
                      out += *scene;
                    }));
  return c;
}

}  // namespace

std::vector<NodeCase> cloudClusterCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud) {
  std::vector<NodeCase> c = clusterCases(scene, cloud);
  for (auto& k : registrationCases(scene, cloud)) c.push_back(std::move(k));
  return c;
}

std::vector<NodeCase> cloudOtherCases(const TypedPtr& scene, const std::shared_ptr<const Cloud>& cloud) {
  return depthCases(scene, cloud);
}

}  // namespace apex_bench
