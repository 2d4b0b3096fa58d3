// apex_bench_images' cases of the video and geometry nodes, each against the OpenCV calls it makes on
// the same data (image_bench.cpp has the table): VideoWriter against cv::VideoWriter::write (MJPG),
// ImageSequenceWriter against cv::imwrite (PNG), SolvePnP against cv::solvePnP and projectPoints on
// left01.jpg's chessboard with left_intrinsics.yml, Stitcher against cv::Stitcher::stitch on two
// halves of the bench's image. The writers' files go to /tmp, rewritten (images) or grown (videos).
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/stitching.hpp>
#include <opencv2/videoio.hpp>

#include "apex_nodes/shapes.hpp"
#include "image_cases.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Corners;
using sensor_msgs::CameraInfo;

/** left01.jpg's 9x6 inner corners, as ChessboardCorners sends them; nullptr if the board is not found. */
std::shared_ptr<const Corners> leftCorners() {
  const cv::Mat gray = cv::imread(kData + "/left01.jpg", cv::IMREAD_GRAYSCALE);
  auto c = std::make_shared<Corners>();
  c->header.frame_id = "camera";
  c->image_size = gray.size(), c->pattern_size = cv::Size(9, 6);
  if (gray.empty() ||
      !cv::findChessboardCorners(gray, c->pattern_size, c->corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return nullptr;
  cv::cornerSubPix(gray, c->corners, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  c->found = true;
  return c;
}

NodeCase solvePnPCase() {
  const auto camera = leftCamera();
  const auto corners = leftCorners();
  if (!camera || !corners)
    return notMeasured("SolvePnP", "", "", "left_intrinsics.yml or left01.jpg (opencv-doc) cannot be read");
  std::vector<cv::Point3f> board;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j) board.emplace_back(float(j * 0.025), float(i * 0.025), 0.f);
  return fixedCase("SolvePnP (iterative)", "apex_nodes/SolvePnP", "left01.jpg's 54 corners, its model",
                   feedType<Corners, CameraInfo>(), {"corners", "camera_info"}, {msg(corners), msg(camera)},
                   {{"method", "iterative"}, {"square_size", "0.025"}}, "error", sinkType<double>(),
                   "solvePnP ITERATIVE, projectPoints (the error)",
                   [board, corners, K = cv::Matx33d(camera->K.data()), D = cv::Mat(camera->D).clone(),
                    projected = std::vector<cv::Point2f>()]() mutable {
                     cv::Vec3d rvec, tvec;
                     cv::solvePnP(board, corners->corners, K, D, rvec, tvec, false, cv::SOLVEPNP_ITERATIVE);
                     cv::projectPoints(board, rvec, tvec, K, D, projected);
                   });
}

}  // namespace

std::vector<NodeCase> videoCases(const Inputs& in) {
  std::vector<NodeCase> c;
  c.push_back(notMeasured("VideoSource", "vtest.avi", "VideoCapture::read",
                          "a source: the bench feeds a node's inputs and times its firing on them; a source has no "
                          "input, and its firing is the read"));
  c.push_back(imageCase("VideoWriter (MJPG)", "apex_nodes/VideoWriter", "8 bgr8 frames, a patch moving", in.moving,
                        {{"file", "/tmp/apex_bench_video_node.avi"}, {"fourcc", "MJPG"}, {"fps", "25"}, {"overwrite", "true"}},
                        "frames", sinkType<int>(), "VideoWriter (FFmpeg, MJPG, 25 fps) write, opened on the first frame",
                        [writer = cv::VideoWriter()](const cv::Mat& m) mutable {
                          if (!writer.isOpened())
                            writer.open("/tmp/apex_bench_video_call.avi", cv::CAP_FFMPEG,
                                        cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, m.size(), true);
                          writer.write(m);
                        }));
  std::filesystem::create_directories("/tmp/apex_bench_sequence");  // the call's file is beside the node's
  c.push_back(imageCase(
      "ImageSequenceWriter (png)", "apex_nodes/ImageSequenceWriter", "bgr8", {in.bgr},
      {{"directory", "/tmp/apex_bench_sequence"}, {"pattern", "'frame_%d.png'"}, {"number", "stamp"}, {"overwrite", "true"}},
      "path", sinkType<std::string>(), "imwrite PNG (its default compression), one file rewritten",
      [](const cv::Mat& m) { cv::imwrite("/tmp/apex_bench_sequence/call.png", m); }));
  c.push_back(solvePnPCase());
  // Two halves of the bench image, 426 columns each, the middle 213 shared: a flat scene scanned.
  const cv::Mat left = in.bgr->mat(cv::Rect(0, 0, 426, 480)).clone(), right = in.bgr->mat(cv::Rect(214, 0, 426, 480)).clone();
  c.push_back(fixedCase("Stitcher (scans)", "apex_nodes/Stitcher", "two 426x480 halves of bgr8, overlapping by half",
                        feedType<Image, Image>(), {"image_0", "image_1"}, {msg(image(left, "bgr8")), msg(image(right, "bgr8"))},
                        {{"mode", "scans"}}, "panorama", sinkType<Image>(), "Stitcher::create(SCANS), stitch",
                        [images = std::vector<cv::Mat>{left, right}, pano = cv::Mat()]() mutable {
                          cv::Stitcher::create(cv::Stitcher::SCANS)->stitch(images, pano);
                        }));
  return c;
}

}  // namespace apex_bench
