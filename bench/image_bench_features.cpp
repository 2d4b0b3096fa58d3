// apex_bench_images' cases of the features, motion and detection nodes: each node against the
// OpenCV calls it makes (image_bench.cpp has the table). Inputs the 640x480 frames do not give
// (a second view, markers, a face, a chessboard) come from opencv-doc's other images, or are
// drawn into the frame.
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <opencv2/video/tracking.hpp>

#include "apex_nodes/features.hpp"
#include "apex_nodes/shapes.hpp"
#include "image_cases.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Keypoints;
using apex_nodes::Matches;
using apex_nodes::Regions;

/** ORB's keypoints and descriptors of an image, as the Keypoints node sends them. */
std::shared_ptr<const Keypoints> orbOf(const cv::Mat& gray) {
  auto k = std::make_shared<Keypoints>();
  k->header.frame_id = "camera";
  k->image_size = gray.size();
  k->method = "orb";
  k->norm_type = cv::NORM_HAMMING;
  cv::ORB::create(500)->detectAndCompute(gray, cv::noArray(), k->keypoints, k->descriptors);
  return k;
}

/** An image of opencv-doc's as gray, or empty. */
cv::Mat grayFile(const std::string& name) { return cv::imread(kData + "/" + name, cv::IMREAD_GRAYSCALE); }

std::vector<NodeCase> matchingCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const cv::Mat box = grayFile("box.png"), scene = grayFile("box_in_scene.png");
  if (box.empty() || scene.empty()) {
    for (const char* t : {"MatchDescriptors", "FindHomography", "DrawMatches"})
      c.push_back(notMeasured(t, "", "", "box.png or box_in_scene.png (opencv-doc) cannot be read"));
    return c;
  }
  const auto query = orbOf(box), train = orbOf(scene);
  auto matches = std::make_shared<Matches>();
  matches->query = query, matches->train = train;
  cv::BFMatcher(cv::NORM_HAMMING).match(query->descriptors, train->descriptors, matches->matches);
  const std::string words = "ORB 500 of box.png, box_in_scene.png";
  c.push_back(fixedCase("MatchDescriptors", "apex_nodes/MatchDescriptors", words, feedType<Keypoints, Keypoints>(),
                        {"query", "train"}, {msg(query), msg(train)}, {}, "matches", sinkType<Matches>(),
                        "BFMatcher Hamming: match", [query, train, out = std::vector<cv::DMatch>()]() mutable {
                          cv::BFMatcher(cv::NORM_HAMMING).match(query->descriptors, train->descriptors, out);
                        }));
  c.push_back(fixedCase(
      "FindHomography", "apex_nodes/FindHomography", std::to_string(matches->matches.size()) + " matches of those",
      feedType<Matches>(), {"matches"}, {msg(matches)}, {{"method", "ransac"}, {"ransac_reproj_threshold", "3"}}, "homography",
      sinkType<apex_nodes::Homography>(), "the matches' points, findHomography RANSAC 3",
      [matches, from = std::vector<cv::Point2f>(), to = std::vector<cv::Point2f>(), mask = std::vector<uchar>()]() mutable {
        from.clear(), to.clear();
        for (const auto& d : matches->matches) {
          from.push_back(matches->query->keypoints[d.queryIdx].pt);
          to.push_back(matches->train->keypoints[d.trainIdx].pt);
        }
        cv::Mat h = cv::findHomography(from, to, cv::RANSAC, 3, mask);
      }));
  c.push_back(fixedCase("DrawMatches", "apex_nodes/DrawMatches", "the two images (mono8) and their matches",
                        feedType<Image, Image, Matches>(), {"query_image", "train_image", "matches"},
                        {msg(image(box, "mono8")), msg(image(scene, "mono8")), msg(matches)}, {}, "image", sinkType<Image>(),
                        "drawMatches", [box, scene, matches, out = cv::Mat()]() mutable {
                          cv::drawMatches(box, matches->query->keypoints, scene, matches->train->keypoints, matches->matches, out,
                                          cv::Scalar(0, 255, 0), cv::Scalar(255, 0, 0));
                        }));
  const auto keypoints = orbOf(in.gray->mat);
  const cv::Mat bgr = in.bgr->mat;
  c.push_back(fixedCase("DrawKeypoints", "apex_nodes/DrawKeypoints", "bgr8, its ORB 500 keypoints", feedType<Image, Keypoints>(),
                        {"image", "keypoints"}, {msg(in.bgr), msg(keypoints)}, {}, "image", sinkType<Image>(),
                        "copyTo, drawKeypoints over it", [bgr, keypoints, out = cv::Mat()]() mutable {
                          bgr.copyTo(out);
                          cv::drawKeypoints(out, keypoints->keypoints, out, cv::Scalar(0, 255, 0),
                                            cv::DrawMatchesFlags::DRAW_OVER_OUTIMG);
                        }));
  return c;
}

