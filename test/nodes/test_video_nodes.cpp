// Video and geometry nodes on opencv-doc's data, against the OpenCV calls made directly:
// VideoSource's frames and stamps against cv::VideoCapture's reads of vtest.avi and cv::imread of
// cv::glob's left??.jpg (left01..14, not left.jpg), its seeks, passes and their end-of-sequence
// token; VideoWriter's files read back against cv::VideoWriter's (MJPG) and against the frames
// themselves (lossless FFV1); ImageSequenceWriter's files byte for byte against cv::imwrite's;
// SolvePnP's pose of left01.jpg's chessboard (left_intrinsics.yml) against cv::solvePnP's; Stitcher
// against cv::Stitcher::stitch on two halves of building.jpg that overlap by half. A V4L2 camera is
// not tested (none is here): only that one that is absent is refused, naming it.
#include <gmock/gmock.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/quaternion.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/stitching.hpp>
#include <opencv2/videoio.hpp>

#include "apex_nodes/camera_model.hpp"
#include "apex_nodes/shapes.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using ::testing::HasSubstr;

namespace {

const std::string kVideo = kOpenCvData + "/vtest.avi";
constexpr std::int64_t kFirstStampNs = 1700000000LL * 1000000000LL;  // VideoSource's stamps start here

ros::Time stampAt(double seconds) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(kFirstStampNs + std::llround(seconds * 1e9)));
  return t;
}

/** The first 30 frames of vtest.avi as cv::VideoCapture reads them, and their CAP_PROP_POS_MSEC (read once). */
const std::vector<std::pair<cv::Mat, double>>& videoFrames() {
  static const auto frames = [] {
    cv::VideoCapture video(kVideo);
    std::vector<std::pair<cv::Mat, double>> out;
    cv::Mat m;
    while (out.size() < 30 && video.read(m)) out.emplace_back(m.clone(), video.get(cv::CAP_PROP_POS_MSEC));
    return out;
  }();
  if (frames.size() != 30) ADD_FAILURE() << "cannot read 30 frames of " << kVideo;
  return frames;
}

/** A bgr8 image stamped `seconds` (frame "camera"): writers write a stamp once. */
std::shared_ptr<const Image> frameAt(const cv::Mat& mat, int seconds) {
  auto i = std::make_shared<Image>(*imageOf(mat, "bgr8"));
  i->header.stamp = ros::Time(100 + seconds, 0);
  return i;
}

/** Keeps the first 30 frames it receives (not Nothing): a whole pass of a video goes through it, not held. */
class FirstFrames : public Node {
 public:
  static Manifest manifest() { return Manifest("keeps the first frames").optionalInput<Any>("in"); }
  void process() override {
    std::lock_guard<std::mutex> l(m_);
    if (kept_.size() < 30 && !inputMessage("in").isNothing()) kept_.push_back(inputMessage("in").as<Image>());
  }
  std::vector<std::shared_ptr<const Image>> kept() {
    std::lock_guard<std::mutex> l(m_);
    return kept_;
  }

 private:
  std::mutex m_;
  std::vector<std::shared_ptr<const Image>> kept_;
};

const NodeRegistry& registry() {
  static const NodeRegistry* r = [] {
    auto* r = new NodeRegistry(pluginRegistry());
    EXPECT_TRUE(r->add<FirstFrames>("test/FirstFrames"));
    return r;
  }();
  return *r;
}

using Params = std::vector<std::pair<std::string, std::string>>;

