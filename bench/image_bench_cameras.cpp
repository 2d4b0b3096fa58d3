// apex_bench_images' cases of the cameras-and-stereo and learning nodes: each node against the
// OpenCV calls it makes (image_bench.cpp has the table). The camera model is opencv-doc's
// left_intrinsics.yml, the calibration of its left*.jpg views; the stereo pair its aloe images.
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ml.hpp>
#include <opencv2/objdetect.hpp>

#include "apex_nodes/learning.hpp"
#include "image_cases.hpp"

namespace apex_bench {

/** left_intrinsics.yml's model as a ROS message (R identity, P = [K | 0]); nullptr if unreadable. */
std::shared_ptr<const sensor_msgs::CameraInfo> leftCamera() {
  cv::FileStorage fs(kData + "/left_intrinsics.yml", cv::FileStorage::READ);
  cv::Mat K, D;
  if (fs.isOpened()) fs["camera_matrix"] >> K, fs["distortion_coefficients"] >> D;
  if (K.rows != 3 || K.cols != 3 || D.total() != 5) return nullptr;
  auto info = std::make_shared<sensor_msgs::CameraInfo>();
  info->header.frame_id = "camera";
  info->width = 640, info->height = 480;
  info->distortion_model = "plumb_bob";
  info->D.assign(D.begin<double>(), D.end<double>());
  for (int i = 0; i < 9; ++i) info->K[i] = K.at<double>(i / 3, i % 3), info->R[i] = i % 4 == 0 ? 1 : 0;
  for (int i = 0; i < 12; ++i) info->P[i] = i % 4 == 3 ? 0 : K.at<double>(i / 4, i % 4);
  return info;
}

namespace {

using apex_nodes::Regions;
using sensor_msgs::CameraInfo;

std::vector<NodeCase> cameraModelCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const auto info = leftCamera();
  const cv::Mat raw = cv::imread(kData + "/left01.jpg");
  if (!info || raw.empty()) {
    for (const char* t : {"Rectify", "UndistortRegions"})
      c.push_back(notMeasured(t, "", "", "left_intrinsics.yml or left01.jpg (opencv-doc) cannot be read"));
    return c;
  }
  const cv::Matx33d K(info->K.data());
  const cv::Mat D(info->D);
  cv::Mat map1, map2;  // as image_geometry's PinholeCameraModel makes them, once per model
  cv::initUndistortRectifyMap(K, D, cv::Matx33d::eye(), K, raw.size(), CV_16SC2, map1, map2);
  const ImagePtr frame = image(raw, "bgr8");
  c.push_back(fixedCase("Rectify", "apex_nodes/Rectify", "left01.jpg, bgr8, and its model", feedType<Image, CameraInfo>(),
                        {"image", "camera_info"}, {msg(frame), msg(info)}, {{"interpolation", "linear"}}, "image",
                        sinkType<Image>(), "remap linear (maps made once)",
                        [raw, map1, map2, out = cv::Mat()]() mutable { cv::remap(raw, out, map1, map2, cv::INTER_LINEAR); }));
  auto blobs = std::make_shared<Regions>();
  blobs->header = in.binary->header;
  blobs->image_size = in.binary->mat.size();
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(in.binary->mat, labels, stats, centroids);
  for (int i = 1; i < n; ++i) {
    apex_nodes::Region r;
    r.box = cv::Rect(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3));
    r.centroid = cv::Point2d(centroids.at<double>(i, 0), centroids.at<double>(i, 1));
    blobs->regions.push_back(r);
  }
  c.push_back(fixedCase("UndistortRegions", "apex_nodes/UndistortRegions",
                        std::to_string(blobs->regions.size()) + " blobs of the Otsu mask, the model",
                        feedType<Regions, CameraInfo>(), {"regions", "camera_info"}, {msg(blobs), msg(info)}, {}, "regions",
                        sinkType<Regions>(), "undistortPoints of each centroid and box corner",
                        [blobs, K, D, raw_points = std::vector<cv::Point2d>(), moved = std::vector<cv::Point2d>()]() mutable {
                          raw_points.clear();
                          for (const auto& r : blobs->regions) {
                            const cv::Rect b = r.box;
                            raw_points.insert(raw_points.end(), {r.centroid, b.tl(), cv::Point2d(b.x + b.width, b.y),
                                                                 cv::Point2d(b.x, b.y + b.height), b.br()});
                          }
                          cv::undistortPoints(raw_points, moved, K, D, cv::Matx33d::eye(), K);
                        }));
  c.push_back(notMeasured("CameraInfoFile", "an image", "—",
                          "reads its file once; per frame it sends the model with the frame's header: a message copy, "
                          "no library call to hold it against"));
  c.push_back(notMeasured("CameraCalibration", "ChessboardCorners' corners", "calibrateCamera",
                          "per frame it only keeps the view; cv::calibrateCamera runs once (the calibrate slot or the N-th "
                          "view), not per frame"));
  return c;
}

