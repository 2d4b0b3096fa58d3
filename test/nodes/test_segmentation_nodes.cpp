// Segmentation nodes (watershed.cpp, grab_cut.cpp, kmeans_colours.cpp, connected_components.cpp,
// superpixels.cpp) on opencv-doc's real images, against the same OpenCV call made directly:
// pixel-exact where OpenCV is repeatable (k-means and GrabCut with the same cv::setRNGSeed), and
// each node's error on input it cannot handle, after which it goes on with the next frame.
#include <gmock/gmock.h>

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/lsc.hpp>
#include <opencv2/ximgproc/seeds.hpp>
#include <opencv2/ximgproc/slic.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using apex_nodes::Regions;
namespace xi = cv::ximgproc;

namespace {

/** A second sink, on another output of the harness's node. */
Collector* tap(NodeHarness& h, const std::string& output) {
  add(h.graph(), "test/Collector", "tap_" + output);
  link(h.graph(), "node", output, "tap_" + output, "in");
  return object<Collector>(h.graph(), "tap_" + output);
}

Message last(Collector* sink) { return sink->size() ? sink->messages().back() : Message(); }

int intOf(const Message& m) { return m.isNothing() ? -999 : *m.as<int>(); }

// --- Watershed

/** Markers as OpenCV's watershed tutorial makes them: the sure background 1, each object's sure
 *  middle (far from the background, by distanceTransform) a label from 2, the rest 0 (unknown). */
cv::Mat tutorialMarkers(const cv::Mat& bgr) {
  cv::Mat gray, objects, sure_background, distance, middles, unknown, markers;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  cv::threshold(gray, objects, 0, 255, cv::THRESH_BINARY_INV | cv::THRESH_OTSU);  // coloured candies on white
  const cv::Mat kernel = cv::Mat::ones(3, 3, CV_8U);
  cv::morphologyEx(objects, objects, cv::MORPH_OPEN, kernel, cv::Point(-1, -1), 2);
  cv::dilate(objects, sure_background, kernel, cv::Point(-1, -1), 3);
  cv::distanceTransform(objects, distance, cv::DIST_L2, 5);
  double far = 0;
  cv::minMaxLoc(distance, nullptr, &far);
  cv::threshold(distance, middles, 0.5 * far, 255, cv::THRESH_BINARY);
  middles.convertTo(middles, CV_8U);
  cv::subtract(sure_background, middles, unknown);
  cv::connectedComponents(middles, markers);  // CV_32S: 0 around the middles, 1.. the middles
  cv::add(markers, cv::Scalar(1), markers);
  markers.setTo(cv::Scalar(0), unknown);
  return markers;
}

TEST(SegmentationNodes, WatershedMatchesOpenCVAndLeavesItsMarkersAsTheyCame) {
  const cv::Mat src = readData("smarties.png");
  const cv::Mat markers = tutorialMarkers(src);
  cv::Mat want = markers.clone();
  cv::watershed(src, want);
  ASSERT_GT(cv::countNonZero(want == -1), 0) << "no boundaries: the markers are not the tutorial's";
  NodeHarness h("apex_nodes/Watershed", {"image", "markers"}, "markers");
  expectImage(h, runImages(h, {imageOf(src, "bgr8"), imageOf(markers, "32SC1")}), want, "32SC1");
  expectSameMat(markers, tutorialMarkers(src));  // the input's pixels: watershed wrote into a copy
  cv::Mat mono;
  markers.convertTo(mono, CV_8U);
  expectNothing(h, runImages(h, {imageOf(src, "bgr8"), imageOf(mono, "mono8")}),
                "the markers are 413x356 'mono8' (8UC1); they need a 32SC1 label image (e.g. ConnectedComponents' labels)");
  expectImage(h, runImages(h, {imageOf(src, "bgr8"), imageOf(markers, "32SC1")}), want, "32SC1");
}

// --- GrabCut

/** cv::grabCut's result made directly, as a mask: 255 where its classes say object (certain or probable). */
cv::Mat grabCutMask(const cv::Mat& src, const cv::Rect& rect, int iterations, int seed) {
  cv::Mat classes, background_model, object_model;
  cv::setRNGSeed(seed);
  cv::grabCut(src, classes, rect, background_model, object_model, iterations, cv::GC_INIT_WITH_RECT);
  return (classes == cv::GC_FGD) | (classes == cv::GC_PR_FGD);
}

TEST(SegmentationNodes, GrabCutMatchesOpenCVWithTheParametersRectangleOrARegion) {
  const cv::Mat src = readData("messi5.jpg");
  const cv::Rect player(50, 50, 450, 290);  // as in OpenCV's GrabCut tutorial
  const cv::Mat want = grabCutMask(src, player, 2, 7);
  ASSERT_GT(cv::countNonZero(want), 0);
  NodeHarness h("apex_nodes/GrabCut", {"image"}, "mask");
  for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{
           {"x", "50"}, {"y", "50"}, {"width", "450"}, {"height", "290"}, {"iter_count", "2"}, {"seed", "7"}})
    h.set(name, value);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "mono8");
  expectNothing(h, h.run(imageOf(readGrayData("messi5.jpg"), "mono8")),
                "cannot handle 1-channel images (encoding 'mono8'); needs 3 channels");
  h.set("x", "600");
  expectNothing(h, h.run(imageOf(src, "bgr8")),
                "the rectangle 600,50 450x290 has fewer than 5 pixels in the image 548x342 'bgr8' (8UC3)");

  NodeHarness boxed("apex_nodes/GrabCut", {"image", "regions"}, "mask");  // the rectangle from a detector
  boxed.set("iter_count", "2");
  boxed.set("seed", "7");
  auto regions = std::make_shared<Regions>();
  regions->regions.emplace_back();
  regions->regions.back().box = player;
  const auto frame = Message::share<Image>(imageOf(src, "bgr8"));
  expectImage(boxed, boxed.run({frame, Message::share<Regions>(regions)}), want, "mono8");
  expectImage(boxed, boxed.run({frame, Message::share<Regions>(std::make_shared<Regions>())}),
              cv::Mat::zeros(src.size(), CV_8UC1), "mono8");  // nothing detected: nothing cut out
}

