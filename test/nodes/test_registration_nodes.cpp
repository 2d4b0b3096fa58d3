// ICP and NDT against the same PCL call made directly (same transform, fitness and convergence),
// on a coloured corner and the same corner moved by a known motion, which they must find; the
// aligned cloud keeps the colours. MergeClouds' merging (mergeClouds, mergePoints) without ROS, on
// known transforms: the same as transforming with PCL and concatenating; fields common to all
// when they differ.
#include <gmock/gmock.h>
#include <pcl/common/io.h>
#include <pcl/common/transforms.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>

#include <random>

#include "apex_nodes/cloud_transform.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using ::testing::HasSubstr;
using Rgb = pcl::PointCloud<pcl::PointXYZRGB>;
using Xyz = pcl::PointCloud<pcl::PointXYZ>;
using Params = std::vector<std::pair<std::string, std::string>>;

namespace {

std_msgs::Header header(const std::string& frame, ros::Time stamp) {
  std_msgs::Header h;
  h.frame_id = frame;
  h.stamp = stamp;
  return h;
}
const ros::Time kSourceStamp(5, 123456789), kTargetStamp(4, 0);

/** A corner: a floor and two walls (3000 random points), each point coloured differently. */
Rgb corner() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  Rgb points;
  for (int i = 0; i < 3000; ++i) {
    const int plane = i % 3;
    const float a = 2.f * u(rng);
    const float b = (plane == 0 ? 2.f : 1.5f) * u(rng);
    pcl::PointXYZRGB p(std::uint8_t(i % 256), std::uint8_t(80 * plane), std::uint8_t((i / 256) % 256));
    if (plane == 0) p.x = a, p.y = b, p.z = 0.f;  // floor
    else if (plane == 1) p.x = 0.f, p.y = a, p.z = b;  // wall x = 0
    else p.x = a, p.y = 0.f, p.z = b;  // wall y = 0
    points.push_back(p);
  }
  return points;
}

/** The motion from the source's frame to the target's: the registrations must find it. */
Eigen::Affine3f truth() {
  Eigen::Affine3f m = Eigen::Affine3f::Identity();
  m.translate(Eigen::Vector3f(0.04f, -0.03f, 0.02f));
  m.rotate(Eigen::AngleAxisf(0.02f, Eigen::Vector3f(0.2f, 0.3f, 1.f).normalized()));
  return m;
}

std::shared_ptr<const Cloud> source() { return apex_nodes::makeCloud(header("lidar", kSourceStamp), corner()); }
std::shared_ptr<const Cloud> target() {
  Rgb moved;
  pcl::transformPointCloud(corner(), moved, truth());
  return apex_nodes::makeCloud(header("map", kTargetStamp), moved);
}
std::shared_ptr<Xyz> xyz(const std::shared_ptr<const Cloud>& c) {
  return std::make_shared<Xyz>(apex_nodes::typedPoints<pcl::PointXYZ>(*c));
}

/** What the PCL call gives. */
struct Direct {
  Eigen::Matrix4f transform;
  double fitness;
  bool converged;
};
template <class Registration>
Direct direct(Registration& reg, const Eigen::Matrix4f& guess = Eigen::Matrix4f::Identity()) {
  reg.setInputSource(xyz(source()));
  reg.setInputTarget(xyz(target()));
  Xyz out;
  reg.align(out, guess);
  return {reg.getFinalTransformation(), reg.getFitnessScore(), reg.hasConverged()};
}

/** Each output of a registration node, on source() and target() (and `initial` if given). */
struct Outputs {
  Message aligned, transform, fitness, converged;
};
Outputs runNode(const std::string& type, const Params& params,
                std::shared_ptr<const geometry_msgs::TransformStamped> initial = nullptr) {
  Outputs out;
  const std::vector<std::pair<std::string, Message*>> ports = {
      {"aligned", &out.aligned}, {"transform", &out.transform}, {"fitness", &out.fitness}, {"converged", &out.converged}};
  for (const auto& [port, message] : ports) {
    std::vector<std::string> inputs = {"source", "target"};
    std::vector<Message> messages = {Message::share<Cloud>(source()), Message::share<Cloud>(target())};
    if (initial) {
      inputs.push_back("initial");
      messages.push_back(Message::share<geometry_msgs::TransformStamped>(initial));
    }
    NodeHarness h(type, inputs, port, params);
    *message = h.run(messages);
    EXPECT_EQ(h.error(), "");
  }
  return out;
}