/** VideoSource → its first frames, its stamps, a SequenceMean counting each pass, a counter of `finished`. */
class Player {
 public:
  explicit Player(Params params) : g_(registry()) {
    NodeDescription d;
    d.name = "video", d.type = "apex_nodes/VideoSource", d.parameters = std::move(params);
    auto added = g_.addNode(d);
    EXPECT_TRUE(added) << added.message();
    add(g_, "test/FirstFrames", "images"), add(g_, "test/Collector", "stamps");
    add(g_, "apex_nodes/SequenceMean", "per_pass"), add(g_, "test/Collector", "pass_lengths"), add(g_, "test/Counter", "passes");
    link(g_, "video", "image", "images", "in");
    link(g_, "video", "stamp", "stamps", "in");
    link(g_, "video", "stamp", "per_pass", "value");
    link(g_, "per_pass", "count", "pass_lengths", "in");
    link(g_, "video", "finished", "passes", "reset");
    g_.start();
  }
  Graph& graph() { return g_; }
  std::vector<std::shared_ptr<const Image>> images() { return object<FirstFrames>(g_, "images")->kept(); }
  std::vector<int> passLengths() {  // SequenceMean's counts, at the end of each pass (Nothing on other frames)
    std::vector<int> out;
    for (int n : object<Collector>(g_, "pass_lengths")->ints())
      if (n != -999) out.push_back(n);
    return out;
  }
  bool waitForPasses(std::size_t n, double timeout = kWait) {
    return waitUntil([&] { return passLengths().size() >= n; }, timeout) && g_.waitIdle(kWait);
  }
  int passes() { return object<Counter>(g_, "passes")->resets; }
  std::size_t sent() {  // frames sent (a wake-up with nothing to send sends Nothing)
    std::size_t n = 0;
    for (const auto& m : object<Collector>(g_, "stamps")->messages()) n += m.isNothing() ? 0 : 1;
    return n;
  }
  std::string error() {
    EXPECT_TRUE(g_.waitIdle(kWait));
    for (const auto& s : g_.nodeStats(0))
      if (s.name == "video") return s.error;
    return "no node 'video'";
  }

 private:
  Graph g_;
};

TEST(VideoSource, PlaysAVideoAsVideoCaptureReadsItThenEndsThePassWithTheToken) {
  cv::VideoCapture direct(kVideo);
  int total = 0;
  while (direct.grab()) ++total;
  Player p({{"file", "'" + kVideo + "'"}, {"rate", "0"}, {"frame_id", "cam"}});
  ASSERT_TRUE(p.waitForPasses(1, 120)) << p.error();
  EXPECT_EQ(p.passLengths(), std::vector<int>{total}) << "every frame, then the end of the pass";
  EXPECT_EQ(p.passes(), 1);
  const auto got = p.images();
  ASSERT_EQ(got.size(), 30u);
  for (int k = 0; k < 30; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    EXPECT_EQ(got[k]->encoding, "bgr8");
    EXPECT_EQ(got[k]->header.frame_id, "cam");
    EXPECT_EQ(got[k]->header.stamp, stampAt(videoFrames()[k].second / 1000.0));
    expectSameMat(got[k]->mat, videoFrames()[k].first);
  }
}

TEST(VideoSource, PlaysAFoldersImagesInNameOrderAndRestartsAPass) {
  std::vector<cv::String> files;
  cv::glob(kOpenCvData + "/left??.jpg", files, false);
  ASSERT_EQ(files.size(), 13u);
  Player p({{"file", "'" + kOpenCvData + "'"}, {"pattern", "'left??.jpg'"}, {"fps", "10"}, {"rate", "0"}});
  ASSERT_TRUE(p.waitForPasses(1)) << p.error();
  ASSERT_TRUE(p.graph().fireSlot("video", "restart"));
  ASSERT_TRUE(p.waitForPasses(2)) << p.error();
  EXPECT_EQ(p.passLengths(), (std::vector<int>{13, 13}));
  EXPECT_EQ(p.passes(), 2);
  const auto got = p.images();
  ASSERT_EQ(got.size(), 26u);
  for (std::size_t k = 0; k < got.size(); ++k) {
    SCOPED_TRACE(files[k % 13]);
    EXPECT_EQ(got[k]->header.stamp, stampAt((k % 13) / 10.0));
    expectSameMat(got[k]->mat, cv::imread(files[k % 13], cv::IMREAD_COLOR));
  }
}

