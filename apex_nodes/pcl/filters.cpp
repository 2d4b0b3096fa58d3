// PassThrough and CropBox: keep the points within limits, every field of them.
#include <pcl/filters/crop_box.h>
#include <pcl/filters/passthrough.h>

#include "apex_nodes/cloud_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class PassThrough : public CloudFilter<pcl::PassThrough<pcl::PointXYZ>> {
 public:
  static inline const apex::ParamDecl<std::string> kField = param::choice("field", {"x", "y", "z"}).init("z");
  static inline const apex::ParamDecl<apex::Interval> kLimits =
      param::interval("limits").range(-100.0, 100.0).step(0.01).init({0.0, 3.0}).describe("metres");
  static inline const apex::ParamDecl<bool> kNegative = param::flag("negative").describe("keep the points outside instead");
  static apex::Manifest manifest() {
    return filterManifest("Keeps the points whose x, y or z lies within limits").param(kField).param(kLimits).param(kNegative);
  }

 private:
  void configure(pcl::PassThrough<pcl::PointXYZ>& filter) override {
    filter.setFilterFieldName(field_.get());
    filter.setFilterLimits(static_cast<float>(limits_.get().low), static_cast<float>(limits_.get().high));
    filter.setNegative(negative_.get());
  }
  apex::Param<std::string> field_{this, kField};
  apex::Param<apex::Interval> limits_{this, kLimits};
  apex::Param<bool> negative_{this, kNegative};
};

/** One side of CropBox's box. */
apex::ParamDecl<apex::Interval> limits(const char* axis, double low, double high) {
  return param::interval(axis).range(-100.0, 100.0).step(0.01).init({low, high}).describe("the box's extent in metres");
}

class CropBox : public CloudFilter<pcl::CropBox<pcl::PointXYZ>> {
 public:
  static inline const apex::ParamDecl<apex::Interval> kX = limits("x", -1.0, 1.0);
  static inline const apex::ParamDecl<apex::Interval> kY = limits("y", -1.0, 1.0);
  static inline const apex::ParamDecl<apex::Interval> kZ = limits("z", 0.0, 3.0);
  static inline const apex::ParamDecl<bool> kNegative = param::flag("negative").describe("keep the points outside instead");
  static apex::Manifest manifest() {
    return filterManifest("Keeps the points inside an axis-aligned box").param(kX).param(kY).param(kZ).param(kNegative);
  }

 private:
  void configure(pcl::CropBox<pcl::PointXYZ>& filter) override {
    const apex::Interval x = x_.get(), y = y_.get(), z = z_.get();
    filter.setMin(Eigen::Vector4f(float(x.low), float(y.low), float(z.low), 1.f));
    filter.setMax(Eigen::Vector4f(float(x.high), float(y.high), float(z.high), 1.f));
    filter.setNegative(negative_.get());
  }
  apex::Param<apex::Interval> x_{this, kX};
  apex::Param<apex::Interval> y_{this, kY};
  apex::Param<apex::Interval> z_{this, kZ};
  apex::Param<bool> negative_{this, kNegative};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::PassThrough, "apex_nodes/PassThrough");
APEX_REGISTER_NODE(apex_nodes::CropBox, "apex_nodes/CropBox");
