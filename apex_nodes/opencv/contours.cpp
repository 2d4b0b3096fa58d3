// Contours of binary images: FindContours, ContourFilter, ContoursToRegions, DrawContours.
#include <climits>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"
#include "apex_nodes/shapes.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
const char* const kCategory = "contours and shapes";

void require8Bit(const Image& in, const std::string& channels) {
  requireImage(in, channels);
  if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image, got '" + in.encoding + "'");
}

std::string sizeText(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }
}  // namespace

class FindContours : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "binary, single-channel 8-bit: non-zero pixels are the shapes"};
  static inline const apex::OutputPort<Contours> kContours{"contours", "with their hierarchy"};
  static inline const apex::ChoiceDecl<int> kMode =
      param::choice<int>("mode", {{"external", cv::RETR_EXTERNAL, "outer contours only"},
                                  {"list", cv::RETR_LIST, "all, no nesting"},
                                  {"ccomp", cv::RETR_CCOMP, "outer and holes"},
                                  {"tree", cv::RETR_TREE, "all nesting"}});
  static inline const apex::ChoiceDecl<int> kMethod =
      param::choice<int>("method", {{"none", cv::CHAIN_APPROX_NONE, "every boundary pixel"},
                                    {"simple", cv::CHAIN_APPROX_SIMPLE, "straight runs as their end points"},
                                    {"tc89_l1", cv::CHAIN_APPROX_TC89_L1, "Teh-Chin"},
                                    {"tc89_kcos", cv::CHAIN_APPROX_TC89_KCOS, "Teh-Chin"}})
          .init("simple");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds the contours of a binary image (cv::findContours)")
        .inCategory(kCategory)
        .input(kImage)
        .output(kContours)
        .param(kMode)
        .param(kMethod);
  }
  void process() override {
    const Image& in = *image_.get();
    require8Bit(in, "1");
    auto out = std::make_shared<Contours>();
    out->header = in.header;
    out->image_size = in.mat.size();
    cv::findContours(in.mat, out->contours, out->hierarchy, mode_.get(), method_.get());  // reads only
    contours_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Contours> contours_{this, kContours};
  apex::Choice<int> mode_{this, kMode};
  apex::Choice<int> method_{this, kMethod};
};