// --- KMeansColours

/** cv::kmeans on the pixels of `src` made directly with `seed`: the labels as an image, and `src`
 *  in the colours of the centres (rounded to 8 bits). */
struct KMeansResult {
  cv::Mat labels, quantised;
};
KMeansResult kmeansColours(const cv::Mat& src, int k, int attempts, int flags, int seed) {
  cv::Mat samples, labels, centres, colours;
  src.convertTo(samples, CV_32F);
  cv::setRNGSeed(seed);
  cv::kmeans(samples.reshape(1, int(src.total())), k, labels,
             cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 20, 0.5), attempts, flags, centres);
  KMeansResult out;
  out.labels = labels.reshape(1, src.rows);
  centres.convertTo(colours, CV_8U);
  out.quantised.create(src.size(), src.type());
  for (int i = 0; i < k; ++i) {
    cv::Scalar colour;
    for (int c = 0; c < src.channels(); ++c) colour[c] = colours.at<uchar>(i, c);
    out.quantised.setTo(colour, out.labels == i);
  }
  return out;
}

TEST(SegmentationNodes, KMeansColoursIsOpenCVsKMeansWithTheSameSeedFrameAfterFrame) {
  const cv::Mat colour = readData("fruits.jpg"), gray = readGrayData("fruits.jpg");
  NodeHarness h("apex_nodes/KMeansColours", {"image"}, "image");
  Collector* labels = tap(h, "labels");
  h.set("k", "5");
  h.set("attempts", "2");
  h.set("max_count", "20");
  h.set("epsilon", "0.5");
  h.set("seed", "11");
  const KMeansResult want = kmeansColours(colour, 5, 2, cv::KMEANS_PP_CENTERS, 11);
  for (int frame = 0; frame < 2; ++frame) {  // the same clusters again: the seed is set before each frame
    expectImage(h, h.run(imageOf(colour, "bgr8")), want.quantised, "bgr8");
    expectImage(h, last(labels), want.labels, "32SC1");
  }
  cv::Mat wide;
  gray.convertTo(wide, CV_16U, 257);
  expectNothing(h, h.run(imageOf(wide, "mono16")), "the image is 512x480 'mono16' (16UC1); it needs 8-bit pixels");
  h.set("k", "3");
  h.set("attempts", "1");
  h.set("flags", "random_centers");
  h.set("seed", "3");
  const KMeansResult grey = kmeansColours(gray, 3, 1, cv::KMEANS_RANDOM_CENTERS, 3);
  expectImage(h, h.run(imageOf(gray, "mono8")), grey.quantised, "mono8");
  expectImage(h, last(labels), grey.labels, "32SC1");
}