Eigen::Matrix4d matrixOf(const geometry_msgs::Transform& t) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z).toRotationMatrix();
  m(0, 3) = t.translation.x, m(1, 3) = t.translation.y, m(2, 3) = t.translation.z;
  return m;
}

/** The node's outputs are PCL's: the transform to 1e-6, the same fitness (to 1e-6 of it) and convergence, and the
 *  source moved by it with its colours; the transform's and the cloud's frames and stamps. */
void expectSameAsPcl(const Outputs& got, const Direct& want) {
  const auto t = got.transform.as<geometry_msgs::TransformStamped>();
  ASSERT_TRUE(t) << got.transform.typeName();
  EXPECT_EQ(t->header.frame_id, "map");
  EXPECT_EQ(t->child_frame_id, "lidar");
  EXPECT_EQ(t->header.stamp, kSourceStamp);
  const Eigen::Matrix4d m = matrixOf(t->transform);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(m(i, j), want.transform(i, j), 1e-6) << i << ", " << j;
  ASSERT_TRUE(got.fitness.as<double>());
  EXPECT_NEAR(*got.fitness.as<double>(), want.fitness, 1e-10 + 1e-6 * want.fitness);
  ASSERT_TRUE(got.converged.as<bool>());
  EXPECT_EQ(*got.converged.as<bool>(), want.converged);

  const auto aligned = got.aligned.as<Cloud>();
  ASSERT_TRUE(aligned) << got.aligned.typeName();
  EXPECT_EQ(aligned->header.frame_id, "map");
  EXPECT_EQ(aligned->header.stamp, kSourceStamp);
  EXPECT_EQ(apex_nodes::fieldNames(*aligned->points), "x, y, z, rgb");
  Rgb moved;
  pcl::transformPointCloud(corner(), moved, want.transform);
  const Rgb points = apex_nodes::typedPoints<pcl::PointXYZRGB>(*aligned);
  ASSERT_EQ(points.size(), moved.size());
  for (std::size_t i = 0; i < moved.size(); ++i) {
    ASSERT_NEAR(points[i].x, moved[i].x, 1e-5) << i;
    ASSERT_NEAR(points[i].y, moved[i].y, 1e-5) << i;
    ASSERT_NEAR(points[i].z, moved[i].z, 1e-5) << i;
    ASSERT_EQ(points[i].rgba, moved[i].rgba) << i;
  }
}

/** How far a transform is from truth(): translation (m) and rotation (rad). */
std::pair<double, double> errorOf(const Eigen::Matrix4f& m) {
  const Eigen::Matrix4d d = m.cast<double>(), t = truth().matrix().cast<double>();
  const Eigen::Matrix3d r = d.topLeftCorner<3, 3>() * t.topLeftCorner<3, 3>().transpose();
  return {(d.topRightCorner<3, 1>() - t.topRightCorner<3, 1>()).norm(), Eigen::AngleAxisd(r).angle()};
}

const Params kIcpParams = {{"max_iterations", "100"},
                           {"max_correspondence_distance", "0.3"},
                           {"transformation_epsilon", "1e-12"},
                           {"euclidean_fitness_epsilon", "0"}};
using Icp = pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>;
/** kIcpParams, for the PCL call. */
void configure(Icp& icp) {
  icp.setMaximumIterations(100);
  icp.setMaxCorrespondenceDistance(0.3);
  icp.setTransformationEpsilon(1e-12);
  icp.setEuclideanFitnessEpsilon(0);
}

