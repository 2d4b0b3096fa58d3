// ConvexHull: the points on a cloud's convex hull (PCL's, by qhull), whole, with its area and
// volume. ConcaveHull: the alpha shape's outline, which follows a table's notch or an L-shaped
// floor where the convex hull would bridge it. ExtractPolygonalPrism: the points above a polygon, e.g. the objects on a table
// whose hull ConvexHull gave.
#include <pcl/common/point_tests.h>
#include <pcl/segmentation/extract_polygonal_prism_data.h>
#include <pcl/surface/concave_hull.h>
#include <pcl/surface/convex_hull.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"
#include "three_numbers.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** The finite points' indices, if some are not; else nullptr (PCL then takes them all). */
pcl::IndicesPtr finiteIndices(const XyzCloud& xyz) {
  auto out = std::make_shared<pcl::Indices>();
  for (std::size_t i = 0; i < xyz.size(); ++i)
    if (pcl::isFinite(xyz[i])) out->push_back(static_cast<pcl::index_t>(i));
  return out->size() < xyz.size() ? out : nullptr;
}

Eigen::Vector3d at(const XyzCloud& points, std::size_t i) { return points[i].getVector3fMap().cast<double>(); }

/** Area and volume of a hull as PCL's ConvexHull gives it: a polygon (2D: one, its points in
 *  order; volume 0) or triangles (3D). Computed here: PCL's own (qhull's "FA") prints a summary
 *  to stderr at every call, and in 2D gives the area of the polygon seen along an axis. */
std::pair<double, double> areaAndVolume(const XyzCloud& hull, const std::vector<pcl::Vertices>& polygons, bool polygon) {
  if (polygon) {
    Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < hull.size(); ++i) twice_area += at(hull, i).cross(at(hull, (i + 1) % hull.size()));
    return {twice_area.norm() / 2, 0.0};
  }
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // inside a convex hull: each face's tetrahedron to it is its share
  for (std::size_t i = 0; i < hull.size(); ++i) centre += at(hull, i);
  centre /= double(hull.size());
  double area = 0, volume = 0;
  for (const auto& triangle : polygons) {
    if (triangle.vertices.size() != 3) continue;
    const Eigen::Vector3d a = at(hull, triangle.vertices[0]), b = at(hull, triangle.vertices[1]),
                          c = at(hull, triangle.vertices[2]);
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    area += normal.norm() / 2;
    volume += std::abs(normal.dot(a - centre)) / 6;
  }
  return {area, volume};
}

}  // namespace

class ConvexHull : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud", "e.g. a table's points (SACSegmentation's inliers)"};
  static inline const apex::OutputPort<Cloud> kHull{"hull", "the hull's points, whole; in 2D in order round the polygon"};
  static inline const apex::OutputPort<double> kArea{"area", "square metres: the polygon's (2D) or the surface's (3D)"};
  static inline const apex::OutputPort<double> kVolume{"volume", "cubic metres (3D; 0 for a polygon)"};
  static inline const apex::ChoiceDecl<int> kDimension =
      param::choice<int>("dimension", {{"auto", 0, "by how flat the points lie (PCL's test)"},
                                       {"2", 2, "a polygon round points on a plane"},
                                       {"3", 3, "a polyhedron"}});
  static apex::Manifest manifest() {
    return apex::Manifest("The points on a cloud's convex hull: a polygon or a polyhedron")
        .inCategory("cloud segmentation")
        .input(kCloud)
        .output(kHull)
        .output(kArea)
        .output(kVolume)
        .param(kDimension);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in, xyz_.next());
    pcl::ConvexHull<pcl::PointXYZ> hull;
    hull.setInputCloud(xyz);
    if (auto finite = finiteIndices(*xyz)) hull.setIndices(finite);
    if (dimension_.get() > 0) hull.setDimension(dimension_.get());  // else auto
    XyzCloud points;
    std::vector<pcl::Vertices> polygons;
    hull.reconstruct(points, polygons);
    if (points.empty())
      throw std::invalid_argument("qhull found no convex hull of " + std::to_string(xyz->size()) + " points (dimension " +
                                  dimension_.text() + "): too few, or all on a line" +
                                  (hull.getDimension() == 3 ? " or a plane (try dimension 2)" : ""));
    pcl::PointIndices indices;
    hull.getHullPointIndices(indices);
    const auto [area, volume] = areaAndVolume(points, polygons, hull.getDimension() == 2);
    hull_.publish(cloudResult(*in, selectPoints(*in->points, indices.indices, points_.next())));
    area_.publish(area);
    volume_.publish(volume);
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Cloud> hull_{this, kHull};
  apex::Output<double> area_{this, kArea};
  apex::Output<double> volume_{this, kVolume};
  apex::Choice<int> dimension_{this, kDimension};
  Reused<XyzCloud> xyz_;  // the x, y, z view and the points sent: reused per frame
  Reused<Blob> points_;
};

