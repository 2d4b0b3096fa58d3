// apex_bench_images' cases of the two-input filters, channels, contours, drawing, blobs and
// template matching: each node against the OpenCV calls it makes (image_bench.cpp has the table).
#include <climits>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/shapes.hpp"
#include "image_cases.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Contours;
using apex_nodes::Regions;

/** The contours of Canny's edges (list, simple), with their hierarchy: what FindContours sends. */
std::shared_ptr<const Contours> contoursOf(const ImagePtr& edges) {
  auto c = std::make_shared<Contours>();
  c->header = edges->header;
  c->image_size = edges->mat.size();
  cv::findContours(edges->mat, c->contours, c->hierarchy, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
  return c;
}

/** The blobs of the binary image of at least 50 pixels: what BlobDetection sends. */
std::shared_ptr<const Regions> blobsOf(const ImagePtr& binary) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(binary->mat, labels, stats, centroids, 8, CV_32S);
  auto r = std::make_shared<Regions>();
  r->header = binary->header;
  r->image_size = binary->mat.size();
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < 50) continue;
    apex_nodes::Region region;
    region.box = cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                          stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    region.area = stats.at<int>(i, cv::CC_STAT_AREA);
    r->regions.push_back(region);
  }
  return r;
}

std::vector<NodeCase> twoImageCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const std::string two = feedType<Image, Image>(), sink = sinkType<Image>();
  const cv::Mat bgr = in.bgr->mat, mask = in.binary->mat, other = in.moving[3]->mat;
  c.push_back(fixedCase("ApplyMask", "apex_nodes/ApplyMask", "bgr8, Otsu mask", two, {"image", "mask"},
                        {msg(in.bgr), msg(in.binary)}, {}, "image", sink, "setTo 0, copyTo with mask",
                        [bgr, mask, out = cv::Mat()]() mutable {
                          out.create(bgr.size(), bgr.type());
                          out.setTo(cv::Scalar::all(0));
                          bgr.copyTo(out, mask);
                        }));
  c.push_back(fixedCase("ImageCombine (absdiff)", "apex_nodes/ImageCombine", "two bgr8 frames", two, {"a", "b"},
                        {msg(in.bgr), msg(in.moving[3])}, {{"operation", "absdiff"}}, "image", sink, "absdiff",
                        [bgr, other, out = cv::Mat()]() mutable { cv::absdiff(bgr, other, out); }));
  c.push_back(imageCase("Crop", "apex_nodes/Crop", "bgr8", {in.bgr},
                        {{"x", "100"}, {"y", "80"}, {"width", "320"}, {"height", "240"}}, "image", sink, "Mat(rect): a view",
                        [out = cv::Mat()](const cv::Mat& m) mutable { out = m(cv::Rect(100, 80, 320, 240)); }));
  c.push_back(imageCase("SplitChannels", "apex_nodes/SplitChannels", "bgr8 (channel_0 taken)", {in.bgr}, {}, "channel_0", sink,
                        "split into 3", [outs = std::vector<cv::Mat>()](const cv::Mat& m) mutable { cv::split(m, outs); }));
  std::vector<cv::Mat> planes;
  cv::split(bgr, planes);
  std::vector<apex::Message> channels;
  for (const cv::Mat& p : planes) channels.push_back(msg(image(p, "mono8")));
  c.push_back(fixedCase("MergeChannels", "apex_nodes/MergeChannels", "bgr8's 3 planes, mono8", feedType<Image, Image, Image>(),
                        {"channel_0", "channel_1", "channel_2"}, channels, {}, "image", sink, "merge 3",
                        [planes, out = cv::Mat()]() mutable { cv::merge(planes, out); }));
  return c;
}

