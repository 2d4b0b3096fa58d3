// Feature nodes on real data, against the OpenCV calls made directly: opencv-doc's box.png found in
// box_in_scene.png, and graf1.png to graf3.png against their true homography (H1to3p.xml).
#include <gmock/gmock.h>

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/features.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Homography;
using apex_nodes::Image;
using apex_nodes::Keypoints;
using apex_nodes::Matches;
using ::testing::HasSubstr;

namespace {

cv::Mat grayOf(const Image& i) {
  cv::Mat g;
  cv::cvtColor(i.mat, g, cv::COLOR_BGR2GRAY);
  return g;
}

/** The Keypoints node's output for `in` with these parameters (nullptr, and a failure, if none). */
std::shared_ptr<const Keypoints> detect(const std::shared_ptr<const Image>& in,
                                        const std::vector<std::pair<std::string, std::string>>& params) {
  NodeHarness h("apex_nodes/Keypoints", {"image"}, "keypoints");
  for (const auto& [name, value] : params) h.set(name, value);
  auto k = h.run(in).as<Keypoints>();
  if (!k) ADD_FAILURE() << "Keypoints sent nothing: " << h.error();
  return k;
}

Message share(const std::shared_ptr<const Keypoints>& k) { return Message::share<Keypoints>(k); }

std::shared_ptr<const Matches> match(const std::shared_ptr<const Keypoints>& q, const std::shared_ptr<const Keypoints>& t,
                                     const std::vector<std::pair<std::string, std::string>>& params) {
  NodeHarness h("apex_nodes/MatchDescriptors", {"query", "train"}, "matches");
  for (const auto& [name, value] : params) h.set(name, value);
  auto m = h.run({share(q), share(t)}).as<Matches>();
  if (!m) ADD_FAILURE() << "MatchDescriptors sent nothing: " << h.error();
  return m;
}

void expectSameKeypoints(const std::vector<cv::KeyPoint>& got, const std::vector<cv::KeyPoint>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const cv::KeyPoint &a = got[i], &b = want[i];
    EXPECT_TRUE(a.pt == b.pt && a.size == b.size && a.angle == b.angle && a.response == b.response && a.octave == b.octave &&
                a.class_id == b.class_id)
        << what << ": keypoint " << i << " at " << a.pt << ", want " << b.pt;
  }
}

void expectSameMatches(const std::vector<cv::DMatch>& got, const std::vector<cv::DMatch>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_TRUE(got[i].queryIdx == want[i].queryIdx && got[i].trainIdx == want[i].trainIdx && got[i].imgIdx == want[i].imgIdx &&
                got[i].distance == want[i].distance)
        << what << ": match " << i;
}

TEST(FeatureNodes, KeypointsEqualOpenCvsDetectors) {
  struct Case {
    std::string method, max_features, threshold;
    cv::Ptr<cv::Feature2D> direct;
    int norm;  // 0: no descriptors
  };
  const std::vector<Case> cases = {
      {"orb", "500", "0", cv::ORB::create(500), cv::NORM_HAMMING},
      {"akaze", "500", "0", cv::AKAZE::create(), cv::NORM_HAMMING},
      {"brisk", "500", "40", cv::BRISK::create(40), cv::NORM_HAMMING},
      {"sift", "300", "0", cv::SIFT::create(300), cv::NORM_L2},
      {"fast", "500", "25", cv::FastFeatureDetector::create(25), 0},
      {"gftt", "200", "0.02", cv::GFTTDetector::create(200, 0.02), 0},
  };
  const auto scene = readDataImage("box_in_scene.png");
  const cv::Mat gray = grayOf(*scene);
  for (const auto& c : cases) {
    const auto got = detect(scene, {{"method", c.method}, {"max_features", c.max_features}, {"threshold", c.threshold}});
    ASSERT_TRUE(got) << c.method;
    std::vector<cv::KeyPoint> want;
    cv::Mat descriptors;
    if (c.norm) c.direct->detectAndCompute(gray, cv::noArray(), want, descriptors);
    else c.direct->detect(gray, want);
    EXPECT_GT(want.size(), 50u) << c.method;  // the scene has texture: not a test of nothing
    expectSameKeypoints(got->keypoints, want, c.method);
    expectSameMat(got->descriptors, descriptors);
    EXPECT_EQ(got->descriptors.rows, c.norm ? int(want.size()) : 0) << c.method;
    EXPECT_EQ(got->method, c.method);
    EXPECT_EQ(got->norm_type, c.norm) << c.method;
    EXPECT_EQ(got->header, scene->header);
    EXPECT_EQ(got->image_size, scene->mat.size());
  }
}