class ConcaveHull : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud", "e.g. a table's points (SACSegmentation's inliers)"};
  static inline const apex::OutputPort<Cloud> kHull{"hull", "the points on the outline, whole (2D: round each polygon in turn)"};
  static inline const apex::OutputPort<int> kPolygons{"polygons", "how many polygons (2D) or triangles (3D) the outline has"};
  static inline const apex::ParamDecl<double> kAlpha =
      param::number("alpha")
          .range(0.0001, 100.0)
          .step(0.001)
          .init(0.1)
          .describe("metres: the radius of the circles that carve the shape; smaller follows the points more closely");
  static inline const apex::ChoiceDecl<int> kDimension =
      param::choice<int>("dimension", {{"2", 2, "outlines of points on a plane"}, {"3", 3, "a surface round the points"}});
  static apex::Manifest manifest() {
    return apex::Manifest("The points on a cloud's concave hull (PCL's ConcaveHull, an alpha shape by qhull)")
        .inCategory("cloud segmentation")
        .input(kCloud)
        .output(kHull)
        .output(kPolygons)
        .param(kAlpha)
        .param(kDimension);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in);
    pcl::ConcaveHull<pcl::PointXYZ> hull;
    hull.setInputCloud(xyz);
    if (auto finite = finiteIndices(*xyz)) hull.setIndices(finite);
    hull.setAlpha(alpha_.get());
    hull.setDimension(dimension_.get());
    hull.setKeepInformation(true);
    XyzCloud points;
    std::vector<pcl::Vertices> polygons;
    hull.reconstruct(points, polygons);
    if (points.empty())
      throw std::invalid_argument("qhull found no concave hull of " + std::to_string(xyz->size()) + " points at alpha " +
                                  apex::toText(alpha_.get()) + ": too few, or alpha too small for their spacing");
    pcl::PointIndices indices;
    hull.getHullPointIndices(indices);
    hull_.publish(cloudResult(*in, selectPoints(*in->points, indices.indices)));
    polygons_.publish(static_cast<int>(polygons.size()));
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Cloud> hull_{this, kHull};
  apex::Output<int> polygons_{this, kPolygons};
  apex::Param<double> alpha_{this, kAlpha};
  apex::Choice<int> dimension_{this, kDimension};
};

class ExtractPolygonalPrism : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::InputPort<Cloud> kHull{"hull", "a polygon on a plane, its points in order (ConvexHull's, 2D)"};
  static inline const apex::OutputPort<Cloud> kCloudOut{"cloud", "the points within the prism, whole"};
  static inline const apex::ParamDecl<apex::Interval> kHeight =
      param::interval("height")
          .range(-10.0, 10.0)
          .step(0.001)
          .init({0.01, 0.5})
          .describe("metres from the polygon's plane, positive on the viewpoint's side");
  static inline const apex::ParamDecl<std::vector<double>> kViewpoint =
      param::list("viewpoint").init({0, 0, 0}).describe("x, y, z on the side heights count up to (the sensor's origin)");
  static inline const apex::ParamDecl<bool> kNegative = param::flag("negative").describe("keep the points outside instead");
  static apex::Manifest manifest() {
    return apex::Manifest("Keeps the points above a polygon, within a height: e.g. the objects on a table")
        .inCategory("cloud segmentation")
        .input(kCloud)
        .input(kHull)
        .output(kCloudOut)
        .param(kHeight)
        .param(kViewpoint)
        .param(kNegative);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in, xyz_.next());
    const auto polygon = xyzOf(*hull_.get());
    if (polygon->size() < 3)
      throw std::invalid_argument("the hull has " + std::to_string(polygon->size()) + " points: a polygon needs at least 3");
    const Eigen::Vector3f viewpoint = threeNumbers(viewpoint_.get(), "viewpoint");
    pcl::ExtractPolygonalPrismData<pcl::PointXYZ> prism;
    prism.setInputCloud(xyz);
    if (auto finite = finiteIndices(*xyz)) prism.setIndices(finite);
    prism.setInputPlanarHull(polygon);
    prism.setHeightLimits(height_.get().low, height_.get().high);
    prism.setViewPoint(viewpoint.x(), viewpoint.y(), viewpoint.z());
    pcl::PointIndices inside;
    prism.segment(inside);
    const pcl::Indices& kept = negative_.get() ? complement(inside.indices, xyz->size()) : inside.indices;
    cloud_out_.publish(cloudResult(*in, selectPoints(*in->points, kept, points_.next())));
  }

 private:
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Input<Cloud> hull_{this, kHull};
  apex::Output<Cloud> cloud_out_{this, kCloudOut};
  apex::Param<apex::Interval> height_{this, kHeight};
  apex::Param<std::vector<double>> viewpoint_{this, kViewpoint};
  apex::Param<bool> negative_{this, kNegative};
  Reused<XyzCloud> xyz_;  // the x, y, z view and the points sent: reused per frame
  Reused<Blob> points_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ConvexHull, "apex_nodes/ConvexHull");
APEX_REGISTER_NODE(apex_nodes::ExtractPolygonalPrism, "apex_nodes/ExtractPolygonalPrism");
APEX_REGISTER_NODE(apex_nodes::ConcaveHull, "apex_nodes/ConcaveHull");