TEST(RegistrationNodes, IcpMatchesPclAndFindsTheMotion) {
  Icp reg;
  configure(reg);
  const Direct want = direct(reg);
  EXPECT_TRUE(want.converged);
  const auto [translation, rotation] = errorOf(want.transform);
  EXPECT_LT(translation, 1e-3);
  EXPECT_LT(rotation, 1e-3);
  expectSameAsPcl(runNode("apex_nodes/ICP", kIcpParams), want);
}

TEST(RegistrationNodes, IcpStartsFromTheInitialGuess) {
  auto initial = std::make_shared<geometry_msgs::TransformStamped>();
  initial->header.frame_id = "map";
  initial->child_frame_id = "lidar";
  initial->transform.translation.x = 0.03, initial->transform.translation.y = -0.02;
  initial->transform.rotation.w = 1.0;
  Icp reg;
  configure(reg);
  const Direct want = direct(reg, apex_nodes::toEigen(initial->transform).matrix());
  expectSameAsPcl(runNode("apex_nodes/ICP", kIcpParams, initial), want);

  initial->child_frame_id = "camera";
  NodeHarness h("apex_nodes/ICP", {"source", "target", "initial"}, "transform", kIcpParams);
  EXPECT_TRUE(h.run({Message::share<Cloud>(source()), Message::share<Cloud>(target()),
                     Message::share<geometry_msgs::TransformStamped>(initial)})
                  .isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the initial transform maps frame 'camera', the source is in 'lidar'"));
}

TEST(RegistrationNodes, NdtMatchesPclAndFindsTheMotion) {
  pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> ndt;
  ndt.setResolution(0.5f);
  ndt.setStepSize(0.1);
  ndt.setTransformationEpsilon(1e-6);
  ndt.setMaximumIterations(50);
  const Direct want = direct(ndt);
  EXPECT_TRUE(want.converged);
  const auto [translation, rotation] = errorOf(want.transform);  // from 0.054 m and 0.02 rad
  EXPECT_LT(translation, 0.02);
  EXPECT_LT(rotation, 0.01);
  expectSameAsPcl(
      runNode("apex_nodes/NDT",
              {{"resolution", "0.5"}, {"step_size", "0.1"}, {"transformation_epsilon", "1e-6"}, {"max_iterations", "50"}}),
      want);
}

// MergeClouds

/** n points with colours and normals, frame `frame`. */
template <class PointT>
pcl::PointCloud<PointT> some(int n, float z) {
  pcl::PointCloud<PointT> points;
  for (int i = 0; i < n; ++i) {
    PointT p;
    p.x = 0.1f * i, p.y = 0.05f * (i % 7), p.z = z;
    if constexpr (pcl::traits::has_color_v<PointT>) p.r = std::uint8_t(10 * i), p.g = 7, p.b = std::uint8_t(i);
    if constexpr (pcl::traits::has_normal_v<PointT>) p.normal_x = 0, p.normal_y = 0, p.normal_z = 1;
    if constexpr (pcl::traits::has_intensity_v<PointT>) p.intensity = float(i);
    points.push_back(p);
  }
  return points;
}

Eigen::Affine3f lidarToBase() {
  Eigen::Affine3f m = Eigen::Affine3f::Identity();
  m.translate(Eigen::Vector3f(1.f, 0.f, 0.5f));
  m.rotate(Eigen::AngleAxisf(static_cast<float>(M_PI / 2), Eigen::Vector3f::UnitZ()));
  return m;
}
Eigen::Affine3f cameraToBase() {
  Eigen::Affine3f m = Eigen::Affine3f::Identity();
  m.translate(Eigen::Vector3f(0.f, 2.f, 1.f));
  m.rotate(Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitX()));
  return m;
}
/** tf2 with two frames under base_link; anything else is unknown. */
Eigen::Affine3f lookup(const std::string& target, const std::string& source, const ros::Time&) {
  if (target == "base_link" && source == "lidar") return lidarToBase();
  if (target == "base_link" && source == "camera") return cameraToBase();
  throw std::runtime_error("\"" + source + "\" passed to lookupTransform argument source_frame does not exist");
}

