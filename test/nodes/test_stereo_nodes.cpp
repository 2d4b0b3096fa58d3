// Calibration and stereo on real data from opencv-doc: the chessboard sequence left01..left14
// (no left10) through ChessboardCorners into CameraCalibration, against cv::calibrateCamera on the
// same corners and OpenCV's own calibration (left_intrinsics.yml); the Middlebury pair aloeL/aloeR
// at half size (as OpenCV's stereo_match.py takes it) through StereoMatcher, against
// cv::StereoSGBM and cv::StereoBM and the ground truth aloeGT.png (disparities in pixels at full
// size, 0: unknown); and DisparityToCloud on that disparity, point by point.
#include <camera_calibration_parsers/parse.h>
#include <gmock/gmock.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/shapes.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using apex_nodes::Corners;
using apex_nodes::Image;
using sensor_msgs::CameraInfo;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

const std::string kData = "/usr/share/doc/opencv-doc/examples/data";  // scripts/install_deps installs opencv-doc

std::shared_ptr<Image> imageFile(const std::string& name, const std::string& frame, int stamp) {
  auto image = std::make_shared<Image>();
  image->mat = cv::imread(kData + "/" + name, cv::IMREAD_COLOR);
  image->encoding = "bgr8";
  image->header.frame_id = frame;
  image->header.stamp = ros::Time(100 + stamp, 0);
  if (image->mat.empty()) ADD_FAILURE() << "cannot read " << kData << "/" << name << ": is opencv-doc installed?";
  return image;
}

/** The 13 views of the chessboard sequence. */
std::vector<std::shared_ptr<Image>> chessboards() {
  std::vector<std::shared_ptr<Image>> out;
  for (int i = 1; i <= 14; ++i)
    if (i != 10) out.push_back(imageFile(cv::format("left%02d.jpg", i), "left_camera", i));
  return out;
}

/** A view's corners, found as ChessboardCorners finds them by default. */
std::shared_ptr<Corners> cornersOf(const Image& image) {
  auto c = std::make_shared<Corners>();
  c->header = image.header, c->image_size = image.mat.size(), c->pattern_size = cv::Size(9, 6);
  c->found = cv::findChessboardCorners(image.mat, c->pattern_size, c->corners,
                                       cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
  EXPECT_TRUE(c->found);
  return c;
}

std::string errorOf(Graph& g, const std::string& node) {
  for (const auto& s : g.nodeStats())
    if (s.name == node) return s.error;
  return "no node '" + node + "'";
}

void expectRelative(const std::vector<double>& got, const cv::Mat& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.total()) << what;
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], want.at<double>(int(i)), 1e-9 * std::abs(want.at<double>(int(i)))) << what << "[" << i << "]";
}

template <std::size_t N>
std::vector<double> values(const boost::array<double, N>& a) {
  return {a.begin(), a.end()};
}

/** feed → ChessboardCorners "board" → CameraCalibration "calib"; collectors on the board's corners
 *  and calib's outputs; calib's `calibrated` → a counter's reset slot. */
struct CalibrationGraph {
  Graph g{pluginRegistry()};
  explicit CalibrationGraph(const std::vector<std::pair<std::string, std::string>>& params) {
    add(g, "test/MessageFeeder", "feed");
    add(g, "apex_nodes/ChessboardCorners", "board");
    add(g, "apex_nodes/CameraCalibration", "calib");
    for (const char* sink : {"corners", "info", "rms"}) add(g, "test/Collector", sink);
    add(g, "test/Counter", "events");
    link(g, "feed", "out", "board", "image");
    link(g, "board", "corners", "calib", "corners");
    link(g, "board", "corners", "corners", "in");
    link(g, "calib", "camera_info", "info", "in");
    link(g, "calib", "rms", "rms", "in");
    link(g, "calib", "calibrated", "events", "reset");
    for (const auto& [name, value] : params) {
      auto r = g.setParameter("calib", name, value);
      EXPECT_TRUE(r) << r.message();
    }
    g.start();
  }
  std::vector<Message> sent(const std::string& sink) { return object<Collector>(g, sink)->messages(); }
};

