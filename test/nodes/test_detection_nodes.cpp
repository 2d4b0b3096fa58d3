// Detection nodes against the same OpenCV calls made directly, on opencv-doc's images: Hough lines
// (sudoku.png) and circles (smarties.png), a template cut from messi5.jpg, faces (messi5.jpg),
// people (basketball1.png), a chessboard (left01.jpg), and codes OpenCV drew pasted into them.
#include <gmock/gmock.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include "apex_nodes/shapes.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using namespace apex_nodes;  // Image, Regions and the shapes
using ::testing::HasSubstr;

namespace {

const std::string kFaces = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";  // opencv-data

template <class T>
std::shared_ptr<const T> result(NodeHarness& h, const Message& m) {
  auto p = m.as<T>();
  if (!p) {
    ADD_FAILURE() << "the node sent " << m.typeName() << ": " << h.error();
    return p;
  }
  expectCameraHeader(p->header);  // the frame's header, kept
  return p;
}

std::vector<cv::Rect> boxes(const Regions& r) {
  std::vector<cv::Rect> out;
  for (const auto& region : r.regions) out.push_back(region.box);
  return out;
}

TEST(DetectionNodes, HoughLinesMatchesOpenCV) {
  cv::Mat edges;
  cv::Canny(readGrayData("sudoku.png"), edges, 50, 200);
  NodeHarness h("apex_nodes/HoughLines", {"image"}, "lines");
  h.set("rho", "1"), h.set("theta", "1"), h.set("threshold", "50"), h.set("min_line_length", "50"), h.set("max_line_gap", "10");
  const auto got = result<Lines>(h, h.run(imageOf(edges, "mono8")));
  ASSERT_TRUE(got);
  std::vector<cv::Vec4i> want;
  cv::HoughLinesP(edges, want, 1, CV_PI / 180, 50, 50, 10);
  ASSERT_EQ(got->lines.size(), want.size());
  EXPECT_GT(want.size(), 10u);  // the grid
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(got->lines[i], cv::Vec4f(want[i])) << i;
  EXPECT_EQ(got->image_size, edges.size());
}

std::vector<cv::Vec3f> sorted(std::vector<cv::Vec3f> v) {
  std::sort(v.begin(), v.end(), [](const cv::Vec3f& a, const cv::Vec3f& b) {
    return std::lexicographical_compare(a.val, a.val + 3, b.val, b.val + 3);
  });
  return v;
}

TEST(DetectionNodes, HoughCirclesMatchesOpenCV) {
  cv::Mat gray;
  cv::medianBlur(readGrayData("smarties.png"), gray, 5);
  NodeHarness h("apex_nodes/HoughCircles", {"image"}, "circles");
  h.set("min_dist", "22.25"), h.set("param1", "100"), h.set("param2", "30"), h.set("min_radius", "1"), h.set("max_radius", "30");
  auto got = result<Circles>(h, h.run(imageOf(gray, "mono8")));
  ASSERT_TRUE(got);
  std::vector<cv::Vec3f> want;
  cv::HoughCircles(gray, want, cv::HOUGH_GRADIENT, 1, 22.25, 100, 30, 1, 30);
  EXPECT_EQ(sorted(got->circles), sorted(want));
  EXPECT_GE(want.size(), 10u);  // the sweets

  h.set("method", "gradient_alt"), h.set("dp", "1.5"), h.set("param1", "300"), h.set("param2", "0.9");
  got = result<Circles>(h, h.run(imageOf(gray, "mono8")));
  ASSERT_TRUE(got);
  cv::HoughCircles(gray, want, cv::HOUGH_GRADIENT_ALT, 1.5, 22.25, 300, 0.9, 1, 30);
  EXPECT_EQ(sorted(got->circles), sorted(want));
  EXPECT_GE(want.size(), 10u);
  h.set("param2", "30");
  EXPECT_TRUE(h.run(imageOf(gray, "mono8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("gradient_alt takes param2 within 0..1"));
}

TEST(DetectionNodes, TemplateMatchFindsTheBestPlacesAsOpenCV) {
  const cv::Mat frame = readData("messi5.jpg");
  const cv::Mat templ = frame(cv::Rect(244, 62, 85, 85)).clone();  // the face
  NodeHarness h("apex_nodes/TemplateMatch", {"image", "template"}, "regions");
  const std::vector<Message> in{Message::share<Image>(imageOf(frame, "bgr8")), Message::share<Image>(imageOf(templ, "bgr8"))};
  auto got = result<Regions>(h, h.run(in));
  ASSERT_TRUE(got);
  cv::Mat scores;
  cv::matchTemplate(frame, templ, scores, cv::TM_CCOEFF_NORMED);
  double best = 0;
  cv::Point at;
  cv::minMaxLoc(scores, nullptr, &best, nullptr, &at);
  ASSERT_EQ(got->regions.size(), 1u);
  EXPECT_EQ(got->regions[0].box, cv::Rect(at, templ.size()));
  EXPECT_EQ(at, cv::Point(244, 62));
  EXPECT_DOUBLE_EQ(got->regions[0].confidence, best);
  EXPECT_EQ(got->image_size, frame.size());

  h.set("max_matches", "4"), h.set("threshold", "0"), h.set("method", "sqdiff");
  got = result<Regions>(h, h.run(in));
  ASSERT_TRUE(got);
  ASSERT_EQ(got->regions.size(), 4u);
  cv::matchTemplate(frame, templ, scores, cv::TM_SQDIFF);
  cv::minMaxLoc(scores, nullptr, nullptr, &at);
  EXPECT_EQ(got->regions[0].box.tl(), at);  // sqdiff: the least is the best
  EXPECT_NEAR(got->regions[0].confidence, 1.0, 1e-6);  // scaled over the frame: the best is 1
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      EXPECT_TRUE((got->regions[i].box & got->regions[j].box).empty()) << i << " " << j;
      EXPECT_GE(got->regions[i].confidence, got->regions[j].confidence);
    }

  NodeHarness s("apex_nodes/TemplateMatch", {"image", "template"}, "scores");
  const auto raw = result<Image>(s, s.run(in));
  ASSERT_TRUE(raw);
  cv::matchTemplate(frame, templ, scores, cv::TM_CCOEFF_NORMED);
  EXPECT_EQ(raw->encoding, "32FC1");
  ASSERT_EQ(raw->mat.size(), scores.size());
  EXPECT_EQ(cv::norm(raw->mat, scores, cv::NORM_INF), 0);

  cv::Mat gray;
  cv::cvtColor(templ, gray, cv::COLOR_BGR2GRAY);
  EXPECT_TRUE(h.run({in[0], Message::share<Image>(imageOf(gray, "mono8"))}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the template ('mono8', 1 channels) is not of the image's type ('bgr8', 3 channels)"));
  EXPECT_TRUE(h.run({Message::share<Image>(imageOf(templ, "bgr8")), in[0]}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the template (548x342) is larger than the image (85x85)"));
}

TEST(DetectionNodes, TemplateMatchTurnsAnRgbTemplateWithoutWritingIt) {
  const cv::Mat frame = readData("messi5.jpg");
  cv::Mat rgb;
  cv::cvtColor(frame(cv::Rect(244, 62, 85, 85)), rgb, cv::COLOR_BGR2RGB);  // the face, as rgb8
  const cv::Mat before = rgb.clone();
  NodeHarness h("apex_nodes/TemplateMatch", {"image", "template"}, "regions");
  h.set("max_matches", "3"), h.set("threshold", "0");
  const std::vector<Message> in{Message::share<Image>(imageOf(frame, "bgr8")), Message::share<Image>(imageOf(rgb, "rgb8"))};
  const auto first = result<Regions>(h, h.run(in));
  ASSERT_TRUE(first);
  expectSameMat(rgb, before);  // the template message's pixels (rgb shares them): as they were
  const auto second = result<Regions>(h, h.run(in));  // the same messages: the same matches
  ASSERT_TRUE(second);
  ASSERT_EQ(first->regions.size(), 3u);
  ASSERT_EQ(second->regions.size(), 3u);
  EXPECT_EQ(first->regions[0].box, cv::Rect(244, 62, 85, 85));  // found in the image's channel order
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(second->regions[i].box, first->regions[i].box) << i;
    EXPECT_EQ(second->regions[i].confidence, first->regions[i].confidence) << i;
  }
}

TEST(DetectionNodes, CascadeDetectorFindsFacesAsOpenCV) {
  const cv::Mat frame = readData("messi5.jpg");
  NodeHarness h("apex_nodes/CascadeDetector", {"image"}, "regions");
  auto got = result<Regions>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  cv::Mat gray;
  cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  cv::equalizeHist(gray, gray);
  cv::CascadeClassifier faces(kFaces);
  ASSERT_FALSE(faces.empty()) << "cannot read " << kFaces << ": is opencv-data installed?";
  std::vector<cv::Rect> want;
  faces.detectMultiScale(gray, want, 1.1, 3, 0, cv::Size(), cv::Size());
  EXPECT_EQ(boxes(*got), want);
  EXPECT_GE(want.size(), 1u);

  h.set("scale_factor", "1.2"), h.set("min_neighbors", "5"), h.set("min_size", "[60, 60]"), h.set("equalize_hist", "false");
  got = result<Regions>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  faces.detectMultiScale(gray, want, 1.2, 5, 0, cv::Size(60, 60), cv::Size());
  EXPECT_EQ(boxes(*got), want);
}

TEST(DetectionNodes, CascadeDetectorNamesAFileItCannotRead) {
  NodeHarness h("apex_nodes/CascadeDetector", {"image"}, "regions");
  const auto frame = readDataImage("messi5.jpg");
  h.set("cascade", "/nonexistent/cascade.xml");
  EXPECT_TRUE(h.run(frame).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot read the cascade '/nonexistent/cascade.xml'"));
  h.set("cascade", kOpenCvData + "/left_intrinsics.yml");  // OpenCV's format, not a cascade
  EXPECT_TRUE(h.run(frame).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the cascade '" + kOpenCvData + "/left_intrinsics.yml' is not a cascade classifier"));
  const std::string damaged = ::testing::TempDir() + "/apex_test_damaged_cascade.xml";
  {
    std::ifstream whole(kFaces);
    std::string text((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
    std::ofstream(damaged) << text.substr(0, text.size() / 2);  // cut off in the middle
  }
  h.set("cascade", damaged);
  EXPECT_TRUE(h.run(frame).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the cascade '" + damaged + "' is not a cascade classifier"));
  h.set("cascade", kFaces);  // a good one again: the node runs on
  EXPECT_FALSE(h.run(frame).isNothing());
  EXPECT_EQ(h.error(), "");
  std::remove(damaged.c_str());
}

TEST(DetectionNodes, HOGPeopleDetectorMatchesOpenCV) {
  const cv::Mat frame = readData("basketball1.png");
  NodeHarness h("apex_nodes/HOGPeopleDetector", {"image"}, "regions");
  const auto got = result<Regions>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  cv::HOGDescriptor hog;
  hog.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
  std::vector<cv::Rect> want;
  std::vector<double> weights;
  hog.detectMultiScale(frame, want, weights, 0, cv::Size(8, 8), cv::Size(), 1.05, 2, false);
  EXPECT_EQ(boxes(*got), want);
  ASSERT_GE(want.size(), 1u);  // the player on the right
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_DOUBLE_EQ(got->regions[i].confidence, 1 / (1 + std::exp(-weights[i])));
    EXPECT_EQ(got->regions[i].label, 0);
  }
}

TEST(DetectionNodes, QRCodeDetectorFindsACodeAsOpenCV) {
  cv::Mat code, big, frame = readData("messi5.jpg");
  cv::QRCodeEncoder::create()->encode("APEX node test", code);
  cv::resize(code, big, cv::Size(), 6, 6, cv::INTER_NEAREST);
  cv::copyMakeBorder(big, big, 24, 24, 24, 24, cv::BORDER_CONSTANT, cv::Scalar(255));
  cv::cvtColor(big, big, cv::COLOR_GRAY2BGR);
  big.copyTo(frame(cv::Rect(cv::Point(300, 100), big.size())));
  NodeHarness h("apex_nodes/QRCodeDetector", {"image"}, "regions");
  const auto got = result<Regions>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  cv::Mat gray;
  cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  ASSERT_TRUE(cv::QRCodeDetector().detect(gray, corners));
  ASSERT_EQ(got->regions.size(), 1u);
  EXPECT_EQ(got->regions[0].box, cv::boundingRect(corners));
  EXPECT_TRUE(cv::Rect(300, 100, big.cols, big.rows).contains(cv::Point(got->regions[0].centroid)));
  EXPECT_DOUBLE_EQ(got->regions[0].area, cv::contourArea(corners));

  // The text: what OpenCV reads ("" from a build without a decoder, as Debian's).
  NodeHarness t("apex_nodes/QRCodeDetector", {"image"}, "text");
  const auto text = t.run(imageOf(frame, "bgr8")).as<std::string>();
  ASSERT_TRUE(text) << t.error();
  const std::string want = cv::QRCodeDetector().detectAndDecode(gray);
  EXPECT_EQ(*text, want);
  if (!want.empty()) {
    EXPECT_EQ(want, "APEX node test");
  }
  EXPECT_EQ(*t.run(imageOf(cv::Mat(200, 200, CV_8UC1, cv::Scalar(128)), "mono8")).as<std::string>(), "");  // no code
  EXPECT_TRUE(result<Regions>(h, h.run(imageOf(cv::Mat(200, 200, CV_8UC1, cv::Scalar(128)), "mono8")))->regions.empty());
}

TEST(DetectionNodes, ArucoDetectorFindsMarkersAndPosesAsOpenCV) {
  cv::Mat frame = readData("left01.jpg");  // 640x480, as its calibration
  const auto dictionary = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50);
  for (const auto& [id, at] : std::vector<std::pair<int, cv::Point>>{{7, {20, 20}}, {23, {480, 320}}}) {
    cv::Mat marker;
    cv::aruco::drawMarker(dictionary, id, 120, marker);
    cv::rectangle(frame, cv::Rect(at.x - 15, at.y - 15, 150, 150), cv::Scalar::all(255), cv::FILLED);  // its white margin
    cv::cvtColor(marker, marker, cv::COLOR_GRAY2BGR);
    marker.copyTo(frame(cv::Rect(at, cv::Size(120, 120))));
  }
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(frame, dictionary, corners, ids, cv::aruco::DetectorParameters::create());
  ASSERT_EQ(ids.size(), 2u);

  NodeHarness h("apex_nodes/ArucoDetector", {"image"}, "markers");
  const auto got = result<Markers>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  EXPECT_EQ(got->ids, ids);
  EXPECT_EQ(got->corners, corners);
  EXPECT_EQ(got->dictionary, "4x4_50");
  EXPECT_TRUE(got->rvecs.empty());  // no camera model: no poses

  sensor_msgs::CameraInfo camera;
  camera.header.frame_id = "camera", camera.width = 640, camera.height = 480, camera.distortion_model = "plumb_bob";
  cv::FileStorage fs(kOpenCvData + "/left_intrinsics.yml", cv::FileStorage::READ);
  cv::Mat K, D;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  std::copy(K.begin<double>(), K.end<double>(), camera.K.begin());
  camera.D.assign(D.begin<double>(), D.end<double>());
  NodeHarness posed("apex_nodes/ArucoDetector", {"image", "camera_info"}, "markers");
  posed.set("marker_length", "0.08");
  const auto with = result<Markers>(posed, posed.run({Message::share<Image>(imageOf(frame, "bgr8")), Message::make(camera)}));
  ASSERT_TRUE(with);
  std::vector<cv::Vec3d> rvecs, tvecs;
  cv::aruco::estimatePoseSingleMarkers(corners, 0.08f, K, D, rvecs, tvecs);
  ASSERT_EQ(with->tvecs.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LT(cv::norm(with->rvecs[i] - rvecs[i]), 1e-9) << i;
    EXPECT_LT(cv::norm(with->tvecs[i] - tvecs[i]), 1e-9) << i;
    EXPECT_GT(with->tvecs[i][2], 0.1) << i;  // in front of the camera
  }
  camera.width = 320;  // a model for another image
  EXPECT_TRUE(posed.run({Message::share<Image>(imageOf(frame, "bgr8")), Message::make(camera)}).isNothing());
  EXPECT_THAT(posed.error(), HasSubstr("is not for an image of 640x480"));
}

TEST(DetectionNodes, ChessboardCornersMatchesOpenCV) {
  const cv::Mat frame = readData("left01.jpg");
  NodeHarness h("apex_nodes/ChessboardCorners", {"image"}, "corners");
  auto got = result<Corners>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  std::vector<cv::Point2f> want;
  ASSERT_TRUE(
      cv::findChessboardCorners(frame, cv::Size(9, 6), want, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE));
  cv::Mat gray;
  cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  cv::cornerSubPix(gray, want, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  EXPECT_TRUE(got->found);
  EXPECT_EQ(got->pattern_size, cv::Size(9, 6));
  EXPECT_EQ(got->corners, want);
  ASSERT_EQ(want.size(), 54u);

  h.set("pattern_columns", "7"), h.set("pattern_rows", "7");  // not this board: found = false, not an error
  got = result<Corners>(h, h.run(imageOf(frame, "bgr8")));
  ASSERT_TRUE(got);
  EXPECT_FALSE(got->found);
  EXPECT_TRUE(got->corners.empty());
  EXPECT_EQ(h.error(), "");
}

TEST(DetectionNodes, DetectorsNameTheImagesTheyCannotTake) {
  cv::Mat deep(64, 64, CV_16UC1, cv::Scalar(1000)), two(64, 64, CV_8UC2, cv::Scalar(1, 2));
  const std::vector<std::pair<std::string, std::string>> types{
      {"apex_nodes/HoughLines", "lines"},         {"apex_nodes/HoughCircles", "circles"},
      {"apex_nodes/CascadeDetector", "regions"},  {"apex_nodes/HOGPeopleDetector", "regions"},
      {"apex_nodes/QRCodeDetector", "regions"},   {"apex_nodes/ArucoDetector", "markers"},
      {"apex_nodes/ChessboardCorners", "corners"}};
  for (const auto& [type, output] : types) {
    NodeHarness h(type, {"image"}, output);
    EXPECT_TRUE(h.run(imageOf(deep, "mono16")).isNothing()) << type;
    EXPECT_THAT(h.error(), HasSubstr("needs an 8-bit image, got 'mono16'")) << type;
    EXPECT_TRUE(h.run(imageOf(two, "yuv422")).isNothing()) << type;
    EXPECT_THAT(h.error(), HasSubstr("cannot handle 2-channel images (encoding 'yuv422'); needs ")) << type;
    EXPECT_TRUE(h.run(imageOf(cv::Mat(), "bgr8")).isNothing()) << type;
    EXPECT_THAT(h.error(), HasSubstr("received an empty image")) << type;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  cv::setNumThreads(1);  // the detectors' parallel loops collect hits in any order: one thread, one order
  return RUN_ALL_TESTS();
}