TEST(VideoSource, SeekingSendsTheFrameAskedForAndEndPassCutsAPass) {
  Player p({{"file", "'" + kVideo + "'"}, {"playing", "false"}});
  for (int k : {10, 3}) {
    ASSERT_TRUE(p.graph().setParameter("video", "frame", std::to_string(k)));
    ASSERT_TRUE(waitUntil([&] { return p.sent() == (k == 10 ? 1u : 2u); })) << p.error();
    ASSERT_TRUE(p.graph().waitIdle(kWait));
    EXPECT_EQ(p.images().back()->header.stamp, stampAt(videoFrames()[k].second / 1000.0)) << "frame " << k;
    expectSameMat(p.images().back()->mat, videoFrames()[k].first);
  }
  ASSERT_TRUE(p.graph().setParameter("video", "rate", "50"));
  ASSERT_TRUE(p.graph().setParameter("video", "playing", "true"));  // from frame 4, 50 a second
  ASSERT_TRUE(waitUntil([&] { return p.sent() >= 6; }));
  ASSERT_TRUE(p.graph().fireSlot("video", "end_pass"));
  ASSERT_TRUE(p.waitForPasses(1));
  EXPECT_EQ(p.passLengths(), std::vector<int>{int(p.sent())}) << "the frames sent (the two seeks' too), then the end";
  EXPECT_LT(p.sent(), 100u);
  EXPECT_EQ(p.passes(), 1);
}

TEST(VideoSource, AMissingSourceIsAnErrorNamingIt) {
  EXPECT_THAT(Player(Params{{"file", "/nonexistent/walk.avi"}}).error(),
              HasSubstr("cannot open the video '/nonexistent/walk.avi': no such file"));
  EXPECT_THAT(Player({{"file", "'" + kOpenCvData + "'"}, {"pattern", "'nothing*.png'"}}).error(),
              HasSubstr("no files in the folder '" + kOpenCvData + "' match 'nothing*.png'"));
  if (!std::filesystem::exists("/dev/video63")) {  // a camera cannot be tested here; its absence can
    EXPECT_THAT(Player(Params{{"device", "63"}}).error(),
                HasSubstr("no camera /dev/video63: this machine has no such V4L2 device"));
  }
}

/** Every frame of a video file, as cv::VideoCapture reads them. */
std::vector<cv::Mat> readAll(const std::string& path) {
  cv::VideoCapture video(path);
  std::vector<cv::Mat> out;
  for (cv::Mat m; video.read(m);) out.push_back(m.clone());
  return out;
}

std::filesystem::path freshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("apex_video_test_" + std::to_string(getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/** VideoWriter's file of `frames` (fourcc, 10 fps), closed by its stop slot. */
std::string writeWithNode(const std::vector<cv::Mat>& frames, const std::string& fourcc, const std::string& path) {
  NodeHarness h("apex_nodes/VideoWriter", {"image"}, "frames");
  h.set("file", "'" + path + "'"), h.set("fourcc", fourcc), h.set("fps", "10");
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const Message m = h.run(frameAt(frames[k], int(k)));
    EXPECT_TRUE(m.as<int>() && *m.as<int>() == int(k + 1)) << h.error();
  }
  EXPECT_TRUE(h.graph().fireSlot("node", "stop"));
  EXPECT_TRUE(h.graph().waitIdle(kWait));
  return path;
}

TEST(VideoWriter, WritesWhatCvVideoWriterWrites) {
  const auto dir = freshDir("writer");
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 20; ++k) frames.push_back(videoFrames()[k].first);
  const auto got = readAll(writeWithNode(frames, "MJPG", (dir / "node.avi").string()));
  cv::VideoWriter direct((dir / "direct.avi").string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
                         frames[0].size(), true);
  for (const auto& f : frames) direct.write(f);
  direct.release();
  const auto want = readAll((dir / "direct.avi").string());
  ASSERT_EQ(got.size(), 20u);
  ASSERT_EQ(want.size(), 20u);
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(got[k].size(), cv::Size(768, 576));
    expectSameMat(got[k], want[k]);  // MJPG is lossy: the same frames decoded as cv::VideoWriter's
  }
  // FFV1 is lossless: the frames read back as they were
  const auto exact = readAll(writeWithNode({frames.begin(), frames.begin() + 5}, "FFV1", (dir / "lossless.avi").string()));
  ASSERT_EQ(exact.size(), 5u);
  for (int k = 0; k < 5; ++k) expectSameMat(exact[k], frames[k]);
}

