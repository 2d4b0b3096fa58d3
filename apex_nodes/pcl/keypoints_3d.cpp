// ISSKeypoints and HarrisKeypoints3D: points that stand out in a cloud's shape, e.g. to match two
// views. ISS (intrinsic shape signatures) keeps the input's points whose neighbourhood's spread is
// unequal in all three directions, whole; Harris 3D scores each point's surface normals as Harris
// scores an image's gradients and sends the keypoints with their response as intensity.
#include <pcl/keypoints/harris_3d.h>
#include <pcl/keypoints/iss_3d.h>
#include <pcl/search/kdtree.h>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ISSKeypoints : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::OutputPort<Cloud> kKeypoints{"keypoints", "the input's points that are keypoints, whole"};
  static inline const apex::OutputPort<int> kCount{"count"};
  static inline const apex::ParamDecl<double> kSalientRadius =
      param::number("salient_radius")
          .range(0.0001, 100.0)
          .step(0.001)
          .init(0.06)
          .describe("metres: the neighbourhood each point's spread is measured over");
  static inline const apex::ParamDecl<double> kNonMaxRadius =
      param::number("non_max_radius")
          .range(0.0001, 100.0)
          .step(0.001)
          .init(0.04)
          .describe("metres: only the strongest keypoint within it is kept");
  static inline const apex::ParamDecl<double> kThreshold21 = param::number("threshold21")
                                                                 .range(0.0, 1.0)
                                                                 .step(0.005)
                                                                 .init(0.975)
                                                                 .describe("the most the second spread may be of the first");
  static inline const apex::ParamDecl<double> kThreshold32 = param::number("threshold32")
                                                                 .range(0.0, 1.0)
                                                                 .step(0.005)
                                                                 .init(0.975)
                                                                 .describe("the most the third spread may be of the second");
  static inline const apex::ParamDecl<int> kMinNeighbours =
      param::integer("min_neighbours").range(1, 10000).step(1).init(5).describe("within salient_radius, for a point to count");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Intrinsic shape signature keypoints (PCL's ISSKeypoint3D): points whose neighbourhood spreads unequally")
        .inCategory("cloud features")
        .input(kCloud)
        .output(kKeypoints)
        .output(kCount)
        .param(kSalientRadius)
        .param(kNonMaxRadius)
        .param(kThreshold21)
        .param(kThreshold32)
        .param(kMinNeighbours);
  }
  void process() override {
    const auto in = cloud_.get();
    pcl::ISSKeypoint3D<pcl::PointXYZ, pcl::PointXYZ> iss;
    iss.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
    iss.setSalientRadius(salient_.get());
    iss.setNonMaxRadius(non_max_.get());
    iss.setThreshold21(t21_.get());
    iss.setThreshold32(t32_.get());
    iss.setMinNeighbors(min_neighbours_.get());
    iss.setNumberOfThreads(1);  // the graph's thread groups are the parallelism
    iss.setInputCloud(xyzOf(*in));
    XyzCloud found;
    iss.compute(found);
    const auto& indices = iss.getKeypointsIndices()->indices;
    count_.publish(static_cast<int>(indices.size()));
    keypoints_.publish(cloudResult(*in, selectPoints(*in->points, indices)));
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Cloud> keypoints_{this, kKeypoints};
  apex::Output<int> count_{this, kCount};
  apex::Param<double> salient_{this, kSalientRadius};
  apex::Param<double> non_max_{this, kNonMaxRadius};
  apex::Param<double> t21_{this, kThreshold21};
  apex::Param<double> t32_{this, kThreshold32};
  apex::Param<int> min_neighbours_{this, kMinNeighbours};
};

class HarrisKeypoints3D : public apex::Node {
 public:
  using Harris = pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI>;
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::OutputPort<Cloud> kKeypoints{
      "keypoints", "x, y, z and intensity (the response); refined: where the response peaks, not an input point"};
  static inline const apex::OutputPort<int> kCount{"count"};
  static inline const apex::ChoiceDecl<Harris::ResponseMethod> kMethod =
      param::choice<Harris::ResponseMethod>("method", {{"harris", Harris::HARRIS, "det - k trace² of the normals' covariance"},
                                                       {"noble", Harris::NOBLE, "det / trace"},
                                                       {"lowe", Harris::LOWE, "det / trace²"},
                                                       {"tomasi", Harris::TOMASI, "the smallest eigenvalue"},
                                                       {"curvature", Harris::CURVATURE, "the surface's curvature"}})
          .describe("the response");
  static inline const apex::ParamDecl<double> kRadius =
      param::number("radius").range(0.0001, 100.0).step(0.001).init(0.05).describe("metres: the neighbourhood of normals");
  static inline const apex::ParamDecl<double> kThreshold = param::number("threshold")
                                                               .range(0.0, 1e6)
                                                               .step(0.0001)
                                                               .init(0.0)
                                                               .describe("the least response kept (with non_max_suppression)");
  static inline const apex::ParamDecl<bool> kNonMax =
      param::flag("non_max_suppression")
          .init(true)
          .describe("only local peaks of the response above threshold; off: every point");
  static inline const apex::ParamDecl<bool> kRefine =
      param::flag("refine").init(true).describe("moves each keypoint to where the response peaks");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Harris keypoints in 3D (PCL's HarrisKeypoint3D): where the surface's normals change in every direction")
        .inCategory("cloud features")
        .input(kCloud)
        .output(kKeypoints)
        .output(kCount)
        .param(kMethod)
        .param(kRadius)
        .param(kThreshold)
        .param(kNonMax)
        .param(kRefine);
  }
  void process() override {
    const auto in = cloud_.get();
    Harris harris(method_.get(), static_cast<float>(radius_.get()), static_cast<float>(threshold_.get()));
    harris.setNonMaxSupression(non_max_.get());
    harris.setRefine(refine_.get());
    harris.setNumberOfThreads(1);
    harris.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
    harris.setInputCloud(xyzOf(*in));
    pcl::PointCloud<pcl::PointXYZI> found;
    harris.compute(found);
    count_.publish(static_cast<int>(found.size()));
    keypoints_.publish(makeCloud(in->header, found));
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Cloud> keypoints_{this, kKeypoints};
  apex::Output<int> count_{this, kCount};
  apex::Choice<Harris::ResponseMethod> method_{this, kMethod};
  apex::Param<double> radius_{this, kRadius};
  apex::Param<double> threshold_{this, kThreshold};
  apex::Param<bool> non_max_{this, kNonMax};
  apex::Param<bool> refine_{this, kRefine};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ISSKeypoints, "apex_nodes/ISSKeypoints");
APEX_REGISTER_NODE(apex_nodes::HarrisKeypoints3D, "apex_nodes/HarrisKeypoints3D");