TEST(StereoNodes, CameraCalibrationEqualsCalibrateCameraOnTheChessboardSequence) {
  const std::string file = ::testing::TempDir() + "/apex_test_calibration.yaml";
  fs::remove(file);
  CalibrationGraph c({{"views", "13"}, {"fix_aspect_ratio", "true"}, {"output_file", file}});  // left_intrinsics.yml's flags
  const auto images = chessboards();
  for (const auto& image : images) object<MessageFeeder>(c.g, "feed")->feed(Message::share<Image>(image));
  ASSERT_TRUE(object<Collector>(c.g, "info")->waitFor(images.size()));
  ASSERT_TRUE(c.g.waitIdle(kWait));
  const auto infos = c.sent("info"), rmss = c.sent("rms"), corners = c.sent("corners");
  ASSERT_EQ(infos.size(), images.size());
  for (std::size_t i = 0; i + 1 < infos.size(); ++i) EXPECT_TRUE(infos[i].isNothing()) << "view " << i;  // until calibrated
  const auto sent = infos.back().as<CameraInfo>();
  ASSERT_TRUE(sent) << errorOf(c.g, "calib");
  ASSERT_TRUE(rmss.back().as<double>());
  EXPECT_EQ(object<Counter>(c.g, "events")->resets, 1);
  EXPECT_EQ(sent->header, images.back()->header);

  // cv::calibrateCamera on the corners the node received
  std::vector<std::vector<cv::Point2f>> views;
  for (const Message& m : corners) {
    ASSERT_TRUE(m.as<Corners>() && m.as<Corners>()->found);
    views.push_back(m.as<Corners>()->corners);
  }
  std::vector<cv::Point3f> board;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j) board.emplace_back(float(j * 0.025), float(i * 0.025), 0.f);
  cv::Mat K = cv::Mat::eye(3, 3, CV_64F), D;
  std::vector<cv::Mat> rvecs, tvecs;
  const cv::Size size(640, 480);
  const double rms = cv::calibrateCamera(std::vector<std::vector<cv::Point3f>>(views.size(), board), views, size, K, D, rvecs,
                                         tvecs, cv::CALIB_FIX_ASPECT_RATIO);
  EXPECT_NEAR(*rmss.back().as<double>(), rms, 1e-9 * rms);
  expectRelative(values(sent->K), K.reshape(1, 9), "K");
  expectRelative(sent->D, D.reshape(1, int(D.total())), "D");
  cv::Mat P = cv::Mat::zeros(3, 4, CV_64F);
  cv::getOptimalNewCameraMatrix(K, D, size, 0.0).copyTo(P.colRange(0, 3));  // as ROS's cameracalibrator, alpha 0
  expectRelative(values(sent->P), P.reshape(1, 12), "P");
  EXPECT_EQ(sent->R, (boost::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_TRUE(sent->width == 640 && sent->height == 480 && sent->distortion_model == "plumb_bob");

  // the file: camera_calibration_parsers reads back what was sent
  CameraInfo back;
  std::string name;
  ASSERT_TRUE(camera_calibration_parsers::readCalibration(file, name, back));
  EXPECT_EQ(name, "left_camera");
  back.header = sent->header;  // a file has none
  EXPECT_EQ(back, *sent);

  // near OpenCV's own calibration of the sequence (its calibration sample, other corner settings)
  cv::FileStorage opencv(kData + "/left_intrinsics.yml", cv::FileStorage::READ);
  cv::Mat theirs;
  opencv["camera_matrix"] >> theirs;
  std::cout << "K: " << cv::Matx33d(sent->K.data()) << "\nleft_intrinsics.yml: " << theirs << "\nRMS " << rms << " px\n";
  for (int i : {0, 2, 4, 5}) EXPECT_NEAR(sent->K[i], theirs.at<double>(i), 0.01 * theirs.at<double>(i)) << "K[" << i << "]";
}

TEST(StereoNodes, CameraCalibrationNeedsThreeViewsAndWritesItsFileWholeOrNotAtAll) {
  const auto images = chessboards();
  NodeHarness h("apex_nodes/CameraCalibration", {"corners"}, "camera_info");
  auto* sink = object<Collector>(h.graph(), "sink");
  const auto calibrate = [&] {
    EXPECT_TRUE(h.graph().fireSlot("node", "calibrate"));
    EXPECT_TRUE(h.graph().waitIdle(kWait));
  };
  EXPECT_TRUE(h.run<Corners>(cornersOf(*images[0])).isNothing());  // kept: a sink until calibrated
  EXPECT_TRUE(h.run<Corners>(cornersOf(*images[1])).isNothing());
  auto unseen = std::make_shared<Corners>();  // the board not in the frame: skipped
  unseen->image_size = cv::Size(640, 480), unseen->pattern_size = cv::Size(9, 6);
  EXPECT_TRUE(h.run<Corners>(unseen).isNothing());
  EXPECT_EQ(h.error(), "");
  calibrate();
  EXPECT_THAT(h.error(), HasSubstr("needs at least 3 views of the board to calibrate, has 2"));

  auto other = std::make_shared<Corners>(*cornersOf(*images[2]));  // another board
  other->pattern_size = cv::Size(6, 9);
  EXPECT_TRUE(h.run<Corners>(other).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("a view of a 6x9 pattern in a 640x480 image does not fit the 2 kept"));
  EXPECT_TRUE(h.run<Corners>(cornersOf(*images[2])).isNothing());

  // files it cannot write: an error naming the file, which stays as it was (or absent)
  const std::string dir = ::testing::TempDir() + "/apex_test_calibration_files";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string kept = dir + "/read_only.yaml";
  std::ofstream(kept) << "old\n";
  fs::permissions(kept, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const std::size_t before = sink->size();
  h.set("output_file", kept);
  calibrate();
  EXPECT_THAT(h.error(), HasSubstr("cannot write '" + kept + "'"));
  std::string text;
  EXPECT_TRUE(std::getline(std::ifstream(kept), text) && text == "old");
  const std::string missing = dir + "/no_such_folder/camera.yaml";
  h.set("output_file", missing);
  calibrate();
  EXPECT_THAT(h.error(), HasSubstr("cannot write '" + missing + "'"));
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path().filename().string());
  EXPECT_EQ(files, std::vector<std::string>{"read_only.yaml"});  // no temporary left behind
  EXPECT_EQ(sink->size(), before);  // nor a model sent

  const std::string good = dir + "/camera.yaml";
  h.set("output_file", good);
  calibrate();
  ASSERT_TRUE(sink->waitFor(before + 1));
  const auto sent = sink->messages().back().as<CameraInfo>();
  ASSERT_TRUE(sent) << h.error();
  CameraInfo back;
  std::string name;
  ASSERT_TRUE(camera_calibration_parsers::readCalibration(good, name, back));
  back.header = sent->header;
  EXPECT_EQ(back, *sent);

  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));
  calibrate();
  EXPECT_THAT(h.error(), HasSubstr("has 0"));
  fs::remove_all(dir);
}