TEST(MergeClouds, SameFieldsAsPclTransformAndConcatenate) {
  const Rgb a = some<pcl::PointXYZRGB>(20, 1.f), b = some<pcl::PointXYZRGB>(30, 2.f);
  const auto merged = apex_nodes::mergeClouds(
      {apex_nodes::makeCloud(header("lidar", ros::Time(5)), a), apex_nodes::makeCloud(header("camera", ros::Time(6)), b),
       apex_nodes::makeCloud(header("base_link", ros::Time(4)), a)},
      "base_link", lookup);
  EXPECT_EQ(merged->header.frame_id, "base_link");
  EXPECT_EQ(merged->header.stamp, ros::Time(6));  // the newest
  EXPECT_EQ(apex_nodes::fieldNames(*merged->points), "x, y, z, rgb");

  Rgb want, moved;
  pcl::transformPointCloud(a, want, lidarToBase());
  pcl::transformPointCloud(b, moved, cameraToBase());
  want += moved;
  want += a;  // already in base_link
  const Rgb got = apex_nodes::typedPoints<pcl::PointXYZRGB>(*merged);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_NEAR(got[i].x, want[i].x, 1e-5) << i;
    ASSERT_NEAR(got[i].y, want[i].y, 1e-5) << i;
    ASSERT_NEAR(got[i].z, want[i].z, 1e-5) << i;
    ASSERT_EQ(got[i].rgba, want[i].rgba) << i;
  }

  // PCL's concatenate of the moved clouds: the same points
  pcl::PCLPointCloud2 concatenated;
  ASSERT_TRUE(pcl::concatenate(*apex_nodes::transformPoints(*apex_nodes::toBlob(a), lidarToBase()),
                               *apex_nodes::transformPoints(*apex_nodes::toBlob(b), cameraToBase()), concatenated));
  const auto two = apex_nodes::mergePoints({{apex_nodes::toBlob(a), lidarToBase()}, {apex_nodes::toBlob(b), cameraToBase()}});
  EXPECT_EQ(two->width, concatenated.width);
  EXPECT_EQ(two->height, concatenated.height);
  EXPECT_EQ(apex_nodes::fieldNames(*two), apex_nodes::fieldNames(concatenated));
  Rgb pcl_points, our_points;
  pcl::fromPCLPointCloud2(concatenated, pcl_points);
  pcl::fromPCLPointCloud2(*two, our_points);
  for (std::size_t i = 0; i < pcl_points.size(); ++i) {
    ASSERT_TRUE(our_points[i].getVector3fMap() == pcl_points[i].getVector3fMap()) << i;
    ASSERT_EQ(our_points[i].rgba, pcl_points[i].rgba) << i;
  }
}

TEST(MergeClouds, DifferentFieldsKeepThoseCommonToAll) {
  const auto rgb = apex_nodes::toBlob(some<pcl::PointXYZRGB>(5, 1.f));
  const auto normals = apex_nodes::toBlob(some<pcl::PointXYZRGBNormal>(6, 2.f));
  const auto intensity = apex_nodes::toBlob(some<pcl::PointXYZI>(7, 3.f));
  const Eigen::Affine3f turn = cameraToBase();

  const auto colours = apex_nodes::mergePoints({{rgb, Eigen::Affine3f::Identity()}, {normals, turn}});
  EXPECT_EQ(apex_nodes::fieldNames(*colours), "x, y, z, rgb");
  EXPECT_EQ(colours->width, 11u);
  const auto got = apex_nodes::typedPoints<pcl::PointXYZRGB>(Cloud{{}, colours});
  const auto b = some<pcl::PointXYZRGBNormal>(6, 2.f);
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Eigen::Vector3f want = turn * b[i].getVector3fMap();
    ASSERT_TRUE(got[5 + i].getVector3fMap().isApprox(want, 1e-6f)) << i;
    ASSERT_EQ(got[5 + i].rgba, b[i].rgba) << i;
  }

  const auto plain = apex_nodes::mergePoints({{rgb, turn}, {intensity, turn}, {normals, turn}});
  EXPECT_EQ(apex_nodes::fieldNames(*plain), "x, y, z");
  EXPECT_EQ(plain->point_step, 12u);
  EXPECT_EQ(plain->width, 18u);

  // the same fields everywhere: normals are turned too
  const auto turned = apex_nodes::mergePoints({{normals, turn}, {normals, Eigen::Affine3f::Identity()}});
  EXPECT_EQ(apex_nodes::fieldNames(*turned), apex_nodes::fieldNames(*normals));
  const auto n = apex_nodes::typedPoints<pcl::PointXYZRGBNormal>(Cloud{{}, turned});
  ASSERT_EQ(n.size(), 12u);
  EXPECT_TRUE(n[0].getNormalVector3fMap().isApprox(turn.linear() * Eigen::Vector3f::UnitZ(), 1e-6f));
  EXPECT_TRUE(n[6].getNormalVector3fMap() == Eigen::Vector3f::UnitZ());
  EXPECT_EQ(n[0].rgba, b[0].rgba);
}

