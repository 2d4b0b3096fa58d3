// RandomSample and UniformSampling: fewer points, each one of the input's, whole (every field).
// RandomSample keeps `sample` points at random (PCL's, seeded: the same cloud gives the same
// points); UniformSampling keeps per cube of `radius` the point nearest its centre.
#include <pcl/filters/random_sample.h>
#include <pcl/filters/uniform_sampling.h>

#include <algorithm>

#include "apex_nodes/cloud_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class RandomSample : public apex::Node, public CloudFilterPorts {
 public:
  static inline const apex::ParamDecl<int> kSample =
      param::integer("sample").range(1, 100000000).step(1).init(1000).describe("points kept (all if the cloud has fewer)");
  static inline const apex::ParamDecl<int> kSeed =
      param::integer("seed").range(0, 1000000000).step(1).init(0).describe("the same seed keeps the same points");
  static apex::Manifest manifest() {
    return filterManifest("Keeps a number of points chosen at random, in their order").param(kSample).param(kSeed);
  }
  void process() override {
    const auto in = in_.get();
    pcl::RandomSample<pcl::PCLPointCloud2> filter;  // on the message itself: the choice needs no coordinate
    filter.setInputCloud(in->points);
    filter.setSample(static_cast<unsigned>(sample_.get()));
    filter.setSeed(static_cast<unsigned>(seed_.get()));
    filter.filter(kept_);
    out_.publish(cloudResult(*in, selectPoints(*in->points, kept_)));
  }

 private:
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kCloudOut};
  apex::Param<int> sample_{this, kSample};
  apex::Param<int> seed_{this, kSeed};
  pcl::Indices kept_;
};

namespace {

/** PCL's UniformSampling, saying which points it kept (one per cube, in the input's order): its
 *  output holds copies of them, in the order of its hash map. */
class KeptUniformSampling : public pcl::UniformSampling<pcl::PointXYZ> {
 public:
  void kept(pcl::Indices& out) const {
    out.clear();
    for (const auto& [key, leaf] : leaves_) out.push_back(leaf.idx);
    std::sort(out.begin(), out.end());
  }
};

}  // namespace

class UniformSampling : public apex::Node, public CloudFilterPorts {
 public:
  static inline const apex::ParamDecl<double> kRadius =
      param::number("radius")
          .range(0.0001, 100.0)
          .step(0.001)
          .init(0.05)
          .describe("metres: the side of the cubes, one point kept in each (the one nearest its centre)");
  static apex::Manifest manifest() {
    return filterManifest("Keeps one point per cube of a grid, the one nearest the cube's centre, in the input's order")
        .param(kRadius);
  }
  void process() override {
    const auto in = in_.get();
    KeptUniformSampling filter;
    filter.setInputCloud(xyzOf(*in, xyz_.next()));
    filter.setRadiusSearch(radius_.get());
    filter.filter(copies_);
    filter.kept(kept_);
    out_.publish(cloudResult(*in, selectPoints(*in->points, kept_)));
  }

 private:
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kCloudOut};
  apex::Param<double> radius_{this, kRadius};
  Reused<XyzCloud> xyz_;  // kept between frames: the x, y, z view, PCL's copies and the indices
  XyzCloud copies_;
  pcl::Indices kept_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::RandomSample, "apex_nodes/RandomSample");
APEX_REGISTER_NODE(apex_nodes::UniformSampling, "apex_nodes/UniformSampling");