// --- ConnectedComponents

TEST(SegmentationNodes, ConnectedComponentsMatchesOpenCVOnAThresholdedPhotograph) {
  cv::Mat binary;  // the grid's lines and the digits of a photographed sudoku, and some noise
  cv::adaptiveThreshold(readGrayData("sudoku.png"), binary, 255, cv::ADAPTIVE_THRESH_MEAN_C, cv::THRESH_BINARY_INV, 11, 2);
  NodeHarness h("apex_nodes/ConnectedComponents", {"image"}, "labels");
  Collector *count = tap(h, "count"), *regions = tap(h, "regions");
  const auto check = [&](const std::string& connectivity, const std::string& ccltype, int cv_ccltype) {
    SCOPED_TRACE(connectivity + ", " + ccltype);
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, std::stoi(connectivity), CV_32S, cv_ccltype);
    ASSERT_GT(n, 10);
    h.set("connectivity", connectivity);
    h.set("ccltype", ccltype);
    expectImage(h, h.run(imageOf(binary, "mono8")), labels, "32SC1");
    EXPECT_EQ(intOf(last(count)), n - 1);
    const auto got = last(regions).as<Regions>();
    ASSERT_TRUE(got) << h.error();
    expectCameraHeader(got->header);
    EXPECT_EQ(got->image_size, binary.size());
    ASSERT_EQ(got->regions.size(), std::size_t(n - 1));
    for (int i = 1; i < n; ++i) {
      const apex_nodes::Region& r = got->regions[i - 1];
      EXPECT_EQ(r.box, cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                                stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT)));
      EXPECT_EQ(r.area, double(stats.at<int>(i, cv::CC_STAT_AREA)));
      EXPECT_EQ(r.centroid, cv::Point2d(centroids.at<double>(i, 0), centroids.at<double>(i, 1)));
    }
  };
  check("8", "default", cv::CCL_DEFAULT);
  expectNothing(h, h.run(readDataImage("sudoku.png")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
  check("4", "sauf", cv::CCL_SAUF);
}

// --- Superpixels

/** What a superpixel segmentation gives: its labels, the mask of its borders, its count. */
struct Segments {
  cv::Mat labels, mask;
  int count = 0;
};

/** A SLIC or an LSC made directly: refined, its small superpixels joined, read. */
template <class Segmentation>
Segments segments(Segmentation& s, int iterations, int min_element_size, bool thick_line) {
  Segments out;
  s.iterate(iterations);
  s.enforceLabelConnectivity(min_element_size);
  s.getLabels(out.labels);
  s.getLabelContourMask(out.mask, thick_line);
  out.count = s.getNumberOfSuperpixels();
  return out;
}

/** The Superpixels node on `h`, with taps on its mask and count. */
struct SuperpixelsHarness {
  NodeHarness h{"apex_nodes/Superpixels", {"image"}, "labels"};
  Collector* mask = tap(h, "mask");
  Collector* count = tap(h, "count");
  void expect(const cv::Mat& src, const Segments& want) {
    expectImage(h, h.run(imageOf(src, "bgr8")), want.labels, "32SC1");
    expectImage(h, last(mask), want.mask, "mono8");
    EXPECT_EQ(intOf(last(count)), want.count);
  }
};

TEST(SegmentationNodes, SuperpixelsSlicSlicoAndMslicAreXimgprocs) {
  const cv::Mat src = readData("fruits.jpg");
  SuperpixelsHarness s;
  s.h.set("region_size", "20");
  s.h.set("ruler", "15");
  s.h.set("num_iterations", "5");
  for (const auto& [name, algorithm] :
       std::vector<std::pair<std::string, int>>{{"slic", xi::SLIC}, {"slico", xi::SLICO}, {"mslic", xi::MSLIC}}) {
    SCOPED_TRACE(name);
    const auto slic = xi::createSuperpixelSLIC(src, algorithm, 20, 15.0f);
    const Segments want = segments(*slic, 5, 25, false);
    ASSERT_GT(want.count, 100);
    s.h.set("algorithm", name);
    s.expect(src, want);
  }
  expectNothing(s.h, s.h.run(imageOf(src(cv::Rect(0, 0, 30, 30)).clone(), "bgr8")),
                "region_size 20 needs an image of at least 40x40 pixels, got 30x30 'bgr8' (8UC3)");
}

TEST(SegmentationNodes, SuperpixelsSeedsIsXimgprocsAndItsGridMustFitTheImage) {
  const cv::Mat src = readData("fruits.jpg");
  const auto seeds = xi::createSuperpixelSEEDS(src.cols, src.rows, src.channels(), 300, 4, 2, 5, true);
  seeds->iterate(src, 5);
  Segments want;
  seeds->getLabels(want.labels);
  seeds->getLabelContourMask(want.mask, true);
  want.count = seeds->getNumberOfSuperpixels();
  SuperpixelsHarness s;
  s.h.set("algorithm", "seeds");
  s.h.set("num_superpixels", "300");  // num_levels 4, prior 2, histogram_bins 5: the defaults
  s.h.set("double_step", "true");
  s.h.set("num_iterations", "5");
  s.h.set("thick_line", "true");
  s.expect(src, want);
  expectNothing(s.h, s.h.run(imageOf(src(cv::Rect(0, 0, 40, 3)).clone(), "bgr8")),
                "num_superpixels 300 lays a grid of 53x4 on a 40x3 image; SEEDS needs 2x2 at least, one pixel each at most");
  s.expect(src, want);
}

TEST(SegmentationNodes, SuperpixelsLscIsXimgprocsButForItsRaces) {
  // OpenCV's LSC does not repeat itself to the pixel: its k-means step writes overlapping windows
  // from parallel_for_, and it sums floats in a TBB parallel_reduce whose split varies between
  // runs. So the borders are compared, not the label numbers (a superpixel more or less renumbers
  // the ones after it): nearly all agree, and the counts nearly do.
  const cv::Mat src = readData("fruits.jpg");
  const auto lsc = xi::createSuperpixelLSC(src, 20, 0.075f);
  const Segments want = segments(*lsc, 5, 25, false);
  ASSERT_GT(want.count, 100);
  SuperpixelsHarness s;
  s.h.set("algorithm", "lsc");
  s.h.set("region_size", "20");
  s.h.set("num_iterations", "5");
  const auto labels = s.h.run(imageOf(src, "bgr8")).as<Image>();
  ASSERT_TRUE(labels) << s.h.error();
  EXPECT_EQ(labels->encoding, "32SC1");
  EXPECT_EQ(labels->mat.type(), CV_32SC1);
  EXPECT_EQ(labels->mat.size(), src.size());
  const auto mask = last(s.mask).as<Image>();
  ASSERT_TRUE(mask);
  ASSERT_EQ(mask->mat.size(), want.mask.size());
  ASSERT_EQ(mask->mat.type(), want.mask.type());
  EXPECT_LE(cv::countNonZero(mask->mat != want.mask), int(src.total() / 100)) << "over 1% of the border mask differs";
  EXPECT_NEAR(intOf(last(s.count)), want.count, want.count / 50.0);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
