// A node shape: one cloud in, the points a PCL filter keeps out (pcl::PassThrough<pcl::PointXYZ>,
// any pcl::FilterIndices). The shape checks the cloud (x, y, z, some finite), gives the filter its
// x, y, z, lets the node set the filter's parameters, and publishes the kept points whole, with
// every field (colour, intensity, ring...) and the input's header:
//
//   class PassThrough : public CloudFilter<pcl::PassThrough<pcl::PointXYZ>> {
//    public:
//     static inline const apex::ParamDecl<double> kMax = apex::param::number("max").range(0, 100).init(3);
//     static apex::Manifest manifest() { return filterManifest("Keeps the near points").param(kMax); }
//    private:
//     void configure(pcl::PassThrough<pcl::PointXYZ>& f) override { f.setFilterFieldName("z"); f.setFilterLimits(0, max_.get());
//     } apex::Param<double> max_{this, kMax};
//   };
#pragma once

#include <string>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"

namespace apex_nodes {

/** The ports of every cloud filter (not in the template: a class template's static members may
 *  be initialised after the registration lines that read them). */
struct CloudFilterPorts {
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud", "the cloud"};
  static inline const apex::OutputPort<Cloud> kCloudOut{"cloud", "the points kept"};
  /** @brief A cloud filter's manifest: its description and the two ports, in the category "clouds";
   *  add the parameters. */
  static apex::Manifest filterManifest(std::string description) {
    return apex::Manifest(std::move(description)).inCategory("clouds").input(kCloudIn).output(kCloudOut);
  }
};

template <class Filter>
class CloudFilter : public apex::Node, public CloudFilterPorts {
 protected:
  /** @brief Sets the filter's parameters for this firing (its input is set already). */
  virtual void configure(Filter& filter) = 0;

 private:
  void process() final {
    const auto in = in_.get();
    Filter filter;
    filter.setInputCloud(xyzOf(*in, xyz_.next()));
    configure(filter);
    kept_.clear();  // PCL leaves it as it was if the filter cannot start
    filter.filter(kept_);
    out_.publish(cloudResult(*in, selectPoints(*in->points, kept_, points_.next())));
  }
  Reused<XyzCloud> xyz_;  // the filter's input, the filter's output and the points sent: reused
  pcl::Indices kept_;
  Reused<Blob> points_;
  apex::Input<Cloud> in_{this, kCloudIn};
  apex::Output<Cloud> out_{this, kCloudOut};
};

}  // namespace apex_nodes