std::vector<NodeCase> contourCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const auto contours = contoursOf(in.edges);
  const std::string words = std::to_string(contours->contours.size()) + " contours of Canny edges";
  c.push_back(fixedCase("ContourFilter", "apex_nodes/ContourFilter", words, feedType<Contours>(), {"contours"}, {msg(contours)},
                        {{"area", "[10, 1e7]"}, {"solidity", "[0.5, 1]"}}, "contours", sinkType<Contours>(),
                        "contourArea, arcLength, boundingRect, convexHull; copy the kept",
                        [contours, kept = std::vector<std::vector<cv::Point>>(), hull = std::vector<cv::Point>()]() mutable {
                          kept.clear();
                          for (const auto& k : contours->contours) {
                            const double area = cv::contourArea(k), perimeter = cv::arcLength(k, true);
                            const cv::Rect box = cv::boundingRect(k);
                            cv::convexHull(k, hull);
                            const double hull_area = cv::contourArea(hull), solidity = hull_area > 0 ? area / hull_area : 1.0;
                            if (area >= 10 && solidity >= 0.5 && perimeter >= 0 && box.height > 0) kept.push_back(k);
                          }
                        }));
  c.push_back(fixedCase("ContoursToRegions", "apex_nodes/ContoursToRegions", words, feedType<Contours>(), {"contours"},
                        {msg(contours)}, {}, "regions", sinkType<Regions>(), "boundingRect, contourArea, moments each",
                        [contours, out = std::vector<apex_nodes::Region>()]() mutable {
                          out.clear();
                          for (const auto& k : contours->contours) {
                            apex_nodes::Region r;
                            r.box = cv::boundingRect(k);
                            r.area = cv::contourArea(k);
                            const cv::Moments m = cv::moments(k);
                            if (m.m00 != 0) r.centroid = cv::Point2d(m.m10 / m.m00, m.m01 / m.m00);
                            out.push_back(r);
                          }
                        }));
  const cv::Mat bgr = in.bgr->mat;
  c.push_back(fixedCase("DrawContours", "apex_nodes/DrawContours", "bgr8, " + words, feedType<Image, Contours>(),
                        {"image", "contours"}, {msg(in.bgr), msg(contours)}, {{"thickness", "2"}}, "image", sinkType<Image>(),
                        "copyTo, drawContours with hierarchy, 2 px", [bgr, contours, out = cv::Mat()]() mutable {
                          bgr.copyTo(out);
                          cv::drawContours(out, contours->contours, -1, cv::Scalar(0, 255, 0), 2, cv::LINE_8, contours->hierarchy,
                                           INT_MAX);
                        }));
  const auto blobs = blobsOf(in.binary);
  c.push_back(fixedCase("DrawRegions", "apex_nodes/DrawRegions",
                        "bgr8, " + std::to_string(blobs->regions.size()) + " blobs of the Otsu mask", feedType<Image, Regions>(),
                        {"image", "regions"}, {msg(in.bgr), msg(blobs)}, {{"thickness", "2"}}, "image", sinkType<Image>(),
                        "copyTo, rectangle each, 2 px", [bgr, blobs, out = cv::Mat()]() mutable {
                          bgr.copyTo(out);
                          for (const auto& r : blobs->regions) cv::rectangle(out, r.box, cv::Scalar(0, 255, 0), 2);
                        }));
  return c;
}

std::vector<NodeCase> detectionCases(const Inputs& in) {
  std::vector<NodeCase> c;
  c.push_back(imageCase(
      "BlobDetection", "apex_nodes/BlobDetection", "binary mono8", {in.binary}, {{"min_area", "50"}, {"max_area", "1000000"}},
      "regions", sinkType<Regions>(), "connectedComponentsWithStats 8, keep ≥ 50 px",
      [labels = cv::Mat(), stats = cv::Mat(), centroids = cv::Mat(), out = std::vector<cv::Rect>()](const cv::Mat& m) mutable {
        const int n = cv::connectedComponentsWithStats(m, labels, stats, centroids, 8, CV_32S);
        out.clear();
        for (int i = 1; i < n; ++i)
          if (stats.at<int>(i, cv::CC_STAT_AREA) >= 50)
            out.emplace_back(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3));
      }));
  const cv::Mat bgr = in.bgr->mat, templ = bgr(cv::Rect(300, 200, 64, 64)).clone();
  c.push_back(fixedCase("TemplateMatch", "apex_nodes/TemplateMatch", "bgr8, a 64x64 patch of it", feedType<Image, Image>(),
                        {"image", "template"}, {msg(in.bgr), msg(image(templ, "bgr8"))},
                        {{"method", "ccoeff_normed"}, {"threshold", "0.8"}, {"max_matches", "1"}}, "regions", sinkType<Regions>(),
                        "matchTemplate ccoeff_normed, minMaxLoc", [bgr, templ, scores = cv::Mat()]() mutable {
                          cv::matchTemplate(bgr, templ, scores, cv::TM_CCOEFF_NORMED);
                          double best = 0;
                          cv::Point at;
                          cv::minMaxLoc(scores, nullptr, &best, nullptr, &at);
                        }));
  return c;
}

}  // namespace

std::vector<NodeCase> shapeCases(const Inputs& in) {
  std::vector<NodeCase> c;
  for (auto* part : {twoImageCases, contourCases, detectionCases})
    for (auto& k : part(in)) c.push_back(std::move(k));
  return c;
}

}  // namespace apex_bench