TEST(MergeClouds, FramesAndEmptyClouds) {
  const auto a = apex_nodes::makeCloud(header("lidar", ros::Time(5)), some<pcl::PointXYZ>(4, 1.f));
  const auto camera = apex_nodes::makeCloud(header("camera", ros::Time(5)), some<pcl::PointXYZ>(4, 1.f));
  const auto empty = apex_nodes::makeCloud(header("lidar", ros::Time(9)), Xyz());
  // no frame: the inputs' own, which must be one
  const auto same = apex_nodes::mergeClouds({a, a, empty}, "", lookup);
  EXPECT_EQ(same->header.frame_id, "lidar");
  EXPECT_EQ(same->header.stamp, ros::Time(9));
  EXPECT_EQ(apex_nodes::pointCount(*same), 8u);
  EXPECT_THAT(
      [&] {
        apex_nodes::mergeClouds({a, camera}, "", lookup);
      },
      testing::ThrowsMessage<std::invalid_argument>(
          HasSubstr("cloud_1 is in frame 'camera', cloud_0 in 'lidar': set `frame` to merge clouds of different frames")));
  EXPECT_THAT(
      [&] {
        apex_nodes::mergeClouds({empty, empty}, "", lookup);
      },
      testing::ThrowsMessage<std::invalid_argument>(HasSubstr("all 2 clouds are empty")));
  // a frame tf2 does not know: both frames and the stamp
  const auto radar = apex_nodes::makeCloud(header("radar", ros::Time(7, 250000000)), some<pcl::PointXYZ>(4, 1.f));
  EXPECT_THAT(
      [&] {
        apex_nodes::mergeClouds({a, radar}, "base_link", lookup);
      },
      testing::ThrowsMessage<std::runtime_error>(
          HasSubstr("no transform radar -> base_link at 7.250000 for cloud_1: \"radar\" passed to lookupTransform")));
}

TEST(MergeClouds, TheNodeHasAnInputPerCloud) {
  NodeHarness h("apex_nodes/MergeClouds", {"cloud_0", "cloud_1", "cloud_2"}, "cloud", {{"inputs", "3"}});
  const auto a = apex_nodes::makeCloud(header("lidar", ros::Time(5)), some<pcl::PointXYZRGB>(4, 1.f));
  const Message got = h.run({Message::share<Cloud>(a), Message::share<Cloud>(a), Message::share<Cloud>(a)});
  ASSERT_TRUE(got.as<Cloud>()) << h.error();
  EXPECT_EQ(apex_nodes::pointCount(*got.as<Cloud>()), 12u);
  EXPECT_EQ(apex_nodes::fieldNames(*got.as<Cloud>()->points), "x, y, z, rgb");
  // tf2 needs ROS (test/ros/test_ros_tf.cpp has it): here a lookup fails, naming both frames
  h.set("frame", "base_link");
  EXPECT_TRUE(h.run({Message::share<Cloud>(a), Message::share<Cloud>(a), Message::share<Cloud>(a)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("no transform lidar -> base_link at 5.000000 for cloud_0"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
