// CloudToOccupancyGrid and HeightMap: a cloud's points within a z band, binned on a grid of square
// cells in x and y (the cloud's own frame: move it first, e.g. TransformCloud, for a map in another).
// The grid covers the band's points (its origin their least x and y) or a fixed area; a point at x,
// y falls in the cell (floor((x - origin x) / resolution), floor((y - origin y) / resolution)), with
// the resolution as the message holds it (a float), so that the map's own numbers place each cell.
// Cells are row by row from the origin, x along a row, as nav_msgs/OccupancyGrid lays them out.
// No rays are traced: a cell is occupied, free or unknown by the points that fell in it alone.

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/maps.hpp"

namespace apex_nodes {
namespace param = apex::param;

/** A node shape: a cloud in, its band's points placed on a grid (its parameters and the binning). */
class CloudGrid : public apex::Node {
 public:
  enum class Extent { kCloud, kFixed };
  static inline const apex::InputPort<Cloud> kCloud{"cloud", "needs x, y, z"};
  static inline const apex::ParamDecl<apex::Interval> kZBand =
      param::interval("z_band").range(-100.0, 100.0).step(0.01).describe("metres: the points binned, ends included");
  static inline const apex::ParamDecl<double> kResolution =
      param::number("resolution").range(0.001, 100.0).step(0.001).init(0.05).describe("metres: a cell's side");
  static inline const apex::ChoiceDecl<Extent> kExtent =
      param::choice<Extent>("extent", {{"cloud", Extent::kCloud, "just covers the band's points"},
                                       {"fixed", Extent::kFixed, "origin, width and height; points outside are left out"}})
          .describe("the area the grid covers");
  static inline const apex::ParamDecl<apex::Pair> kOrigin =
      param::pair("origin").init({-10.0, -10.0}).describe("fixed: x, y in metres of the first cell's corner (least x and y)");
  static inline const apex::ParamDecl<int> kWidth =
      param::integer("width").range(1, 10000).init(400).describe("fixed: cells along x");
  static inline const apex::ParamDecl<int> kHeight =
      param::integer("height").range(1, 10000).init(400).describe("fixed: cells along y");
  static apex::Manifest gridManifest(std::string description) {
    return apex::Manifest(std::move(description))
        .inCategory("clouds")
        .input(kCloud)
        .param(kZBand)
        .param(kResolution)
        .param(kExtent)
        .param(kOrigin)
        .param(kWidth)
        .param(kHeight);
  }

 protected:
  /** The grid's geometry. */
  struct Grid {
    double x0 = 0, y0 = 0, resolution = 1;
    int width = 0, height = 0;
    std::size_t cells() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
    /** The cell x, y falls in, row by row; -1 outside the grid (or not finite). */
    long cell(double x, double y) const {
      const double i = (x - x0) / resolution, j = (y - y0) / resolution;
      if (!(i >= 0 && i < width && j >= 0 && j < height)) return -1;
      return static_cast<long>(j) * width + static_cast<long>(i);
    }
    nav_msgs::MapMetaData info(const ros::Time& stamp) const {
      nav_msgs::MapMetaData m;
      m.map_load_time = stamp;
      m.resolution = static_cast<float>(resolution);
      m.width = static_cast<std::uint32_t>(width), m.height = static_cast<std::uint32_t>(height);
      m.origin.position.x = x0, m.origin.position.y = y0;
      m.origin.orientation.w = 1;
      return m;
    }
  };
  /** A band point and the cell it falls in. */
  struct Binned {
    long cell;
    float z;
  };