/** A frame-to-frame call on the moving frames: `f(previous gray, this gray)`, both kept. */
std::function<void(const cv::Mat&)> onPairs(std::function<void(const cv::Mat&, const cv::Mat&)> f) {
  return [f = std::move(f), previous = cv::Mat(), gray = cv::Mat()](const cv::Mat& m) mutable {
    cv::cvtColor(m, gray, cv::COLOR_BGR2GRAY);
    if (previous.size() == gray.size()) f(previous, gray);
    std::swap(previous, gray);
  };
}

std::vector<NodeCase> motionCases(const Inputs& in) {
  std::vector<NodeCase> c;
  c.push_back(imageCase("OpticalFlowFarneback", "apex_nodes/OpticalFlowFarneback", "8 bgr8 frames, a patch moving", in.moving,
                        {{"pyr_scale", "0.5"}, {"levels", "3"}, {"winsize", "15"}, {"iterations", "3"}, {"poly_sigma", "1.2"}},
                        "flow", sinkType<Image>(), "cvtColor gray, calcOpticalFlowFarneback 0.5, 3, 15, 3, 5, 1.2",
                        onPairs([flow = cv::Mat()](const cv::Mat& a, const cv::Mat& b) mutable {
                          cv::calcOpticalFlowFarneback(a, b, flow, 0.5, 3, 15, 3, 5, 1.2, 0);
                        })));
  c.push_back(
      imageCase("OpticalFlowLK", "apex_nodes/OpticalFlowLK", "8 bgr8 frames, a patch moving", in.moving,
                {{"max_corners", "200"},
                 {"quality_level", "0.01"},
                 {"min_distance", "10"},
                 {"redetect", "every_frame"},
                 {"win_size", "21"},
                 {"max_level", "3"}},
                "tracks", sinkType<apex_nodes::Tracks>(), "cvtColor gray, goodFeaturesToTrack 200, calcOpticalFlowPyrLK 21, 3",
                onPairs([points = std::vector<cv::Point2f>(), next = std::vector<cv::Point2f>(), status = std::vector<uchar>(),
                         err = std::vector<float>()](const cv::Mat& a, const cv::Mat& b) mutable {
                  cv::goodFeaturesToTrack(a, points, 200, 0.01, 10);
                  if (!points.empty()) cv::calcOpticalFlowPyrLK(a, b, points, next, status, err, cv::Size(21, 21), 3);
                })));
  return c;
}

/** The frame with four 4x4_50 markers (ids 0-3, 96 px, white margins) drawn into it. */
ImagePtr withMarkers(const cv::Mat& bgr) {
  cv::Mat m = bgr.clone(), marker, bordered, colour;
  const auto dict = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50);
  for (int id = 0; id < 4; ++id) {
    cv::aruco::drawMarker(dict, id, 96, marker);
    cv::copyMakeBorder(marker, bordered, 16, 16, 16, 16, cv::BORDER_CONSTANT, cv::Scalar(255));
    cv::cvtColor(bordered, colour, cv::COLOR_GRAY2BGR);
    colour.copyTo(m(cv::Rect(40 + 150 * id, 40 + 80 * (id % 2), bordered.cols, bordered.rows)));
  }
  return image(m, "bgr8");
}

/** The frame with a QR code saying "apex" (8 px modules) drawn into it. */
ImagePtr withQrCode(const cv::Mat& bgr) {
  cv::Mat m = bgr.clone(), code, big, colour;
  cv::QRCodeEncoder::create()->encode("apex", code);
  cv::resize(code, big, cv::Size(), 8, 8, cv::INTER_NEAREST);
  cv::copyMakeBorder(big, big, 32, 32, 32, 32, cv::BORDER_CONSTANT, cv::Scalar(255));
  cv::cvtColor(big, colour, cv::COLOR_GRAY2BGR);
  colour.copyTo(m(cv::Rect(200, 100, colour.cols, colour.rows)));
  return image(m, "bgr8");
}