std::vector<NodeCase> stereoCases() {
  std::vector<NodeCase> c;
  cv::Mat left = cv::imread(kData + "/aloeL.jpg"), right = cv::imread(kData + "/aloeR.jpg");
  if (left.empty() || right.empty()) {
    c.push_back(notMeasured("StereoMatcher", "", "", "aloeL.jpg or aloeR.jpg (opencv-doc) cannot be read"));
    return c;
  }
  cv::resize(left, left, cv::Size(640, 480), 0, 0, cv::INTER_AREA);  // both alike: still a rectified pair
  cv::resize(right, right, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  auto sgbm = cv::StereoSGBM::create(0, 64, 5, 8 * 25, 32 * 25, 1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM);
  c.push_back(fixedCase("StereoMatcher (sgbm)", "apex_nodes/StereoMatcher", "aloeL/R.jpg scaled to 640x480, bgr8",
                        feedType<Image, Image>(), {"left", "right"}, {msg(image(left, "bgr8")), msg(image(right, "bgr8"))},
                        {{"algorithm", "sgbm"}, {"num_disparities", "64"}, {"block_size", "5"}, {"invalid", "opencv"}},
                        "disparity", sinkType<Image>(), "cvtColor both gray, StereoSGBM 64, 5: compute, convertTo 32F / 16",
                        [left, right, sgbm, l = cv::Mat(), r = cv::Mat(), fixed = cv::Mat(), out = cv::Mat()]() mutable {
                          cv::cvtColor(left, l, cv::COLOR_BGR2GRAY);
                          cv::cvtColor(right, r, cv::COLOR_BGR2GRAY);
                          sgbm->compute(l, r, fixed);
                          fixed.convertTo(out, CV_32F, 1.0 / 16);
                        }));
  return c;
}

/** A 3-class linear SVM trained on random 64-float rows, saved to a file in /tmp (Classifier reads it on its first frame): its
 * path. */
std::string trainedSvm() {
  cv::Mat samples(300, 64, CV_32F), labels(300, 1, CV_32S);
  cv::RNG rng(1);
  rng.fill(samples, cv::RNG::UNIFORM, 0.0, 1.0);
  for (int i = 0; i < samples.rows; ++i) {
    labels.at<int>(i) = i % 3;
    samples.at<float>(i, i % 3) += 2.0f;  // separable: what it learns does not change its cost
  }
  auto svm = cv::ml::SVM::create();
  svm->setKernel(cv::ml::SVM::LINEAR);
  svm->train(samples, cv::ml::ROW_SAMPLE, labels);
  const std::string path = "/tmp/apex_bench_svm.yml";
  svm->save(path);
  return path;
}

std::vector<NodeCase> learningCases(const Inputs& in) {
  std::vector<NodeCase> c;
  // The regions FeatureExtract and Classifier get: the Otsu mask's blobs of 50 pixels or more.
  auto regions = std::make_shared<Regions>();
  regions->header = in.gray->header;
  regions->image_size = in.gray->mat.size();
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(in.binary->mat, labels, stats, centroids);
  for (int i = 1; i < n; ++i) {
    apex_nodes::Region r;
    r.box = cv::Rect(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3));
    if (stats.at<int>(i, cv::CC_STAT_AREA) >= 50) regions->regions.push_back(r);
  }
  const std::string words = "mono8, its " + std::to_string(regions->regions.size()) + " blobs ≥ 50 px";
  const cv::Mat gray = in.gray->mat;
  const cv::HOGDescriptor hog(cv::Size(20, 20), cv::Size(20, 20), cv::Size(10, 10), cv::Size(10, 10), 16, 1, -1,
                              cv::HOGDescriptor::L2Hys, 0.2, false, cv::HOGDescriptor::DEFAULT_NLEVELS, true);
  c.push_back(fixedCase("FeatureExtract (hog)", "apex_nodes/FeatureExtract", words, feedType<Image, Regions>(),
                        {"image", "regions"}, {msg(in.gray), msg(regions)},
                        {{"method", "hog"}, {"size", "20"}, {"cells", "2"}, {"bins", "16"}, {"deskew", "false"}}, "features",
                        sinkType<apex_nodes::Features>(), "per region: resize 20x20 area, HOGDescriptor::compute into a row",
                        [gray, regions, hog, square = cv::Mat(), values = std::vector<float>(), rows = cv::Mat()]() mutable {
                          rows.create(static_cast<int>(regions->regions.size()), 64, CV_32F);
                          for (std::size_t i = 0; i < regions->regions.size(); ++i) {
                            cv::resize(gray(regions->regions[i].box), square, cv::Size(20, 20), 0, 0, cv::INTER_AREA);
                            hog.compute(square, values, cv::Size(20, 20), cv::Size(0, 0));
                            std::copy(values.begin(), values.end(), rows.ptr<float>(static_cast<int>(i)));
                          }
                        }));
  auto features = std::make_shared<apex_nodes::Features>();
  features->header = regions->header;
  features->regions = regions;
  features->length = 64;
  features->rows = cv::Mat(static_cast<int>(regions->regions.size()), 64, CV_32F);
  cv::RNG(2).fill(features->rows, cv::RNG::UNIFORM, 0.0, 1.0);
  features->valid.assign(regions->regions.size(), 1);
  const std::string model = trainedSvm();
  auto svm = cv::ml::SVM::load(model);
  c.push_back(fixedCase("Classifier (svm)", "apex_nodes/Classifier",
                        std::to_string(regions->regions.size()) + " rows of 64 features", feedType<apex_nodes::Features>(),
                        {"features"}, {msg(features)}, {{"model", model}, {"min_confidence", "0"}}, "regions",
                        sinkType<Regions>(), "3-class linear SVM (trained here): predict",
                        [features, svm, results = cv::Mat()]() mutable { svm->predict(features->rows, results); }));
  c.push_back(notMeasured("DigitClassifier", "bgr8, sign regions", "—",
                          "its model is apex_train_mlp's own file and its work per region the project's digitFeatures and "
                          "network, not a library call: apex_bench_digits measures it"));
  c.push_back(notMeasured("SampleExport", "an image, regions", "—",
                          "its work is writing PNG files and an index to disk, not a call to hold it against"));
  return c;
}

}  // namespace

std::vector<NodeCase> cameraCases(const Inputs& in) {
  std::vector<NodeCase> c = cameraModelCases(in);
  for (auto& k : stereoCases()) c.push_back(std::move(k));
  for (auto& k : learningCases(in)) c.push_back(std::move(k));
  return c;
}

}  // namespace apex_bench