/** aloe's left ("L") or right ("R") image at half size, as OpenCV's stereo_match.py takes it. */
std::shared_ptr<Image> aloe(const std::string& side) {
  auto image = imageFile("aloe" + side + ".jpg", side == "L" ? "left_camera" : "right_camera", 7);
  cv::pyrDown(image->mat, image->mat);
  return image;
}

/** Disparities 16..111 at half size (stereo_match.py's range); 5 x 5 blocks. */
const std::vector<std::pair<std::string, std::string>> kAloeSettings = {
    {"min_disparity", "16"}, {"num_disparities", "96"}, {"block_size", "5"}};

cv::Mat grayOf(const Image& image) {
  cv::Mat gray;
  cv::cvtColor(image.mat, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

/** OpenCV's fixed-point disparity as StereoMatcher sends it: pixels, NaN where no match. */
cv::Mat pixels(const cv::Mat& fixed, int min_disparity) {
  cv::Mat out;
  fixed.convertTo(out, CV_32F, 1.0 / 16);
  out.setTo(std::numeric_limits<float>::quiet_NaN(), fixed < min_disparity * 16);
  return out;
}

/** Pixels where a and b differ (NaN equals NaN). */
int differing(const cv::Mat& a, const cv::Mat& b) {
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a.type(), CV_32FC1);
  int n = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) {
      const float p = a.at<float>(y, x), q = b.at<float>(y, x);
      n += !(p == q || (std::isnan(p) && std::isnan(q)));
    }
  return n;
}

/** Of the pixels the ground truth knows: the share wrong by over 1 pixel or without a match, and
 *  the share without a match. The truth is at full size: its pixel (2x, 2y), halved. */
std::pair<double, double> wrongShare(const cv::Mat& disparity) {
  const cv::Mat truth = cv::imread(kData + "/aloeGT.png", cv::IMREAD_GRAYSCALE);
  int known = 0, wrong = 0, unmatched = 0;
  for (int y = 0; y < disparity.rows; ++y)
    for (int x = 0; x < disparity.cols; ++x) {
      const int t = truth.at<std::uint8_t>(2 * y, 2 * x);
      if (t == 0) continue;
      const float d = disparity.at<float>(y, x);
      ++known;
      unmatched += std::isnan(d);
      wrong += std::isnan(d) || std::abs(d - t / 2.0) > 1;
    }
  return {double(wrong) / known, double(unmatched) / known};
}