class ContourFilter : public apex::Node {
 public:
  static inline const apex::InputPort<Contours> kIn{"contours"};
  static inline const apex::OutputPort<Contours> kOut{"contours", "those within every interval; the hierarchy among them"};
  static inline const apex::ParamDecl<apex::Interval> kArea =
      param::interval("area").range(0.0, 1e7).step(1.0).describe("pixels (cv::contourArea); at the top: no upper limit");
  static inline const apex::ParamDecl<apex::Interval> kPerimeter =
      param::interval("perimeter").range(0.0, 1e5).step(0.1).describe("pixels (closed); at the top: no upper limit");
  static inline const apex::ParamDecl<apex::Interval> kAspect =
      param::interval("aspect_ratio").range(0.0, 100.0).step(0.01).describe("bounding box width / height; at the top: no limit");
  static inline const apex::ParamDecl<apex::Interval> kSolidity =
      param::interval("solidity").range(0.0, 1.0).step(0.01).describe("area / convex hull area (1 for a contour without area)");
  static inline const apex::ParamDecl<apex::Interval> kCircularity =
      param::interval("circularity").range(0.0, 1.0).step(0.01).describe("4 pi area / perimeter^2: 1 for a circle");
  static inline const apex::ParamDecl<apex::Interval> kVertices =
      param::interval("vertices").range(0.0, 1000.0).step(1.0).describe("after cv::approxPolyDP; at the top: no upper limit");
  static inline const apex::ParamDecl<apex::Interval> kExtent = param::interval("extent").range(0.0, 1.0).step(0.01).describe(
      "area / bounding box area: 1 for an upright rectangle, pi/4 for a circle");
  static inline const apex::ParamDecl<apex::Interval> kHoles =
      param::interval("holes")
          .range(0.0, 1000.0)
          .step(1.0)
          .describe("contours directly inside (needs FindContours' ccomp or tree); at the top: no upper limit");
  static inline const apex::ParamDecl<double> kEpsilon =
      param::number("epsilon").range(0.0, 0.5).step(0.001).init(0.02).describe("approxPolyDP's epsilon, times the perimeter");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Keeps the contours whose area, perimeter, aspect ratio, solidity, circularity, vertex count, "
               "extent and holes are within their intervals")
        .inCategory(kCategory)
        .input(kIn)
        .output(kOut)
        .param(kArea)
        .param(kPerimeter)
        .param(kAspect)
        .param(kSolidity)
        .param(kCircularity)
        .param(kVertices)
        .param(kEpsilon)
        .param(kExtent)
        .param(kHoles);
  }
  void process() override {
    const auto in = in_.get();
    const bool nested = !in->hierarchy.empty() && in->hierarchy.size() == in->contours.size();
    if (!all(holes_.get(), kHoles) && !nested)
      throw std::invalid_argument("holes needs the contours' hierarchy: FindContours with mode ccomp or tree");
    std::vector<int> kept;
    for (std::size_t i = 0; i < in->contours.size(); ++i)
      if (keep(in->contours[i]) && (!nested || within(holes(in->hierarchy, i), holes_.get(), kHoles)))
        kept.push_back(static_cast<int>(i));
    if (kept.size() == in->contours.size()) {  // all of them: the message as it came
      out_.publishMessage(in_.take());
      return;
    }
    auto out = std::make_shared<Contours>();
    out->header = in->header;
    out->image_size = in->image_size;
    for (int i : kept) out->contours.push_back(in->contours[i]);
    if (in->hierarchy.size() == in->contours.size() && !in->hierarchy.empty())
      out->hierarchy = keptHierarchy(in->hierarchy, kept);
    out_.publish(std::move(out));
  }

 private:
  /** Whether `v` is within the interval; at the top of its range, the interval has no upper limit. */
  static bool within(double v, const apex::Interval& i, const apex::ParamDecl<apex::Interval>& d) {
    return v >= i.low && (v <= i.high || i.high >= d.spec().max);
  }
  static bool all(const apex::Interval& i, const apex::ParamDecl<apex::Interval>& d) {
    return i.low <= d.spec().min && i.high >= d.spec().max;
  }
  bool keep(const std::vector<cv::Point>& c) const {
    if (c.empty()) return false;
    const double area = cv::contourArea(c);
    if (!within(area, area_.get(), kArea)) return false;
    const double perimeter = cv::arcLength(c, true);
    if (!within(perimeter, perimeter_.get(), kPerimeter)) return false;
    const cv::Rect box = cv::boundingRect(c);
    if (!within(double(box.width) / box.height, aspect_.get(), kAspect)) return false;
    if (!within(area / box.area(), extent_.get(), kExtent)) return false;
    if (!all(solidity_.get(), kSolidity)) {
      std::vector<cv::Point> hull;
      cv::convexHull(c, hull);
      const double hull_area = cv::contourArea(hull);
      if (!within(hull_area > 0 ? std::min(1.0, area / hull_area) : 1.0, solidity_.get(), kSolidity)) return false;
    }
    const double circularity = perimeter > 0 ? std::min(1.0, 4 * M_PI * area / (perimeter * perimeter)) : 0.0;
    if (!within(circularity, circularity_.get(), kCircularity)) return false;
    if (!all(vertices_.get(), kVertices)) {
      std::vector<cv::Point> polygon;
      cv::approxPolyDP(c, polygon, epsilon_.get() * perimeter, true);
      if (!within(double(polygon.size()), vertices_.get(), kVertices)) return false;
    }
    return true;
  }
  /** How many contours lie directly inside contour `i` (its children). */
  static double holes(const std::vector<cv::Vec4i>& h, std::size_t i) {
    int n = 0;
    for (int k = h[i][2]; k >= 0 && k < int(h.size()) && n <= int(h.size()); k = h[k][0]) ++n;
    return n;
  }
  /** The kept contours' hierarchy: each one's parent is its nearest kept ancestor; its siblings
   *  are the kept contours of that parent, in their order. */
  static std::vector<cv::Vec4i> keptHierarchy(const std::vector<cv::Vec4i>& h, const std::vector<int>& kept) {
    std::vector<int> index(h.size(), -1);
    for (std::size_t k = 0; k < kept.size(); ++k) index[kept[k]] = static_cast<int>(k);
    std::vector<cv::Vec4i> out(kept.size(), cv::Vec4i(-1, -1, -1, -1));
    std::vector<int> last_child(kept.size() + 1, -1);  // per parent, +1: the top level at 0
    for (std::size_t k = 0; k < kept.size(); ++k) {
      int p = h[kept[k]][3];
      for (std::size_t steps = 0; p >= 0 && p < int(h.size()) && index[p] < 0 && steps < h.size(); ++steps) p = h[p][3];
      const int parent = p >= 0 && p < int(h.size()) ? index[p] : -1;
      const int self = static_cast<int>(k);
      out[k][3] = parent;
      int& last = last_child[parent + 1];
      if (last >= 0) out[last][0] = self, out[k][1] = last;
      else if (parent >= 0) out[parent][2] = self;
      last = self;
    }
    return out;
  }

  apex::Input<Contours> in_{this, kIn};
  apex::Output<Contours> out_{this, kOut};
  apex::Param<apex::Interval> area_{this, kArea};
  apex::Param<apex::Interval> perimeter_{this, kPerimeter};
  apex::Param<apex::Interval> aspect_{this, kAspect};
  apex::Param<apex::Interval> solidity_{this, kSolidity};
  apex::Param<apex::Interval> circularity_{this, kCircularity};
  apex::Param<apex::Interval> vertices_{this, kVertices};
  apex::Param<double> epsilon_{this, kEpsilon};
  apex::Param<apex::Interval> extent_{this, kExtent};
  apex::Param<apex::Interval> holes_{this, kHoles};
};