TEST(VideoWriter, RefusesAFrameOfAnotherSizeAndAFileItDidNotWrite) {
  const auto dir = freshDir("refusals");
  NodeHarness h("apex_nodes/VideoWriter", {"image"}, "frames");
  h.set("file", "'" + (dir / "a.avi").string() + "'");
  EXPECT_EQ(*h.run(frameAt(videoFrames()[0].first, 0)).as<int>(), 1);
  cv::Mat half;
  cv::resize(videoFrames()[1].first, half, cv::Size(384, 288));
  expectNothing(h, h.run(frameAt(half, 1)), "a frame of 384x288 colour in a video of 768x576 colour");
  NodeHarness other("apex_nodes/VideoWriter", {"image"}, "frames");
  other.set("file", "'" + (dir / "a.avi").string() + "'");
  expectNothing(other, other.run(frameAt(videoFrames()[0].first, 0)), "exists (not written by this node)");
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(ImageSequenceWriter, WritesNumberedFilesByteForByteAsImwrite) {
  const auto dir = freshDir("sequence");
  NodeHarness h("apex_nodes/ImageSequenceWriter", {"image"}, "path");
  h.set("directory", "'" + dir.string() + "'");
  h.set("pattern", "'frame_%03d.png'");
  for (int k = 0; k < 3; ++k) {
    const cv::Mat image = readData("left0" + std::to_string(k + 1) + ".jpg");
    const Message m = h.run(frameAt(image, k));
    ASSERT_TRUE(m.as<std::string>()) << h.error();
    const std::string want = (dir / ("frame_00" + std::to_string(k) + ".png")).string(), direct = want + ".direct.png";
    EXPECT_EQ(*m.as<std::string>(), want);
    ASSERT_TRUE(cv::imwrite(direct, image));
    EXPECT_EQ(bytesOf(want), bytesOf(direct)) << want;
  }
  h.set("pattern", "'%d.jpg'"), h.set("number", "stamp"), h.set("jpeg_quality", "80");
  const cv::Mat image = readData("left04.jpg");
  const Message m = h.run(frameAt(image, 3));
  ASSERT_TRUE(m.as<std::string>()) << h.error();
  EXPECT_EQ(*m.as<std::string>(), (dir / "103000000000.jpg").string());  // the stamp, 103 s, in nanoseconds
  ASSERT_TRUE(cv::imwrite((dir / "direct.jpg").string(), image, {cv::IMWRITE_JPEG_QUALITY, 80}));
  EXPECT_EQ(bytesOf(*m.as<std::string>()), bytesOf((dir / "direct.jpg").string()));
  h.set("pattern", "'frame.png'");
  expectNothing(h, h.run(frameAt(image, 4)), "pattern 'frame.png' has 0 %d: it needs one");
}

TEST(SolvePnP, PoseAndErrorEqualCvSolvePnPsOnLeft01sChessboard) {
  const cv::Mat gray = readGrayData("left01.jpg");
  auto corners = std::make_shared<apex_nodes::Corners>();
  corners->header = imageOf(gray, "mono8")->header;
  corners->image_size = gray.size(), corners->pattern_size = cv::Size(9, 6);
  corners->found = cv::findChessboardCorners(gray, corners->pattern_size, corners->corners,
                                             cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
  ASSERT_TRUE(corners->found);
  cv::cornerSubPix(gray, corners->corners, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  const auto camera = std::make_shared<sensor_msgs::CameraInfo>(apex_nodes::readCameraFile(kOpenCvData + "/left_intrinsics.yml"));
  std::vector<cv::Point3f> board;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j) board.emplace_back(float(j * 0.025), float(i * 0.025), 0.f);
  const cv::Matx33d K(camera->K.data());
  const cv::Mat D(camera->D);
  const std::pair<const char*, int> methods[] = {{"iterative", cv::SOLVEPNP_ITERATIVE},
                                                 {"epnp", cv::SOLVEPNP_EPNP},
                                                 {"ippe", cv::SOLVEPNP_IPPE},
                                                 {"sqpnp", cv::SOLVEPNP_SQPNP}};
  for (const auto& [name, flag] : methods) {
    SCOPED_TRACE(name);
    NodeHarness h("apex_nodes/SolvePnP", {"corners", "camera_info"}, "pose", {{"method", name}});
    add(h.graph(), "test/Collector", "errors");
    link(h.graph(), "node", "error", "errors", "in");
    const Message m = h.run({Message::share<apex_nodes::Corners>(corners), Message::share<sensor_msgs::CameraInfo>(camera)});
    ASSERT_TRUE(m.as<geometry_msgs::PoseStamped>()) << h.error();
    const geometry_msgs::PoseStamped& got = *m.as<geometry_msgs::PoseStamped>();
    cv::Vec3d rvec, tvec;
    ASSERT_TRUE(cv::solvePnP(board, corners->corners, K, D, rvec, tvec, false, flag));
    const cv::Quatd q = cv::Quatd::createFromRvec(rvec);
    EXPECT_EQ(got.header, corners->header);
    const auto& at = got.pose.position;
    const auto& turn = got.pose.orientation;
    const double gave[] = {at.x, at.y, at.z, turn.w, turn.x, turn.y, turn.z},
                 want[] = {tvec[0], tvec[1], tvec[2], q.w, q.x, q.y, q.z};
    for (int i = 0; i < 7; ++i) EXPECT_NEAR(gave[i], want[i], 1e-12) << "position x, y, z, orientation w, x, y, z: " << i;
    std::vector<cv::Point2f> projected;
    cv::projectPoints(board, rvec, tvec, K, D, projected);
    const double rms = cv::norm(projected, corners->corners, cv::NORM_L2) / std::sqrt(double(projected.size()));
    ASSERT_TRUE(object<Collector>(h.graph(), "errors")->waitFor(1));
    EXPECT_NEAR(*object<Collector>(h.graph(), "errors")->messages().back().as<double>(), rms, 1e-6);
    EXPECT_LT(rms, 1.0);
    // where the calibration put this view (left_intrinsics.yml's first extrinsics: about 40 cm ahead)
    EXPECT_NEAR(tvec[2], 0.3997, 0.01);
  }
}

TEST(Stitcher, StitchesAsCvStitcherAndNamesTheStatusWhenItCannot) {
  const cv::Mat building = readData("building.jpg");  // 868x600: two halves of 578 columns, 288 of them shared
  const cv::Mat left = building(cv::Rect(0, 0, 578, 600)).clone(), right = building(cv::Rect(290, 0, 578, 600)).clone();
  NodeHarness h("apex_nodes/Stitcher", {"image_0", "image_1"}, "panorama", {{"mode", "scans"}});
  cv::Mat want;
  ASSERT_EQ(cv::Stitcher::create(cv::Stitcher::SCANS)->stitch(std::vector<cv::Mat>{left, right}, want), cv::Stitcher::OK);
  expectImage(h, runImages(h, {imageOf(left, "bgr8"), imageOf(right, "bgr8")}), want, "bgr8");

  const cv::Mat baboon = readData("baboon.jpg");  // nothing in common with the building
  cv::Mat none;
  const int status = cv::Stitcher::create(cv::Stitcher::SCANS)->stitch(std::vector<cv::Mat>{left, baboon}, none);
  ASSERT_GE(status, 1) << "the images were meant not to stitch";
  ASSERT_LE(status, 3);
  const char* names[] = {"OK", "ERR_NEED_MORE_IMGS", "ERR_HOMOGRAPHY_EST_FAIL", "ERR_CAMERA_PARAMS_ADJUST_FAIL"};
  expectNothing(h, runImages(h, {imageOf(left, "bgr8"), imageOf(baboon, "bgr8")}), std::string("cv::Stitcher: ") + names[status]);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