Message match(NodeHarness& h, const std::shared_ptr<Image>& left, const std::shared_ptr<Image>& right) {
  return h.run({Message::share<Image>(left), Message::share<Image>(right)});
}

TEST(StereoNodes, StereoMatcherEqualsStereoSgbmAndBmOnAloe) {
  const auto left = aloe("L"), right = aloe("R");
  NodeHarness h("apex_nodes/StereoMatcher", {"left", "right"}, "disparity", kAloeSettings);
  const Message m = match(h, left, right);
  ASSERT_TRUE(m.as<Image>()) << h.error();
  const Image& got = *m.as<Image>();
  EXPECT_EQ(got.encoding, "32FC1");
  EXPECT_EQ(got.header, left->header);
  cv::Mat want;  // p1, p2 = 0: OpenCV's sample's 8 and 32 x block_size² (one channel)
  cv::StereoSGBM::create(16, 96, 5, 8 * 25, 32 * 25, 1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM)
      ->compute(grayOf(*left), grayOf(*right), want);
  EXPECT_EQ(differing(got.mat, pixels(want, 16)), 0);
  const auto [node_share, node_unmatched] = wrongShare(got.mat);
  const auto [opencv_share, opencv_unmatched] = wrongShare(pixels(want, 16));
  std::cout << "aloe, half size, SGBM: " << 100 * node_share << "% of the ground truth's pixels wrong by over 1 px or unmatched ("
            << 100 * node_unmatched << "% unmatched); cv::StereoSGBM: " << 100 * opencv_share << "%\n";
  EXPECT_EQ(node_share, opencv_share);
  EXPECT_NEAR(node_share, 0.317, 0.005);  // 26.6% unmatched (17.5% of the width is left of the search range)

  h.set("invalid", "opencv");  // OpenCV's min_disparity - 1, divided by 16 like the rest
  cv::Mat opencv_float;
  want.convertTo(opencv_float, CV_32F, 1.0 / 16);
  EXPECT_EQ(differing(match(h, left, right).as<Image>()->mat, opencv_float), 0);

  h.set("invalid", "nan");
  h.set("algorithm", "bm");
  h.set("block_size", "15");
  auto bm = cv::StereoBM::create(96, 15);
  bm->setMinDisparity(16), bm->setPreFilterCap(31), bm->setTextureThreshold(10), bm->setUniquenessRatio(10);
  bm->setSpeckleWindowSize(100), bm->setSpeckleRange(32), bm->setDisp12MaxDiff(1);
  bm->compute(grayOf(*left), grayOf(*right), want);
  const Message by_bm = match(h, left, right);
  ASSERT_TRUE(by_bm.as<Image>()) << h.error();
  EXPECT_EQ(differing(by_bm.as<Image>()->mat, pixels(want, 16)), 0);
  std::cout << "aloe, half size, BM: " << 100 * wrongShare(by_bm.as<Image>()->mat).first << "% wrong or unmatched\n";

  h.set("block_size", "3");
  EXPECT_TRUE(match(h, left, right).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("bm needs a block_size of at least 5, got 3"));
  h.set("block_size", "15");
  auto small = std::make_shared<Image>(*right);
  cv::resize(right->mat, small->mat, cv::Size(320, 240));
  EXPECT_TRUE(match(h, left, small).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the left image is 641x555, the right image 320x240"));
}

constexpr double kFx = 700, kFy = 702.5, kCx = 320.5, kCy = 277.25, kBaseline = 0.16;  // a made-up camera

CameraInfo madeUpCamera(const std_msgs::Header& header, double tx) {
  CameraInfo c;
  c.header = header;
  c.width = 641, c.height = 555, c.distortion_model = "plumb_bob";
  c.D = {0, 0, 0, 0, 0};
  c.K = {kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1};
  c.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c.P = {kFx, 0, kCx, tx, 0, kFy, kCy, 0, 0, 0, 1, 0};
  return c;
}

TEST(StereoNodes, DisparityToCloudProjectsEachValidDisparity) {
  const auto left = aloe("L"), right = aloe("R");
  NodeHarness matcher("apex_nodes/StereoMatcher", {"left", "right"}, "disparity", kAloeSettings);
  const Message disparity = match(matcher, left, right);
  ASSERT_TRUE(disparity.as<Image>()) << matcher.error();
  const cv::Mat d = disparity.as<Image>()->mat;
  const Message info = Message::make(madeUpCamera(left->header, 0));
  std::vector<cv::Point> valid;  // row by row, as the cloud lists its points
  for (int v = 0; v < d.rows; ++v)
    for (int u = 0; u < d.cols; ++u)
      if (std::isfinite(d.at<float>(v, u)) && d.at<float>(v, u) > 0) valid.emplace_back(u, v);

  NodeHarness h("apex_nodes/DisparityToCloud", {"disparity", "image", "camera_info"}, "cloud",
                {{"baseline", std::to_string(kBaseline)}});
  const Message m = h.run({disparity, Message::share<Image>(left), info});
  ASSERT_TRUE(m.as<Cloud>()) << h.error();
  EXPECT_EQ(m.as<Cloud>()->header, left->header);
  const auto points = apex_nodes::typedPoints<pcl::PointXYZRGB>(*m.as<Cloud>());
  ASSERT_EQ(points.size(), valid.size());
  EXPECT_EQ(points.height, 1u);
  double worst = 0;
  int colours = 0;
  for (std::size_t i = 0; i < valid.size(); ++i) {
    const int u = valid[i].x, v = valid[i].y;
    const double z = kFx * kBaseline / d.at<float>(v, u), x = (u - kCx) * z / kFx, y = (v - kCy) * z / kFy;
    const pcl::PointXYZRGB& p = points[i];
    worst = std::max({worst, std::abs(p.x - x) / z, std::abs(p.y - y) / z, std::abs(p.z - z) / z});
    const cv::Vec3b bgr = left->mat.at<cv::Vec3b>(v, u);
    colours += p.r == bgr[2] && p.g == bgr[1] && p.b == bgr[0];
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(colours, int(valid.size()));
  const auto& middle = points[valid.size() / 2];
  std::cout << valid.size() << " points; pixel " << valid[valid.size() / 2] << " at (" << middle.x << ", " << middle.y << ", "
            << middle.z << ") m\n";

  // the baseline from the right camera's P: Tx = -fx B
  NodeHarness stereo("apex_nodes/DisparityToCloud", {"disparity", "image", "camera_info", "right_camera_info"}, "cloud");
  const Message from_right =
      stereo.run({disparity, Message::share<Image>(left), info, Message::make(madeUpCamera(right->header, -kFx * kBaseline))});
  ASSERT_TRUE(from_right.as<Cloud>()) << stereo.error();
  const auto same = apex_nodes::typedPoints<pcl::PointXYZRGB>(*from_right.as<Cloud>());
  ASSERT_EQ(same.size(), points.size());
  for (std::size_t i = 0; i < same.size(); i += 997) EXPECT_NEAR(same[i].z, points[i].z, 1e-6 * points[i].z);

  // organized, without colour: a point per pixel, NaN where none, white
  NodeHarness grid("apex_nodes/DisparityToCloud", {"disparity", "camera_info"}, "cloud",
                   {{"baseline", std::to_string(kBaseline)}, {"organized", "true"}});
  const Message organized = grid.run({disparity, info});
  ASSERT_TRUE(organized.as<Cloud>()) << grid.error();
  const auto all = apex_nodes::typedPoints<pcl::PointXYZRGB>(*organized.as<Cloud>());
  EXPECT_TRUE(all.width == 641 && all.height == 555);
  std::size_t nan = 0;
  for (const auto& p : all) nan += std::isnan(p.z);
  EXPECT_EQ(nan, d.total() - valid.size());
  EXPECT_EQ(all.at(valid[0].x, valid[0].y).z, points[0].z);
  EXPECT_TRUE(all[0].r == 255 && all[0].g == 255 && all[0].b == 255);

  // refused: no baseline; not a disparity image
  NodeHarness bare("apex_nodes/DisparityToCloud", {"disparity", "camera_info"}, "cloud");
  EXPECT_TRUE(bare.run({disparity, info}).isNothing());
  EXPECT_THAT(bare.error(), HasSubstr("no baseline: set 'baseline' (metres) or connect right_camera_info"));
  bare.set("baseline", "0.16");
  auto mono = std::make_shared<Image>(*left);
  mono->encoding = "mono8", mono->mat = grayOf(*left);
  EXPECT_TRUE(bare.run({Message::share<Image>(mono), info}).isNothing());
  EXPECT_THAT(bare.error(), HasSubstr("disparity image encoding 'mono8' (OpenCV type 0) is not 32FC1"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
