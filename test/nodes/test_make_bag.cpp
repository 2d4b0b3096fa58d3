// apex_make_bag (apex_nodes/tools/make_bag.hpp) on opencv-doc's real data: frames read back from
// the bag equal the decoded video frames and images pixel for pixel, stamped at the rate or as a
// timestamps file says, with camera info when asked; a stereo pair's frames share their stamps;
// unreadable inputs are refused naming the file, leaving neither a bag nor a .active file.
#include <camera_calibration_parsers/parse.h>
#include <cv_bridge/cv_bridge.h>
#include <gmock/gmock.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "apex_test/real_images.hpp"
#include "make_bag.hpp"
#include "make_bag_sources.hpp"

using namespace apex_test;
using testing::HasSubstr;
namespace fs = std::filesystem;
using Args = std::vector<std::string>;

namespace {

/** A folder of the test's own: `bag` in it the output, path(name) any other file. */
class MakeBag : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("apex_make_bag_" + std::to_string(getpid()) + "_" + testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    bag = (dir_ / "out.bag").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  /** A file `name` in the folder holding `text`; its path. */
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  /** apex_make_bag's command line `args`, writing `bag`. */
  apex_tools::MakeBagSummary make(Args args) const {
    args.insert(args.end(), {"-o", bag});
    return apex_tools::makeBag(apex_tools::parseMakeBagArgs(args));
  }
  /** Why `args` are refused; and that they left neither `bag` nor bag.active. */
  std::string refusal(const Args& args) const {
    std::string why = "not refused";
    try {
      make(args);
    } catch (const std::exception& e) {
      why = e.what();
    }
    EXPECT_FALSE(fs::exists(bag)) << why;
    EXPECT_FALSE(fs::exists(bag + ".active")) << why;
    return why;
  }

  fs::path dir_;
  std::string bag;
};

std::string data(const std::string& name) { return kOpenCvData + "/" + name; }

/** The first `n` frames of vtest.avi as OpenCV decodes them. */
std::vector<cv::Mat> videoFrames(std::size_t n) {
  cv::VideoCapture video(data("vtest.avi"));
  std::vector<cv::Mat> frames;
  for (cv::Mat f; frames.size() < n && video.read(f);) frames.push_back(f.clone());
  EXPECT_EQ(frames.size(), n) << "cannot read " << n << " frames of " << data("vtest.avi");
  return frames;
}

/** A topic's messages in the bag, in order. */
template <class M>
std::vector<boost::shared_ptr<M>> messages(const std::string& bag, const std::string& topic) {
  rosbag::Bag b(bag, rosbag::bagmode::Read);
  std::vector<boost::shared_ptr<M>> out;
  for (const rosbag::MessageInstance& m : rosbag::View(b, rosbag::TopicQuery(topic))) {
    out.push_back(m.instantiate<M>());
    EXPECT_TRUE(out.back()) << topic << " carries " << m.getDataType();
    if (out.back()) {
      EXPECT_EQ(m.getTime(), out.back()->header.stamp);  // recorded at its stamp
    }
  }
  return out;
}

std::vector<std::string> topicsOf(const std::string& bag) {
  rosbag::Bag b(bag, rosbag::bagmode::Read);
  std::vector<std::string> topics;
  for (const rosbag::ConnectionInfo* c : rosbag::View(b).getConnections()) topics.push_back(c->topic);
  std::sort(topics.begin(), topics.end());
  return topics;
}

/** Expects the bag's images on `topic` to be `want`, in `encoding`, on frame `frame`, numbered. */
void expectFrames(const std::string& bag, const std::string& topic, const std::vector<cv::Mat>& want,
                  const std::string& encoding = "bgr8", const std::string& frame = "camera") {
  const auto images = messages<sensor_msgs::Image>(bag, topic);
  ASSERT_EQ(images.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(images[i]->encoding, encoding);
    EXPECT_EQ(images[i]->header.frame_id, frame);
    EXPECT_EQ(images[i]->header.seq, i);
    expectSameMat(cv_bridge::toCvCopy(images[i])->image, want[i]);
  }
}

std::vector<ros::Time> stamps(const std::string& bag, const std::string& topic) {
  std::vector<ros::Time> out;
  for (const auto& m : messages<sensor_msgs::Image>(bag, topic)) out.push_back(m->header.stamp);
  return out;
}

ros::Time at(std::int64_t ns) { return ros::Time().fromNSec(static_cast<std::uint64_t>(ns)); }

/** A camera model as ROS's camera_calibration writes it, for images of `width` x `height`. */
sensor_msgs::CameraInfo cameraModel(std::uint32_t width, std::uint32_t height, double fx) {
  sensor_msgs::CameraInfo c;
  c.width = width, c.height = height, c.distortion_model = "plumb_bob";
  c.K = {fx, 0, width / 2.0, 0, fx, height / 2.0, 0, 0, 1};
  c.D = {-0.2, 0.05, 0.001, -0.001, 0};
  c.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c.P = {fx, 0, width / 2.0, 0, 0, fx, height / 2.0, 0, 0, 0, 1, 0};
  return c;
}

/** Expects each image on `topic` to have, on `info_topic`, `model` with the image's header. */
void expectCameraInfo(const std::string& bag, const std::string& topic, const std::string& info_topic,
                      const sensor_msgs::CameraInfo& model) {
  const auto images = messages<sensor_msgs::Image>(bag, topic);
  const auto infos = messages<sensor_msgs::CameraInfo>(bag, info_topic);
  ASSERT_EQ(infos.size(), images.size());
  for (std::size_t i = 0; i < infos.size(); ++i) {
    sensor_msgs::CameraInfo want = model;
    want.header = images[i]->header;
    EXPECT_EQ(*infos[i], want);
  }
}

/** opencv-doc's chessboard frames (left01..left05.jpg; right01... with `side` right). */
std::vector<cv::Mat> chessboards(const std::string& side = "left", int n = 5) {
  std::vector<cv::Mat> frames;
  for (int k = 1; k <= n; ++k) frames.push_back(readData(side + "0" + std::to_string(k) + ".jpg"));
  return frames;
}

/** `frames` through cv::cvtColor with `code`. */
std::vector<cv::Mat> converted(const std::vector<cv::Mat>& frames, int code) {
  std::vector<cv::Mat> out(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) cv::cvtColor(frames[i], out[i], code);
  return out;
}

TEST_F(MakeBag, VideoFramesComeBackAsDecodedAtTheVideosFrameRate) {
  cv::VideoCapture video(data("vtest.avi"));
  const double fps = video.get(cv::CAP_PROP_FPS);
  ASSERT_GT(fps, 0);
  const auto s = make({data("vtest.avi"), "--max-frames", "20"});
  EXPECT_EQ(s.frames, 20u);
  EXPECT_EQ(s.rate, fps);
  expectFrames(bag, "/camera/image_raw", videoFrames(20));
  const auto t = stamps(bag, "/camera/image_raw");
  ASSERT_EQ(t.size(), 20u);
  for (std::size_t i = 0; i < t.size(); ++i)
    EXPECT_EQ(t[i], at(apex_tools::kDefaultStart + std::llround(i * 1e9 / fps))) << "frame " << i;
  EXPECT_EQ(topicsOf(bag), Args{"/camera/image_raw"});  // no calibration, no camera_info
  EXPECT_FALSE(fs::exists(bag + ".active"));
}

TEST_F(MakeBag, VideoInGrayOnATopicAndFrameOfItsOwn) {
  make({data("vtest.avi"), "--max-frames=3", "--encoding", "mono8", "--topic", "cam/image", "--frame-id", "ptz"});
  expectFrames(bag, "/cam/image", converted(videoFrames(3), cv::COLOR_BGR2GRAY), "mono8", "ptz");
}

TEST_F(MakeBag, AFolderOfImagesComesBackInNaturalOrderAtTenHertz) {
  fs::create_directories(path("frames"));
  const std::vector<std::string> names = {"left01", "left02", "left03", "left04", "left05", "left06",
                                          "left07", "left08", "left09", "left11", "left12"};
  std::vector<cv::Mat> want;
  for (std::size_t k = 0; k < names.size(); ++k) {  // img1.jpg ... img11.jpg: img10 after img9, not after img1
    fs::copy_file(data(names[k] + ".jpg"), path("frames/img" + std::to_string(k + 1) + ".jpg"));
    want.push_back(readData(names[k] + ".jpg"));
  }
  write("frames/notes.txt", "not an image: a folder's other files are not frames");
  const auto s = make({path("frames")});
  EXPECT_EQ(s.rate, apex_tools::kDefaultRate);
  expectFrames(bag, "/camera/image_raw", want);
  const auto t = stamps(bag, "/camera/image_raw");
  ASSERT_EQ(t.size(), want.size());
  EXPECT_EQ(t.front(), at(apex_tools::kDefaultStart));
  EXPECT_EQ(t.back(), at(apex_tools::kDefaultStart + 1000000000));  // 10 frames later, at 10 Hz
}

TEST_F(MakeBag, AGlobOfImagesAtARateFromAStart) {
  make({data("left0[1-5].jpg"), "--rate", "4", "--start", "100.5", "--encoding", "rgb8"});
  expectFrames(bag, "/camera/image_raw", converted(chessboards(), cv::COLOR_BGR2RGB), "rgb8");
  const auto t = stamps(bag, "/camera/image_raw");
  ASSERT_EQ(t.size(), 5u);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_EQ(t[i], ros::Time(100, 500000000) + ros::Duration(0.25 * i));
}

TEST_F(MakeBag, StampsFromATimestampsFile) {
  const std::string file = write("times.txt",
                                 "# t [s], image\n1305031102.175304 rgb/1.png\n\n1305031102.211214\n"
                                 "1305031102.243211,x\n1305031102.275326\n1305031102.311267\n");
  make({data("left0[1-5].jpg"), "--timestamps", file});
  EXPECT_EQ(stamps(bag, "/camera/image_raw"),
            (std::vector<ros::Time>{ros::Time(1305031102, 175304000), ros::Time(1305031102, 211214000),
                                    ros::Time(1305031102, 243211000), ros::Time(1305031102, 275326000),
                                    ros::Time(1305031102, 311267000)}));
  fs::remove(bag);
  make({data("left0[1-5].jpg"), "--timestamps", file, "--start", "10"});  // shifted to start at 10 s
  EXPECT_EQ(stamps(bag, "/camera/image_raw")[1], ros::Time(10, 35910000));
  fs::remove(bag);
  make({data("vtest.avi"), "--timestamps", file, "--max-frames", "3"});  // the first 3 of the 5 stamps
  EXPECT_EQ(stamps(bag, "/camera/image_raw")[2], ros::Time(1305031102, 243211000));
}

TEST_F(MakeBag, CameraInfoBesideEachImageAsTheCalibrationFileSays) {
  const sensor_msgs::CameraInfo model = cameraModel(640, 480, 530.5);
  ASSERT_TRUE(camera_calibration_parsers::writeCalibration(path("camera.yaml"), "camera", model));
  const auto s = make({data("left0[1-5].jpg"), "--camera-info", path("camera.yaml"), "--frame-id", "left_optical"});
  EXPECT_EQ(s.topics, (Args{"/camera/image_raw", "/camera/camera_info"}));
  expectFrames(bag, "/camera/image_raw", chessboards(), "bgr8", "left_optical");
  expectCameraInfo(bag, "/camera/image_raw", "/camera/camera_info", model);
}

TEST_F(MakeBag, CameraInfoFromOpenCvsCalibrationOutput) {
  make({data("left0[1-3].jpg"), "--camera-info", data("left_intrinsics.yml")});
  cv::FileStorage fs(data("left_intrinsics.yml"), cv::FileStorage::READ);
  cv::Mat K;
  fs["camera_matrix"] >> K;
  const auto infos = messages<sensor_msgs::CameraInfo>(bag, "/camera/camera_info");
  ASSERT_EQ(infos.size(), 3u);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(infos[0]->K[k], K.at<double>(k / 3, k % 3));
}

TEST_F(MakeBag, AStereoPairSharesItsStamps) {
  ASSERT_TRUE(camera_calibration_parsers::writeCalibration(path("l.yaml"), "left", cameraModel(640, 480, 500)));
  sensor_msgs::CameraInfo right = cameraModel(640, 480, 500);
  right.P[3] = -500 * 0.06;  // Tx = -fx * baseline
  ASSERT_TRUE(camera_calibration_parsers::writeCalibration(path("r.yaml"), "right", right));
  make({"--left", data("left0[1-5].jpg"), "--right", data("right0[1-5].jpg"), "--left-info", path("l.yaml"), "--right-info",
        path("r.yaml"), "--rate", "2"});
  expectFrames(bag, "/stereo/left/image_raw", chessboards("left"));
  expectFrames(bag, "/stereo/right/image_raw", chessboards("right"));
  EXPECT_EQ(stamps(bag, "/stereo/left/image_raw"), stamps(bag, "/stereo/right/image_raw"));
  expectCameraInfo(bag, "/stereo/left/image_raw", "/stereo/left/camera_info", cameraModel(640, 480, 500));
  expectCameraInfo(bag, "/stereo/right/image_raw", "/stereo/right/camera_info", right);
}

TEST_F(MakeBag, APairOfDifferentLengthsIsRefusedNamingBoth) {
  const std::string why = refusal({"--left", data("left0[1-5].jpg"), "--right", data("right0[1-4].jpg")});
  EXPECT_THAT(why, HasSubstr("--left '" + data("left0[1-5].jpg") + "' has 5 frames"));
  EXPECT_THAT(why, HasSubstr("--right '" + data("right0[1-4].jpg") + "' has 4"));
}

TEST_F(MakeBag, UnreadableInputsAreRefusedNamingTheFile) {
  EXPECT_THAT(refusal({path("missing.avi")}), HasSubstr("'" + path("missing.avi") + "' does not exist"));
  EXPECT_THAT(refusal({write("text.avi", "not a video")}), HasSubstr("OpenCV cannot open '" + path("text.avi") + "'"));
  EXPECT_THAT(refusal({path("none/*.png")}), HasSubstr("no files match '" + path("none/*.png") + "'"));
  fs::create_directories(path("empty"));
  EXPECT_THAT(refusal({path("empty")}), HasSubstr("the folder '" + path("empty") + "' holds no images"));
  fs::create_directories(path("frames"));  // a good frame first: the failure comes after writing began
  fs::copy_file(data("left01.jpg"), path("frames/f1.jpg"));
  write("frames/f2.jpg", "not a JPEG");
  EXPECT_THAT(refusal({path("frames")}), HasSubstr("'" + path("frames/f2.jpg") + "' does not decode as an image"));
}

TEST_F(MakeBag, BadCalibrationsAndTimestampsAreRefusedNamingTheFileAndLine) {
  const std::string images = data("left0[1-3].jpg");
  EXPECT_THAT(refusal({images, "--camera-info", write("bad.yaml", "image_width: [\n")}), HasSubstr("'" + path("bad.yaml") + "'"));
  EXPECT_THAT(refusal({images, "--camera-info", path("none.yaml")}), HasSubstr("'" + path("none.yaml") + "'"));
  ASSERT_TRUE(camera_calibration_parsers::writeCalibration(path("small.yaml"), "c", cameraModel(320, 240, 300)));
  EXPECT_THAT(refusal({images, "--camera-info", path("small.yaml")}),
              HasSubstr("'" + path("small.yaml") + "' is for 320x240 images but '" + data("left01.jpg") + "' is 640x480"));
  EXPECT_THAT(refusal({images, "--timestamps", write("t1.txt", "1.0\n1.1\nsoon\n")}),
              HasSubstr("'" + path("t1.txt") + "' line 3: 'soon' is not a time in seconds"));
  EXPECT_THAT(refusal({images, "--timestamps", write("t2.txt", "1.0\n0.9\n1.2\n")}),
              HasSubstr("'" + path("t2.txt") + "' line 2: 0.9 is not later than the stamp before it"));
  EXPECT_THAT(refusal({images, "--timestamps", write("t3.txt", "1.0\n1.1\n")}),
              HasSubstr("'" + path("t3.txt") + "' has 2 timestamps but '" + images + "' has 3 frames"));
  EXPECT_THAT(refusal({data("vtest.avi"), "--timestamps", path("t3.txt")}),
              HasSubstr("'" + path("t3.txt") + "' has 2 timestamps"));
  EXPECT_THAT(refusal({images, "--timestamps", write("t4.txt", "0\n1\n2\n")}), HasSubstr("give --start"));
  EXPECT_THAT(refusal({data("left01.jpg"), "--encoding", "mono16"}), HasSubstr("'" + data("left01.jpg") + "' is not a 16-bit"));
}

TEST_F(MakeBag, AnExistingBagIsKeptUnlessOverwriteIsGiven) {
  write("out.bag", "someone's recording");
  EXPECT_THAT([&] { make({data("left01.jpg")}); },
              testing::ThrowsMessage<std::runtime_error>(HasSubstr("'" + bag + "' exists: give --overwrite")));
  std::string kept;
  std::getline(std::ifstream(bag), kept);
  EXPECT_EQ(kept, "someone's recording");
  EXPECT_FALSE(fs::exists(bag + ".active"));
  make({data("left01.jpg"), "--overwrite"});
  expectFrames(bag, "/camera/image_raw", chessboards("left", 1));
}

TEST_F(MakeBag, AnInterruptedRunLeavesNoBag) {
  apex_tools::make_bag_interrupted = true;
  EXPECT_THAT(refusal({data("left0[1-5].jpg")}), HasSubstr("interrupted"));
  apex_tools::make_bag_interrupted = false;
}

TEST(MakeBagCommandLine, OptionsOutOfPlaceAreRefusedNamingThem) {
  const auto why = [](const Args& args) {
    try {
      apex_tools::parseMakeBagArgs(args);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(why({"v.avi"}), HasSubstr("-o OUT.bag"));
  EXPECT_THAT(why({"-o", "b.bag"}), HasSubstr("needs an INPUT"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--fps", "3"}), HasSubstr("unknown option '--fps'"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--rate"}), HasSubstr("--rate needs a value"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--rate", "0"}), HasSubstr("--rate needs Hz"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--rate", "5", "--timestamps", "t"}), HasSubstr("--rate or --timestamps"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--encoding", "bayer_rggb8"}), HasSubstr("--encoding is one of bgr8"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--start", "0"}), HasSubstr("--start needs seconds after 0"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--topic", "a b"}), HasSubstr("--topic 'a b' is not a topic name"));
  EXPECT_THAT(why({"v.avi", "-o", "b.bag", "--left-info", "l.yaml"}), HasSubstr("--left-info is for a stereo pair"));
  EXPECT_THAT(why({"--left", "l", "-o", "b.bag"}), HasSubstr("needs both --left and --right"));
  EXPECT_THAT(why({"--left", "l", "--right", "r", "-o", "b.bag", "--camera-info", "c"}), HasSubstr("--camera-info is for one"));
  const auto o = apex_tools::parseMakeBagArgs({"a.png", "b.png", "--output=x.bag", "--topic", "cam/img", "--max-frames", "7"});
  EXPECT_EQ(o.inputs, (Args{"a.png", "b.png"}));
  EXPECT_EQ(o.output, "x.bag");
  EXPECT_EQ(o.topic, "/cam/img");
  EXPECT_EQ(o.max_frames, 7u);
}

TEST(MakeBagCommandLine, NamesSortInNaturalOrder) {
  Args names = {"img10.png", "img2.png", "img1.png", "img02b.png", "a/img9.png", "img.png", "img100.png"};
  std::sort(names.begin(), names.end(), apex_tools::naturalLess);
  EXPECT_EQ(names, (Args{"a/img9.png", "img.png", "img1.png", "img2.png", "img02b.png", "img10.png", "img100.png"}));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
