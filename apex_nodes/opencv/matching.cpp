// MatchDescriptors (brute force, ratio test or cross check), FindHomography (RANSAC, LMedS, RHO) and DrawMatches.
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/features.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {

std::string sizeText(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

/** An 8-bit image (1, 3 or 4 channels) as cv::drawMatches takes it: gray or bgr8 as it is (it only
 *  reads them, and turns gray to BGR itself, as cv::cvtColor's GRAY2BGR); rgb8, rgba8 and bgra8 as
 *  bgr8 in `scratch` (a 4-channel image would make its result 4-channel). */
const cv::Mat& drawable(const Image& in, cv::Mat& scratch) {
  requireImage(in, "134");
  if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
  const bool rgb = in.encoding.rfind("rgb", 0) == 0;
  if (in.mat.channels() == 1 || (in.mat.channels() == 3 && !rgb)) return in.mat;
  if (in.mat.channels() == 4) cv::cvtColor(in.mat, scratch, rgb ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
  else cv::cvtColor(in.mat, scratch, cv::COLOR_RGB2BGR);
  return scratch;
}

/** "orb descriptors (32 columns of 8U)", for errors. */
std::string describe(const Keypoints& k) {
  static const char* depths[] = {"8U", "8S", "16U", "16S", "32S", "32F", "64F", "16F"};
  return k.method + " descriptors (" + std::to_string(k.descriptors.cols) + " columns of " + depths[k.descriptors.depth()] + ")";
}

}  // namespace

class MatchDescriptors : public apex::Node {
 public:
  static inline const apex::InputPort<Keypoints> kQuery{"query", "keypoints with descriptors, e.g. of the object"};
  static inline const apex::InputPort<Keypoints> kTrain{"train", "keypoints of the same method, e.g. of the scene"};
  static inline const apex::OutputPort<Matches> kMatches{"matches", "for each kept query keypoint, its best train keypoint"};
  static inline const apex::ParamDecl<double> kRatio =
      param::number("ratio_test")
          .range(0.0, 1.0)
          .step(0.01)
          .describe(
              "0: off; else Lowe's ratio test: keep a match if its distance is below this times the second best's (e.g. 0.75)");
  static inline const apex::ParamDecl<bool> kCrossCheck =
      param::flag("cross_check")
          .describe("keep a match only if the train keypoint's best match is the query keypoint too (not with the ratio test)");
  static apex::Manifest manifest() {
    return apex::Manifest("Matches two sets of descriptors by brute force, with the norm of their method (cv::BFMatcher)")
        .inCategory("features")
        .input(kQuery)
        .input(kTrain)
        .output(kMatches)
        .param(kRatio)
        .param(kCrossCheck);
  }
  void process() override {
    auto query = query_.get(), train = train_.get();
    const double ratio = ratio_.get();
    if (ratio > 0 && cross_check_.get())
      throw std::invalid_argument("cross_check cannot be combined with the ratio test (ratio_test " + std::to_string(ratio) +
                                  "): set ratio_test to 0 or clear cross_check");
    auto out = std::make_shared<Matches>();
    out->header = query->header;
    out->query = query;
    out->train = train;
    if (!query->keypoints.empty() && !train->keypoints.empty()) {
      for (const auto* k : {query.get(), train.get()})
        if (k->descriptors.empty())
          throw std::invalid_argument("the " + std::string(k == query.get() ? "query" : "train") + " keypoints (" + k->method +
                                      ") have no descriptors: use orb, akaze, brisk or sift");
      if (query->method != train->method || query->descriptors.type() != train->descriptors.type() ||
          query->descriptors.cols != train->descriptors.cols)
        throw std::invalid_argument("cannot match the query's " + describe(*query) + " with the train's " + describe(*train));
      if (ratio > 0) {
        std::vector<std::vector<cv::DMatch>> knn;
        cv::BFMatcher(query->norm_type).knnMatch(query->descriptors, train->descriptors, knn, 2);
        for (const auto& m : knn)  // a keypoint without a second neighbour cannot pass the test
          if (m.size() == 2 && m[0].distance < ratio * m[1].distance) out->matches.push_back(m[0]);
      } else {
        cv::BFMatcher(query->norm_type, cross_check_.get()).match(query->descriptors, train->descriptors, out->matches);
      }
    }
    matches_.publish(out);
  }

 private:
  apex::Input<Keypoints> query_{this, kQuery};
  apex::Input<Keypoints> train_{this, kTrain};
  apex::Output<Matches> matches_{this, kMatches};
  apex::Param<double> ratio_{this, kRatio};
  apex::Param<bool> cross_check_{this, kCrossCheck};
};

class FindHomography : public apex::Node {
 public:
  static inline const apex::InputPort<Matches> kMatches{"matches", "at least 4"};
  static inline const apex::OutputPort<Homography> kHomography{"homography",
                                                               "query image -> train image; empty if none was found"};
  static inline const apex::ChoiceDecl<int> kMethod =
      param::choice<int>("method", {{"ransac", cv::RANSAC}, {"lmeds", cv::LMEDS}, {"rho", cv::RHO}});
  static inline const apex::ParamDecl<double> kThreshold =
      param::number("ransac_reproj_threshold")
          .range(0.1, 100.0)
          .step(0.1)
          .init(3.0)
          .describe("pixels: the largest reprojection error of an inlier (ransac, rho; lmeds finds its own)");
  static inline const apex::ParamDecl<int> kMinInliers =
      param::integer("min_inliers").range(4, 100000).step(1).init(10).describe("fewer inliers: the homography is sent empty");
  static apex::Manifest manifest() {
    return apex::Manifest("The homography that maps the query keypoints of matches onto the train keypoints (cv::findHomography)")
        .inCategory("features")
        .input(kMatches)
        .output(kHomography)
        .param(kMethod)
        .param(kThreshold)
        .param(kMinInliers);
  }
  void process() override {
    const Matches& m = *matches_.get();
    if (m.matches.size() < 4) throw std::invalid_argument("needs at least 4 matches, got " + std::to_string(m.matches.size()));
    if (!m.query || !m.train) throw std::invalid_argument("the matches have no keypoints");
    std::vector<cv::Point2f> from, to;
    for (const auto& d : m.matches) {
      if (d.queryIdx < 0 || d.queryIdx >= int(m.query->keypoints.size()) || d.trainIdx < 0 ||
          d.trainIdx >= int(m.train->keypoints.size()))
        throw std::invalid_argument("match " + std::to_string(from.size()) + " refers to keypoints " +
                                    std::to_string(d.queryIdx) + " and " + std::to_string(d.trainIdx) + ", of " +
                                    std::to_string(m.query->keypoints.size()) + " and " +
                                    std::to_string(m.train->keypoints.size()));
      from.push_back(m.query->keypoints[d.queryIdx].pt);
      to.push_back(m.train->keypoints[d.trainIdx].pt);
    }
    auto out = std::make_shared<Homography>();
    out->header = m.header;
    out->image_size = m.query->image_size;
    out->matrix = cv::findHomography(from, to, method_.get(), threshold_.get(), out->inlier_mask);
    out->inliers = out->matrix.empty() ? 0 : cv::countNonZero(out->inlier_mask);
    if (out->matrix.empty()) out->inlier_mask.clear();
    if (out->inliers < min_inliers_.get()) out->matrix.release();
    homography_.publish(out);
  }

 private:
  apex::Input<Matches> matches_{this, kMatches};
  apex::Output<Homography> homography_{this, kHomography};
  apex::Choice<int> method_{this, kMethod};
  apex::Param<double> threshold_{this, kThreshold};
  apex::Param<int> min_inliers_{this, kMinInliers};
};

class DrawMatches : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kQueryImage{"query_image", "8-bit, the query keypoints' image"};
  static inline const apex::InputPort<Image> kTrainImage{"train_image", "8-bit, the train keypoints' image"};
  static inline const apex::InputPort<Matches> kMatches{"matches"};
  static inline const apex::InputPort<Homography> kHomography{
      "homography", "optional: only its inliers are drawn (all matches while it has no inlier mask or is Nothing)", true};
  static inline const apex::OutputPort<Image> kDrawn{"image", "bgr8: the two images side by side, matches joined"};
  static inline const apex::ParamDecl<apex::Color> kMatchColor = param::color("match_color").init({0, 255, 0});
  static inline const apex::ParamDecl<apex::Color> kPointColor =
      param::color("single_point_color").init({255, 0, 0}).describe("keypoints without a match");
  static inline const apex::ParamDecl<bool> kNoSingle = param::flag("not_draw_single_points");
  static inline const apex::ParamDecl<bool> kRich =
      param::flag("rich_keypoints").describe("circles of the keypoints' size with their orientation");
  static apex::Manifest manifest() {
    return apex::Manifest("Draws matches between two images side by side (cv::drawMatches)")
        .inCategory("features")
        .input(kQueryImage)
        .input(kTrainImage)
        .input(kMatches)
        .input(kHomography)
        .output(kDrawn)
        .param(kMatchColor)
        .param(kPointColor)
        .param(kNoSingle)
        .param(kRich);
  }
  void process() override {
    const Image &query = *query_image_.get(), &train = *train_image_.get();
    const Matches& m = *matches_.get();
    if (!m.query || !m.train) throw std::invalid_argument("the matches have no keypoints");
    auto check = [](const Image& image, const Keypoints& keypoints, const std::string& name) {
      requireImage(image, "134");
      if (keypoints.image_size != image.mat.size())
        throw std::invalid_argument("the " + name + " keypoints are of a " + sizeText(keypoints.image_size) + " image, the " +
                                    name + "_image is " + sizeText(image.mat.size()));
    };
    check(query, *m.query, "query");
    check(train, *m.train, "train");
    std::vector<char> mask;
    if (auto h = homography_.get()) {
      if (h->inlier_mask.size() != m.matches.size() && !h->inlier_mask.empty())
        throw std::invalid_argument("the homography's inlier mask has " + std::to_string(h->inlier_mask.size()) +
                                    " entries for " + std::to_string(m.matches.size()) + " matches");
      mask.assign(h->inlier_mask.begin(), h->inlier_mask.end());
    }
    const cv::Mat &query_pixels = drawable(query, query_bgr_), &train_pixels = drawable(train, train_bgr_);
    auto out = buffer_.next(query);
    auto flags = cv::DrawMatchesFlags::DEFAULT;
    if (no_single_.get()) flags = flags | cv::DrawMatchesFlags::NOT_DRAW_SINGLE_POINTS;
    if (rich_.get()) flags = flags | cv::DrawMatchesFlags::DRAW_RICH_KEYPOINTS;
    const apex::Color &c = match_color_.get(), &p = point_color_.get();
    cv::drawMatches(query_pixels, m.query->keypoints, train_pixels, m.train->keypoints, m.matches, out->mat,
                    cv::Scalar(c.b, c.g, c.r), cv::Scalar(p.b, p.g, p.r), mask, flags);
    out->encoding = "bgr8";
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> query_image_{this, kQueryImage};
  apex::Input<Image> train_image_{this, kTrainImage};
  apex::Input<Matches> matches_{this, kMatches};
  apex::Input<Homography> homography_{this, kHomography};
  apex::Output<Image> image_out_{this, kDrawn};
  apex::Param<apex::Color> match_color_{this, kMatchColor};
  apex::Param<apex::Color> point_color_{this, kPointColor};
  apex::Param<bool> no_single_{this, kNoSingle};
  apex::Param<bool> rich_{this, kRich};
  cv::Mat query_bgr_, train_bgr_;  // rgb8 and 4-channel images as bgr8: reused between frames, never sent
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::MatchDescriptors, "apex_nodes/MatchDescriptors");
APEX_REGISTER_NODE(apex_nodes::FindHomography, "apex_nodes/FindHomography");
APEX_REGISTER_NODE(apex_nodes::DrawMatches, "apex_nodes/DrawMatches");