TEST(FeatureNodes, KeypointsRefuseWhatTheyCannotUse) {
  NodeHarness h("apex_nodes/Keypoints", {"image"}, "keypoints");
  EXPECT_TRUE(h.run(imageOf(cv::Mat(64, 64, CV_16UC1, cv::Scalar(1000)), "mono16")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("needs an 8-bit image ('mono16')"));
  EXPECT_TRUE(h.run(imageOf(cv::Mat(), "bgr8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("received an empty image"));
  h.set("max_features", "0");
  EXPECT_TRUE(h.run(readDataImage("box.png")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("orb needs max_features of at least 1"));
  h.set("method", "sift");  // 0: no limit, as SIFT's nfeatures
  EXPECT_FALSE(h.run(readDataImage("box.png")).isNothing());
  EXPECT_EQ(h.error(), "");
}

TEST(FeatureNodes, MatchDescriptorsEqualsBFMatcher) {
  const auto box = detect(readDataImage("box.png", "object"), {}), scene = detect(readDataImage("box_in_scene.png"), {});  // ORB
  ASSERT_TRUE(box && scene);
  std::vector<cv::DMatch> want;
  cv::BFMatcher(cv::NORM_HAMMING).match(box->descriptors, scene->descriptors, want);
  const auto plain = match(box, scene, {});
  ASSERT_TRUE(plain);
  expectSameMatches(plain->matches, want, "plain");
  EXPECT_EQ(plain->query, box);  // the same keypoints, not copies
  EXPECT_EQ(plain->train, scene);
  EXPECT_EQ(plain->header, box->header);

  cv::BFMatcher(cv::NORM_HAMMING, true).match(box->descriptors, scene->descriptors, want);
  const auto crossed = match(box, scene, {{"cross_check", "true"}});
  ASSERT_TRUE(crossed);
  expectSameMatches(crossed->matches, want, "cross_check");
  EXPECT_LT(want.size(), plain->matches.size());

  // Lowe's ratio test, on SIFT's float descriptors (L2).
  const auto sbox = detect(readDataImage("box.png", "object"), {{"method", "sift"}});
  const auto sscene = detect(readDataImage("box_in_scene.png"), {{"method", "sift"}});
  ASSERT_TRUE(sbox && sscene);
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_L2).knnMatch(sbox->descriptors, sscene->descriptors, knn, 2);
  want.clear();
  for (const auto& m : knn)
    if (m.size() == 2 && m[0].distance < 0.75f * m[1].distance) want.push_back(m[0]);
  const auto ratio = match(sbox, sscene, {{"ratio_test", "0.75"}});
  ASSERT_TRUE(ratio);
  expectSameMatches(ratio->matches, want, "ratio_test");
  EXPECT_GT(want.size(), 20u);
}

TEST(FeatureNodes, MatchDescriptorsErrorsNameTheProblem) {
  const auto orb = detect(readDataImage("box.png"), {}), sift = detect(readDataImage("box_in_scene.png"), {{"method", "sift"}});
  const auto fast = detect(readDataImage("box_in_scene.png"), {{"method", "fast"}});
  ASSERT_TRUE(orb && sift && fast);
  NodeHarness h("apex_nodes/MatchDescriptors", {"query", "train"}, "matches");
  EXPECT_TRUE(h.run({share(orb), share(sift)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot match the query's orb descriptors (32 columns of 8U) with the train's sift "
                                   "descriptors (128 columns of 32F)"));
  EXPECT_TRUE(h.run({share(fast), share(orb)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the query keypoints (fast) have no descriptors"));
  h.set("ratio_test", "0.8");
  h.set("cross_check", "true");
  EXPECT_TRUE(h.run({share(orb), share(orb)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cross_check cannot be combined with the ratio test"));
  h.set("cross_check", "false");
  EXPECT_FALSE(h.run({share(orb), share(orb)}).isNothing());
  EXPECT_EQ(h.error(), "");
}

/** The query and train points of matches, in their order. */
void pointsOf(const Matches& m, std::vector<cv::Point2f>& from, std::vector<cv::Point2f>& to) {
  for (const auto& d : m.matches) {
    from.push_back(m.query->keypoints[d.queryIdx].pt);
    to.push_back(m.train->keypoints[d.trainIdx].pt);
  }
}

TEST(FeatureNodes, FindHomographyEqualsOpenCvsOnTheBoxInTheScene) {
  const auto box = detect(readDataImage("box.png", "object"), {{"method", "sift"}});
  const auto scene = detect(readDataImage("box_in_scene.png"), {{"method", "sift"}});
  ASSERT_TRUE(box && scene);
  const auto matches = match(box, scene, {{"ratio_test", "0.75"}});
  ASSERT_TRUE(matches);
  std::vector<cv::Point2f> from, to;
  pointsOf(*matches, from, to);
  // Exactly equal: OpenCV's RANSAC, LMedS and RHO draw from RNGs of their own with a fixed seed, not
  // from cv::theRNG() (which is per thread: cv::setRNGSeed here would not reach the node's thread).
  for (const auto& [method, code] : {std::pair<std::string, int>{"ransac", cv::RANSAC}, {"lmeds", cv::LMEDS}, {"rho", cv::RHO}}) {
    NodeHarness h("apex_nodes/FindHomography", {"matches"}, "homography");
    h.set("method", method);
    h.set("ransac_reproj_threshold", "4");
    const auto got = h.run(matches).as<Homography>();
    ASSERT_TRUE(got) << method << ": " << h.error();
    std::vector<uchar> mask;
    const cv::Mat want = cv::findHomography(from, to, code, 4.0, mask);
    ASSERT_FALSE(want.empty()) << method;
    expectSameMat(got->matrix, want);
    EXPECT_EQ(got->inlier_mask, mask) << method;
    EXPECT_EQ(got->inliers, cv::countNonZero(mask)) << method;
    EXPECT_GE(got->inliers, 10) << method;
    EXPECT_EQ(got->header, box->header);
    EXPECT_EQ(got->image_size, box->image_size);
  }
}

TEST(FeatureNodes, FindHomographyFindsGrafsTrueHomography) {
  cv::FileStorage fs(kOpenCvData + "/H1to3p.xml", cv::FileStorage::READ);
  cv::Mat truth;
  fs["H13"] >> truth;
  ASSERT_EQ(truth.size(), cv::Size(3, 3));
  const auto one = readDataImage("graf1.png"), three = readDataImage("graf3.png");
  const auto q = detect(one, {{"method", "sift"}, {"max_features", "2000"}});
  const auto t = detect(three, {{"method", "sift"}, {"max_features", "2000"}});
  ASSERT_TRUE(q && t);
  const auto matches = match(q, t, {{"ratio_test", "0.75"}});
  ASSERT_TRUE(matches);
  NodeHarness h("apex_nodes/FindHomography", {"matches"}, "homography");
  const auto got = h.run(matches).as<Homography>();
  ASSERT_TRUE(got) << h.error();
  ASSERT_FALSE(got->matrix.empty());
  EXPECT_GE(got->inliers, 50);
  // Where the found and the true homography take a grid over graf1 (the points that land in graf3):
  // the same place but for the keypoints' noise, well under 2 pixels on average.
  std::vector<cv::Point2f> grid, found, want;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) grid.emplace_back(40 + 80 * x, 32 + 64 * y);
  cv::perspectiveTransform(grid, found, got->matrix);
  cv::perspectiveTransform(grid, want, truth);
  double sum = 0, worst = 0;
  int n = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (!cv::Rect(0, 0, three->mat.cols, three->mat.rows).contains(want[i])) continue;
    const double e = cv::norm(found[i] - want[i]);
    sum += e, worst = std::max(worst, e), ++n;
  }
  ASSERT_GT(n, 40);
  EXPECT_LT(sum / n, 2.0);
  EXPECT_LT(worst, 8.0);
}

TEST(FeatureNodes, FindHomographyNeedsFourMatchesAndEnoughInliers) {
  const auto box = detect(readDataImage("box.png", "object"), {{"method", "sift"}});
  const auto scene = detect(readDataImage("box_in_scene.png"), {{"method", "sift"}});
  ASSERT_TRUE(box && scene);
  const auto matches = match(box, scene, {{"ratio_test", "0.75"}});
  ASSERT_TRUE(matches);
  auto three = std::make_shared<Matches>(*matches);
  three->matches.resize(3);
  NodeHarness h("apex_nodes/FindHomography", {"matches"}, "homography");
  EXPECT_TRUE(h.run(std::shared_ptr<const Matches>(three)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("needs at least 4 matches, got 3"));
  const auto found = h.run(matches).as<Homography>();
  ASSERT_TRUE(found) << h.error();
  h.set("min_inliers", std::to_string(found->inliers + 1));
  const auto short_of = h.run(matches).as<Homography>();
  ASSERT_TRUE(short_of);
  EXPECT_TRUE(short_of->matrix.empty());  // too few inliers: none found, but how many it had is told
  EXPECT_EQ(short_of->inliers, found->inliers);
}

TEST(FeatureNodes, DrawKeypointsEqualsOpenCvs) {
  const auto box = readDataImage("box.png");
  const auto k = detect(box, {});
  ASSERT_TRUE(k);
  NodeHarness h("apex_nodes/DrawKeypoints", {"image", "keypoints"}, "image");
  cv::Mat want;
  cv::drawKeypoints(box->mat, k->keypoints, want, cv::Scalar(0, 255, 0));
  auto got = h.run({Message::share<Image>(box), share(k)}).as<Image>();
  ASSERT_TRUE(got) << h.error();
  expectSameMat(got->mat, want);
  EXPECT_EQ(got->encoding, "bgr8");
  EXPECT_EQ(got->header, box->header);
  h.set("rich_keypoints", "true");
  h.set("color", "{r: 255, g: 0, b: 0}");
  const auto gray = imageOf(grayOf(*box), "mono8");  // drawn on its gray as a bgr8 image
  cv::drawKeypoints(gray->mat, k->keypoints, want, cv::Scalar(0, 0, 255), cv::DrawMatchesFlags::DRAW_RICH_KEYPOINTS);
  got = h.run({Message::share<Image>(gray), share(k)}).as<Image>();
  ASSERT_TRUE(got) << h.error();
  expectSameMat(got->mat, want);
  EXPECT_TRUE(h.run({Message::share<Image>(readDataImage("box_in_scene.png")), share(k)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the keypoints are of a 324x223 image, the image is 512x384"));
}

TEST(FeatureNodes, DrawMatchesEqualsOpenCvsWithTheInliersOnly) {
  const auto box = readDataImage("box.png", "object"), scene = readDataImage("box_in_scene.png");
  const auto matches = match(detect(box, {{"method", "sift"}}), detect(scene, {{"method", "sift"}}), {{"ratio_test", "0.75"}});
  ASSERT_TRUE(matches);
  NodeHarness h("apex_nodes/DrawMatches", {"query_image", "train_image", "matches"}, "image");
  cv::Mat want;
  cv::drawMatches(box->mat, matches->query->keypoints, scene->mat, matches->train->keypoints, matches->matches, want,
                  cv::Scalar(0, 255, 0), cv::Scalar(0, 0, 255));
  auto got = h.run({Message::share<Image>(box), Message::share<Image>(scene), Message::share<Matches>(matches)}).as<Image>();
  ASSERT_TRUE(got) << h.error();
  expectSameMat(got->mat, want);
  EXPECT_EQ(got->mat.size(), cv::Size(324 + 512, 384));
  EXPECT_EQ(got->header, box->header);
  EXPECT_TRUE(h.run({Message::share<Image>(scene), Message::share<Image>(box), Message::share<Matches>(matches)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the query keypoints are of a 324x223 image, the query_image is 512x384"));

  NodeHarness inliers("apex_nodes/DrawMatches", {"query_image", "train_image", "matches", "homography"}, "image");
  NodeHarness find("apex_nodes/FindHomography", {"matches"}, "homography");
  const auto homography = find.run(matches).as<Homography>();
  ASSERT_TRUE(homography) << find.error();
  const std::vector<char> mask(homography->inlier_mask.begin(), homography->inlier_mask.end());
  cv::drawMatches(box->mat, matches->query->keypoints, scene->mat, matches->train->keypoints, matches->matches, want,
                  cv::Scalar(0, 255, 0), cv::Scalar(0, 0, 255), mask);
  got = inliers
            .run({Message::share<Image>(box), Message::share<Image>(scene), Message::share<Matches>(matches),
                  Message::share<Homography>(homography)})
            .as<Image>();
  ASSERT_TRUE(got) << inliers.error();
  expectSameMat(got->mat, want);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
