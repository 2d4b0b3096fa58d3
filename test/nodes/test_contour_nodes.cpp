// Contour nodes (FindContours, ContourFilter, ContoursToRegions, DrawContours) against the same
// OpenCV calls made directly, on opencv-doc's pic1.png (dark shapes on white, one with holes).
#include <gmock/gmock.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/shapes.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Contours;
using apex_nodes::Image;
using apex_nodes::Regions;
using ::testing::HasSubstr;

namespace {

/** pic1.png's shapes white on black, as a threshold would give them. */
cv::Mat binary() {
  cv::Mat b;
  cv::threshold(readGrayData("pic1.png"), b, 128, 255, cv::THRESH_BINARY_INV);
  return b;
}

/** The direct call's contours, as a message a node receives. */
std::shared_ptr<const Contours> direct(int mode = cv::RETR_TREE, int method = cv::CHAIN_APPROX_SIMPLE) {
  auto c = std::make_shared<Contours>();
  c->header.stamp = ros::Time(42, 7);
  c->header.frame_id = "camera";
  const cv::Mat b = binary();
  c->image_size = b.size();
  cv::findContours(b, c->contours, c->hierarchy, mode, method);
  return c;
}

TEST(ContourNodes, FindContoursMatchesOpenCV) {
  NodeHarness h("apex_nodes/FindContours", {"image"}, "contours");
  const auto in = imageOf(binary(), "mono8");
  const cv::Mat before = in->mat.clone();
  for (const auto& [mode, method] : std::vector<std::pair<std::string, std::string>>{
           {"external", "simple"}, {"tree", "simple"}, {"ccomp", "none"}, {"list", "tc89_kcos"}}) {
    h.set("mode", mode);
    h.set("method", method);
    const Message m = h.run(in);
    ASSERT_TRUE(m.as<Contours>()) << h.error();
    const Contours& got = *m.as<Contours>();
    const int cv_mode = mode == "external" ? cv::RETR_EXTERNAL
                        : mode == "tree"   ? cv::RETR_TREE
                        : mode == "ccomp"  ? cv::RETR_CCOMP
                                           : cv::RETR_LIST;
    const int cv_method = method == "simple" ? cv::CHAIN_APPROX_SIMPLE
                          : method == "none" ? cv::CHAIN_APPROX_NONE
                                             : cv::CHAIN_APPROX_TC89_KCOS;
    const auto want = direct(cv_mode, cv_method);
    EXPECT_EQ(got.contours, want->contours) << mode << "/" << method;
    EXPECT_EQ(got.hierarchy, want->hierarchy) << mode << "/" << method;
    EXPECT_EQ(got.image_size, in->mat.size());
    expectCameraHeader(got.header);
  }
  EXPECT_GT(direct(cv::RETR_TREE)->contours.size(), direct(cv::RETR_EXTERNAL)->contours.size());  // the holes
  EXPECT_EQ(cv::norm(in->mat, before, cv::NORM_INF), 0);  // the input is left as it was
}

TEST(ContourNodes, FindContoursRefusesWhatItCannotRead) {
  NodeHarness h("apex_nodes/FindContours", {"image"}, "contours");
  EXPECT_TRUE(h.run(readDataImage("pic1.png")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image"));
  cv::Mat deep;
  binary().convertTo(deep, CV_16U);
  EXPECT_TRUE(h.run(imageOf(deep, "mono16")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("needs an 8-bit image, got 'mono16'"));
  EXPECT_TRUE(h.run(imageOf(cv::Mat(), "mono8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("received an empty image"));
  EXPECT_FALSE(h.run(imageOf(binary(), "mono8")).isNothing());
  EXPECT_EQ(h.error(), "");
}

/** The measures ContourFilter documents, computed here from OpenCV's calls. */
struct Measures {
  double area, perimeter, aspect, solidity, circularity;
  std::size_t vertices;
};
Measures measure(const std::vector<cv::Point>& c, double epsilon) {
  Measures m{};
  m.area = cv::contourArea(c);
  m.perimeter = cv::arcLength(c, true);
  const cv::Rect box = cv::boundingRect(c);
  m.aspect = double(box.width) / box.height;
  std::vector<cv::Point> hull, polygon;
  cv::convexHull(c, hull);
  m.solidity = cv::contourArea(hull) > 0 ? std::min(1.0, m.area / cv::contourArea(hull)) : 1.0;
  m.circularity = m.perimeter > 0 ? std::min(1.0, 4 * M_PI * m.area / (m.perimeter * m.perimeter)) : 0.0;
  cv::approxPolyDP(c, polygon, epsilon * m.perimeter, true);
  m.vertices = polygon.size();
  return m;
}

/** The contours of `in` that `keep` says, in order. */
template <class F>
std::vector<std::vector<cv::Point>> select(const Contours& in, F keep) {
  std::vector<std::vector<cv::Point>> out;
  for (const auto& c : in.contours)
    if (keep(measure(c, 0.02))) out.push_back(c);
  return out;
}

TEST(ContourNodes, ContourFilterKeepsWhatItsIntervalsSay) {
  const auto in = direct();
  NodeHarness h("apex_nodes/ContourFilter", {"contours"}, "contours");
  // The default intervals keep everything: the message goes on as it came.
  EXPECT_EQ(h.run(in).as<Contours>(), in);

  h.set("area", "[2000, 10000000]");  // at the top of its range: no upper limit
  auto got = h.run(in).as<Contours>();
  ASSERT_TRUE(got) << h.error();
  auto want = select(*in, [](const Measures& m) { return m.area >= 2000; });
  EXPECT_EQ(got->contours, want);
  EXPECT_GE(want.size(), 3u);
  EXPECT_LT(want.size(), in->contours.size());
  expectCameraHeader(got->header);
  EXPECT_EQ(got->image_size, in->image_size);

  h.set("vertices", "[4, 4]");  // the rectangles
  got = h.run(in).as<Contours>();
  ASSERT_TRUE(got) << h.error();
  want = select(*in, [](const Measures& m) { return m.area >= 2000 && m.vertices == 4; });
  EXPECT_EQ(got->contours, want);
  EXPECT_GE(want.size(), 2u);

  h.set("area", "[0, 10000000]"), h.set("vertices", "[0, 1000]");
  h.set("circularity", "[0.8, 1]"), h.set("solidity", "[0.9, 1]"), h.set("aspect_ratio", "[0.5, 2]");
  got = h.run(in).as<Contours>();
  ASSERT_TRUE(got) << h.error();
  want = select(*in,
                [](const Measures& m) { return m.circularity >= 0.8 && m.solidity >= 0.9 && m.aspect >= 0.5 && m.aspect <= 2; });
  EXPECT_EQ(got->contours, want);
  EXPECT_GE(want.size(), 7u);  // the dots in the dark rectangle are round

  // The hierarchy among the kept ones: each one's parent is its nearest kept ancestor. The big
  // rectangle goes (too large), its holes (the dots) stay: they are at the top now.
  h.set("circularity", "[0, 1]"), h.set("solidity", "[0, 1]"), h.set("aspect_ratio", "[0, 100]");
  h.set("perimeter", "[40, 100000]"), h.set("area", "[0, 19000]");
  got = h.run(in).as<Contours>();
  ASSERT_TRUE(got) << h.error();
  auto kept = [&](int i) { return cv::arcLength(in->contours[i], true) >= 40 && cv::contourArea(in->contours[i]) <= 19000; };
  EXPECT_EQ(got->contours, select(*in, [](const Measures& m) { return m.perimeter >= 40 && m.area <= 19000; }));
  ASSERT_EQ(got->hierarchy.size(), got->contours.size());
  EXPECT_GE(got->contours.size(), 10u);
  for (std::size_t k = 0; k < got->contours.size(); ++k) {
    const int at = std::find(in->contours.begin(), in->contours.end(), got->contours[k]) - in->contours.begin();
    int p = in->hierarchy[at][3];
    while (p >= 0 && !kept(p)) p = in->hierarchy[p][3];
    const cv::Vec4i& link = got->hierarchy[k];
    if (p < 0) {
      EXPECT_EQ(link[3], -1) << k;
    } else {
      ASSERT_GE(link[3], 0) << k;
      EXPECT_EQ(got->contours[link[3]], in->contours[p]) << k;
    }
    if (link[0] >= 0) {
      EXPECT_EQ(got->hierarchy[link[0]][1], int(k)) << k;  // next's previous
      EXPECT_EQ(got->hierarchy[link[0]][3], link[3]) << k;  // siblings share the parent
    }
  }
}

TEST(ContourNodes, ContourFilterKeepsByExtentAndHoles) {
  const auto in = direct(cv::RETR_CCOMP);
  NodeHarness h("apex_nodes/ContourFilter", {"contours"}, "contours");
  h.set("extent", "[0.9, 1]");  // area / bounding box area: the upright rectangles
  auto got = h.run(in).as<Contours>();
  ASSERT_TRUE(got) << h.error();
  std::vector<std::vector<cv::Point>> want;
  for (const auto& c : in->contours)
    if (cv::contourArea(c) / cv::boundingRect(c).area() >= 0.9) want.push_back(c);
  EXPECT_EQ(got->contours, want);
  EXPECT_GE(want.size(), 1u);
  EXPECT_LT(want.size(), in->contours.size());

  h.set("extent", "[0, 1]"), h.set("holes", "[1, 1000]");  // those with a contour directly inside
  got = h.run(in).as<Contours>();
  ASSERT_TRUE(got) << h.error();
  want.clear();
  for (std::size_t i = 0; i < in->contours.size(); ++i)
    if (in->hierarchy[i][2] >= 0) want.push_back(in->contours[i]);
  EXPECT_EQ(got->contours, want);
  EXPECT_GE(want.size(), 1u);  // the rectangle with the dots

  auto flat = std::make_shared<Contours>(*in);
  flat->hierarchy.clear();  // as a node that keeps no hierarchy sends them
  EXPECT_TRUE(h.run(std::shared_ptr<const Contours>(flat)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("holes needs the contours' hierarchy: FindContours with mode ccomp or tree"));
}

TEST(ContourNodes, ContoursToRegionsGivesBoxesAreasAndCentroids) {
  const auto in = direct(cv::RETR_EXTERNAL);
  NodeHarness h("apex_nodes/ContoursToRegions", {"contours"}, "regions");
  const auto got = h.run(in).as<Regions>();
  ASSERT_TRUE(got) << h.error();
  ASSERT_EQ(got->regions.size(), in->contours.size());
  expectCameraHeader(got->header);
  EXPECT_EQ(got->image_size, in->image_size);
  for (std::size_t i = 0; i < in->contours.size(); ++i) {
    const auto& c = in->contours[i];
    const auto& r = got->regions[i];
    EXPECT_EQ(r.box, cv::boundingRect(c));
    EXPECT_EQ(r.area, cv::contourArea(c));
    const cv::Moments m = cv::moments(c);
    if (m.m00 > 0) {
      EXPECT_NEAR(r.centroid.x, m.m10 / m.m00, 1e-9);
      EXPECT_NEAR(r.centroid.y, m.m01 / m.m00, 1e-9);
    }
    EXPECT_TRUE(r.box.contains(cv::Point(r.centroid))) << i;
    EXPECT_EQ(r.label, -1);
  }
  NodeHarness count("apex_nodes/ContoursToRegions", {"contours"}, "count");
  EXPECT_EQ(*count.run(in).as<int>(), static_cast<int>(in->contours.size()));
}

TEST(ContourNodes, DrawContoursMatchesOpenCV) {
  const auto contours = direct();
  const cv::Mat gray = readGrayData("pic1.png");
  NodeHarness h("apex_nodes/DrawContours", {"image", "contours"}, "image");
  h.set("color", "{r: 255, g: 0, b: 0}");
  h.set("thickness", "-1");
  const Message m = h.run({Message::share<Image>(imageOf(gray, "mono8")), Message::share<Contours>(contours)});
  ASSERT_TRUE(m.as<Image>()) << h.error();
  const Image& got = *m.as<Image>();
  cv::Mat want;
  cv::cvtColor(gray, want, cv::COLOR_GRAY2BGR);
  cv::drawContours(want, contours->contours, -1, cv::Scalar(0, 0, 255), cv::FILLED, cv::LINE_8, contours->hierarchy, INT_MAX);
  ASSERT_EQ(got.mat.type(), want.type());
  EXPECT_EQ(cv::norm(got.mat, want, cv::NORM_INF), 0);
  EXPECT_EQ(got.encoding, "bgr8");
  expectCameraHeader(got.header);

  h.set("thickness", "3");  // outlines, on a colour image
  const cv::Mat colour = readData("pic1.png");
  const Message outlined = h.run({Message::share<Image>(imageOf(colour, "bgr8")), Message::share<Contours>(contours)});
  ASSERT_TRUE(outlined.as<Image>()) << h.error();
  colour.copyTo(want);
  cv::drawContours(want, contours->contours, -1, cv::Scalar(0, 0, 255), 3, cv::LINE_8, contours->hierarchy, INT_MAX);
  EXPECT_EQ(cv::norm(outlined.as<Image>()->mat, want, cv::NORM_INF), 0);

  cv::Mat small;
  cv::resize(gray, small, cv::Size(200, 150));
  EXPECT_TRUE(h.run({Message::share<Image>(imageOf(small, "mono8")), Message::share<Contours>(contours)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("contours of a 400x300 image cannot be drawn on one of 200x150"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