std::vector<NodeCase> detectorCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const ImagePtr markers = withMarkers(in.bgr->mat);
  c.push_back(imageCase(
      "ArucoDetector", "apex_nodes/ArucoDetector", "bgr8, four 4x4_50 markers drawn in", {markers},
      {{"dictionary", "4x4_50"}, {"corner_refinement", "none"}}, "markers", sinkType<apex_nodes::Markers>(),
      "cvtColor gray, aruco::detectMarkers 4x4_50",
      [dict = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), params = cv::aruco::DetectorParameters::create(),
       gray = cv::Mat(), corners = std::vector<std::vector<cv::Point2f>>(), ids = std::vector<int>()](const cv::Mat& m) mutable {
        cv::cvtColor(m, gray, cv::COLOR_BGR2GRAY);
        cv::aruco::detectMarkers(gray, dict, corners, ids, params);
      }));
  const ImagePtr qr = withQrCode(in.bgr->mat);
  c.push_back(imageCase(
      "QRCodeDetector", "apex_nodes/QRCodeDetector", "bgr8, a QR code drawn in", {qr}, {}, "regions", sinkType<Regions>(),
      "cvtColor gray, QRCodeDetector::detectAndDecode",
      [detector = cv::QRCodeDetector(), gray = cv::Mat(), corners = std::vector<cv::Point2f>()](const cv::Mat& m) mutable {
        cv::cvtColor(m, gray, cv::COLOR_BGR2GRAY);
        volatile std::size_t n = detector.detectAndDecode(gray, corners).size();
        (void)n;
      }));
  const std::string cascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
  auto classifier = std::make_shared<cv::CascadeClassifier>();
  const cv::Mat messi = cv::imread(kData + "/messi5.jpg");
  if (messi.empty() || !classifier->load(cascade)) {
    c.push_back(notMeasured("CascadeDetector", "messi5.jpg", "CascadeClassifier::detectMultiScale",
                            "messi5.jpg (opencv-doc) or " + cascade + " (opencv-data) cannot be read"));
  } else {
    cv::Mat face;
    cv::resize(messi, face, cv::Size(640, 480));
    c.push_back(imageCase(
        "CascadeDetector", "apex_nodes/CascadeDetector", "messi5.jpg scaled to 640x480, bgr8", {image(face, "bgr8")},
        {{"cascade", cascade}, {"scale_factor", "1.1"}, {"min_neighbors", "3"}, {"equalize_hist", "true"}}, "regions",
        sinkType<Regions>(), "cvtColor gray, equalizeHist, detectMultiScale 1.1, 3 (frontal face)",
        [classifier, gray = cv::Mat(), equalized = cv::Mat(), found = std::vector<cv::Rect>()](const cv::Mat& m) mutable {
          cv::cvtColor(m, gray, cv::COLOR_BGR2GRAY);
          cv::equalizeHist(gray, equalized);
          classifier->detectMultiScale(equalized, found, 1.1, 3, 0, cv::Size(), cv::Size());
        }));
  }
  auto hog = std::make_shared<cv::HOGDescriptor>();
  hog->setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
  c.push_back(
      imageCase("HOGPeopleDetector", "apex_nodes/HOGPeopleDetector", "bgr8", {in.bgr},
                {{"hit_threshold", "0"}, {"win_stride", "8"}, {"padding", "0"}, {"scale", "1.05"}, {"group_threshold", "2"}},
                "regions", sinkType<Regions>(), "HOGDescriptor::detectMultiScale, default people SVM, 8, 1.05, 2",
                [hog, found = std::vector<cv::Rect>(), weights = std::vector<double>()](const cv::Mat& m) mutable {
                  hog->detectMultiScale(m, found, weights, 0, cv::Size(8, 8), cv::Size(0, 0), 1.05, 2, false);
                }));
  const cv::Mat board = cv::imread(kData + "/left01.jpg");
  if (board.empty()) {
    c.push_back(
        notMeasured("ChessboardCorners", "left01.jpg", "findChessboardCorners", "left01.jpg (opencv-doc) cannot be read"));
  } else {
    c.push_back(imageCase("ChessboardCorners", "apex_nodes/ChessboardCorners", "left01.jpg, 9x6 board, bgr8",
                          {image(board, "bgr8")},
                          {{"pattern_columns", "9"},
                           {"pattern_rows", "6"},
                           {"refine", "true"},
                           {"refine_window", "11"},
                           {"adaptive_thresh", "true"},
                           {"normalize_image", "true"},
                           {"fast_check", "false"}},
                          "corners", sinkType<apex_nodes::Corners>(), "cvtColor gray, findChessboardCorners 9x6, cornerSubPix 11",
                          [gray = cv::Mat(), corners = std::vector<cv::Point2f>()](const cv::Mat& m) mutable {
                            cv::cvtColor(m, gray, cv::COLOR_BGR2GRAY);
                            if (cv::findChessboardCorners(gray, cv::Size(9, 6), corners,
                                                          cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
                              cv::cornerSubPix(gray, corners, cv::Size(11, 11), cv::Size(-1, -1),
                                               cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
                          }));
  }
  return c;
}

}  // namespace

std::vector<NodeCase> featureCases(const Inputs& in) {
  std::vector<NodeCase> c;
  for (auto* part : {matchingCases, motionCases, detectorCases})
    for (auto& k : part(in)) c.push_back(std::move(k));
  return c;
}

}  // namespace apex_bench
