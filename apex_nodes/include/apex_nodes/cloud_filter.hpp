// A node shape: one cloud in, one cloud out through a PCL filter (pcl::VoxelGrid<PointT>, ...).
// The shape checks the cloud (points, some finite), hands the filter the input without a copy,
// lets the node set the filter's parameters, and publishes the result with the input's header:
//
//   class VoxelGrid : public CloudFilter<pcl::VoxelGrid<PointT>> {
//    public:
//     static inline const apex::ParamDecl<double> kLeaf = apex::param::number("leaf_size").range(0.001, 10.0).init(0.05);
//     static apex::Manifest manifest() { return filterManifest("Downsamples a cloud").param(kLeaf); }
//    private:
//     void configure(pcl::VoxelGrid<PointT>& f) override { f.setLeafSize(leaf_.get(), leaf_.get(), leaf_.get()); }
//     apex::Param<double> leaf_{this, kLeaf};
//   };
#pragma once

#include <string>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_check.hpp"

namespace apex_nodes {

/** The ports of every cloud filter (not in the template: a class template's static members may
 *  be initialised after the registration lines that read them). */
struct CloudFilterPorts {
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud", "the cloud"};
  static inline const apex::OutputPort<Cloud> kCloudOut{"cloud", "the points kept"};
  /** @brief A cloud filter's manifest: its description and the two ports; add the parameters. */
  static apex::Manifest filterManifest(std::string description) {
    return apex::Manifest(std::move(description)).input(kCloudIn).output(kCloudOut);
  }
};

template <class Filter>
class CloudFilter : public apex::Node, public CloudFilterPorts {
 protected:
  /** @brief Sets the filter's parameters for this firing (its input is set already). */
  virtual void configure(Filter& filter) = 0;

 private:
  void process() final {
    out_.publish(filterCloud<Filter>(*in_.get(), [this](Filter& filter) { configure(filter); }));
  }
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kCloudOut};
};

}  // namespace apex_nodes