class ContoursToRegions : public apex::Node {
 public:
  static inline const apex::InputPort<Contours> kContours{"contours"};
  static inline const apex::OutputPort<Regions> kRegions{
      "regions", "one per contour: its upright bounding box, area (cv::contourArea) and centroid (moments)"};
  static inline const apex::OutputPort<int> kCount{"count", "how many regions"};
  static apex::Manifest manifest() {
    return apex::Manifest("Makes regions of contours: upright bounding boxes (a Region has no rotated box), area, centroid")
        .inCategory(kCategory)
        .input(kContours)
        .output(kRegions)
        .output(kCount);
  }
  void process() override {
    const Contours& in = *contours_.get();
    auto out = std::make_shared<Regions>();
    out->header = in.header;
    out->image_size = in.image_size;
    for (const auto& c : in.contours) {
      if (c.empty()) continue;
      Region r;
      r.box = cv::boundingRect(c);
      r.area = cv::contourArea(c);
      const cv::Moments m = cv::moments(c);
      if (std::abs(m.m00) > 1e-9) {
        r.centroid = cv::Point2d(m.m10 / m.m00, m.m01 / m.m00);
      } else {  // a line or a point: the mean of its points
        for (const auto& p : c) r.centroid += cv::Point2d(p);
        r.centroid /= double(c.size());
      }
      out->regions.push_back(r);
    }
    const int n = static_cast<int>(out->regions.size());
    regions_.publish(std::move(out));
    count_.publish(n);
  }

 private:
  apex::Input<Contours> contours_{this, kContours};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Output<int> count_{this, kCount};
};

class DrawContours : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit: gray, bgr8, rgb8 or with alpha"};
  static inline const apex::InputPort<Contours> kContours{"contours", "found in an image of this size"};
  static inline const apex::OutputPort<Image> kDrawn{"image", "bgr8 with the contours drawn"};
  static inline const apex::ParamDecl<apex::Color> kColor = param::color("color").init({0, 255, 0});
  static inline const apex::ParamDecl<int> kThickness =
      param::integer("thickness")
          .range(-1, 50)
          .step(1)
          .init(2)
          .describe("pixels; -1 (or 0): filled (with a hierarchy, holes stay open)");
  static apex::Manifest manifest() {
    return apex::Manifest("Draws contours over an image (cv::drawContours, with their hierarchy)")
        .inCategory(kCategory)
        .input(kImage)
        .input(kContours)
        .output(kDrawn)
        .param(kColor)
        .param(kThickness);
  }
  void process() override {
    const Image& in = *image_in_.get();
    const Contours& contours = *contours_.get();
    require8Bit(in, "134");
    if (!contours.image_size.empty() && contours.image_size != in.mat.size())
      throw std::invalid_argument("contours of a " + sizeText(contours.image_size) + " image cannot be drawn on one of " +
                                  sizeText(in.mat.size()));
    auto out = buffer_.next(in);
    if (in.mat.channels() == 1) cv::cvtColor(in.mat, out->mat, cv::COLOR_GRAY2BGR);
    else if (in.mat.channels() == 4)
      cv::cvtColor(in.mat, out->mat, in.encoding == "rgba8" ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
    else if (in.encoding == "rgb8") cv::cvtColor(in.mat, out->mat, cv::COLOR_RGB2BGR);
    else in.mat.copyTo(out->mat);
    out->encoding = "bgr8";
    const apex::Color& c = color_.get();
    const int thickness = thickness_.get() <= 0 ? cv::FILLED : thickness_.get();
    const bool nested = !contours.hierarchy.empty() && contours.hierarchy.size() == contours.contours.size();
    if (nested)
      cv::drawContours(out->mat, contours.contours, -1, cv::Scalar(c.b, c.g, c.r), thickness, cv::LINE_8, contours.hierarchy,
                       INT_MAX);
    else cv::drawContours(out->mat, contours.contours, -1, cv::Scalar(c.b, c.g, c.r), thickness);
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, kImage};
  apex::Input<Contours> contours_{this, kContours};
  apex::Output<Image> image_out_{this, kDrawn};
  apex::Param<apex::Color> color_{this, kColor};
  apex::Param<int> thickness_{this, kThickness};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::FindContours, "apex_nodes/FindContours");
APEX_REGISTER_NODE(apex_nodes::ContourFilter, "apex_nodes/ContourFilter");
APEX_REGISTER_NODE(apex_nodes::ContoursToRegions, "apex_nodes/ContoursToRegions");
APEX_REGISTER_NODE(apex_nodes::DrawContours, "apex_nodes/DrawContours");