  /** The grid for `cloud`, and its band's points that fall in it. Throws std::invalid_argument for a
   *  cloud without points, a grid over no point, or one of more than kMaxCells cells. The points
   *  are read where they lie, twice with a grid that covers them (its bounds, then the cells): a
   *  view of x, y, z copied out first cost more than the second read (1.5x the loop by hand). */
  Grid bin(const Cloud& cloud, std::vector<Binned>& binned) {
    requirePoints(cloud);  // throws for a cloud without x, y, z or a finite point
    const Blob& points = *cloud.points;
    const apex::Interval band = z_band_.get();
    const auto inBand = [lo = band.low, hi = band.high](float x, float y, float z) {
      return std::isfinite(x) && std::isfinite(y) && z >= lo && z <= hi;
    };
    Grid g;
    g.resolution = static_cast<float>(resolution_.get());
    if (extent_.get() == Extent::kFixed) {
      g.x0 = origin_.get().first, g.y0 = origin_.get().second;
      g.width = width_.get(), g.height = height_.get();
    } else {
      float x1 = std::numeric_limits<float>::max(), y1 = x1, x2 = -x1, y2 = -x1;
      forEachXyz(points, [&](float x, float y, float z) {
        if (inBand(x, y, z)) x1 = std::min(x1, x), y1 = std::min(y1, y), x2 = std::max(x2, x), y2 = std::max(y2, y);
      });
      if (x1 > x2)
        throw std::invalid_argument("none of the cloud's " + std::to_string(pointCount(cloud)) + " points is within z [" +
                                    std::to_string(band.low) + ", " + std::to_string(band.high) + "]: the grid covers none");
      g.x0 = x1, g.y0 = y1;
      const double w = std::floor((x2 - g.x0) / g.resolution) + 1, h = std::floor((y2 - g.y0) / g.resolution) + 1;
      if (w * h > kMaxCells)
        throw std::invalid_argument("the band's points span " + std::to_string(x2 - x1) + " x " + std::to_string(y2 - y1) +
                                    " m: over " + std::to_string(static_cast<long>(kMaxCells)) + " cells of " +
                                    std::to_string(g.resolution) + " m; take larger cells or a fixed extent");
      g.width = static_cast<int>(w), g.height = static_cast<int>(h);
    }
    binned.clear();
    forEachXyz(points, [&](float x, float y, float z) {
      if (!inBand(x, y, z)) return;
      if (const long c = g.cell(x, y); c >= 0) binned.push_back({c, z});
    });
    return g;
  }

 private:
  static constexpr double kMaxCells = 1e8;
  apex::Param<apex::Interval> z_band_{this, kZBand};
  apex::Param<double> resolution_{this, kResolution};
  apex::Choice<Extent> extent_{this, kExtent};
  apex::Param<apex::Pair> origin_{this, kOrigin};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};

 protected:
  apex::Input<Cloud> cloud_{this, kCloud};
};

class CloudToOccupancyGrid : public CloudGrid {
 public:
  static inline const apex::OutputPort<nav_msgs::OccupancyGrid> kGrid{
      "grid", "100: occupied (min_points or more); 0: free (fewer); -1: unknown (none fell in it); the cloud's header"};
  static inline const apex::ParamDecl<int> kMinPoints =
      param::integer("min_points").range(1, 100000).init(1).describe("the band's points that make a cell occupied");
  static apex::Manifest manifest() {
    return gridManifest("Makes an occupancy grid of the points within a z band, seen from above (rviz's Map display)")
        .output(kGrid)
        .param(kMinPoints);
  }
  void process() override {
    const Cloud& in = *cloud_.get();
    const Grid g = bin(in, binned_);
    std::vector<int>& counts = counts_;  // kept between frames: no allocation per frame
    counts.assign(g.cells(), 0);
    for (const Binned& b : binned_) ++counts[b.cell];
    auto out = std::make_shared<nav_msgs::OccupancyGrid>();
    out->header = in.header;
    out->info = g.info(in.header.stamp);
    out->data.resize(g.cells());
    for (std::size_t k = 0; k < counts.size(); ++k) out->data[k] = counts[k] == 0 ? -1 : counts[k] >= min_points_.get() ? 100 : 0;
    grid_.publish(std::move(out));
  }

 private:
  apex::Output<nav_msgs::OccupancyGrid> grid_{this, kGrid};
  apex::Param<int> min_points_{this, kMinPoints};
  std::vector<Binned> binned_;
  std::vector<int> counts_;
};

class HeightMap : public CloudGrid {
 public:
  static inline const apex::OutputPort<Image> kHeights{
      "heights", "32FC1, a pixel per cell (row 0: the origin's row, as the grid's data): the highest z in it, NaN if none"};
  static inline const apex::OutputPort<nav_msgs::MapMetaData> kInfo{
      "info", "the grid: resolution, width, height, origin (an occupancy grid's info)"};
  static apex::Manifest manifest() {
    return gridManifest("Makes a height map: the highest z of the points within a z band in each cell of a grid")
        .output(kHeights)
        .output(kInfo);
  }
  void process() override {
    const Cloud& in = *cloud_.get();
    const Grid g = bin(in, binned_);
    cv::Mat heights(g.height, g.width, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
    float* h = heights.ptr<float>();
    for (const Binned& b : binned_)
      if (!(h[b.cell] >= b.z)) h[b.cell] = b.z;  // NaN: the first point
    auto image = std::make_shared<Image>();
    image->header = in.header;
    image->encoding = "32FC1";
    image->mat = heights;
    heights_.publish(std::move(image));
    info_.publish(g.info(in.header.stamp));
  }

 private:
  apex::Output<Image> heights_{this, kHeights};
  apex::Output<nav_msgs::MapMetaData> info_{this, kInfo};
  std::vector<Binned> binned_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::CloudToOccupancyGrid, "apex_nodes/CloudToOccupancyGrid");
APEX_REGISTER_NODE(apex_nodes::HeightMap, "apex_nodes/HeightMap");
