// Motion nodes on real data, against the OpenCV calls made directly: background subtraction on
// opencv-doc's pedestrians (vtest.avi), optical flow on basketball1/2.png and rubberwhale1/2.png; and
// Delay, which sends any message again N messages later.
#include <gmock/gmock.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videoio.hpp>

#include "apex_nodes/features.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using apex_nodes::Tracks;
using ::testing::HasSubstr;

namespace {

/** The first `n` frames of vtest.avi, bgr8. */
std::vector<std::shared_ptr<const Image>> pedestrians(int n) {
  cv::VideoCapture video(kOpenCvData + "/vtest.avi");
  if (!video.isOpened()) ADD_FAILURE() << "cannot open " << kOpenCvData << "/vtest.avi";
  std::vector<std::shared_ptr<const Image>> frames;
  cv::Mat frame;
  while (int(frames.size()) < n && video.read(frame)) frames.push_back(imageOf(frame.clone(), "bgr8"));
  EXPECT_EQ(int(frames.size()), n);
  return frames;
}

cv::Mat grayOf(const Image& i) {
  cv::Mat g;
  cv::cvtColor(i.mat, g, cv::COLOR_BGR2GRAY);
  return g;
}

/** The image a node sent, with the frame's header; a failure naming the node's error if none. */
std::shared_ptr<const Image> imageFrom(const Message& m, NodeHarness& h) {
  auto i = m.as<Image>();
  if (!i) {
    ADD_FAILURE() << "expected an image, got " << m.typeName() << ": " << h.error();
    return std::make_shared<Image>();
  }
  expectCameraHeader(i->header);
  return i;
}

TEST(MotionNodes, BackgroundSubtractionEqualsMog2OnPedestrians) {
  const auto frames = pedestrians(22);
  ASSERT_EQ(frames.size(), 22u);
  NodeHarness h("apex_nodes/BackgroundSubtraction", {"image"}, "mask");
  auto mog2 = cv::createBackgroundSubtractorMOG2();  // the node's defaults: history 500, var_threshold 16, shadows
  cv::Mat want;
  for (int i = 0; i < 20; ++i) {
    mog2->apply(frames[i]->mat, want);
    const auto got = imageFrom(h.run(frames[i]), h);
    expectSameMat(got->mat, want);
    EXPECT_EQ(got->encoding, "mono8");
  }
  EXPECT_GT(cv::countNonZero(want == 255), 500);  // people walking: not a test of an empty mask

  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));  // a new model from the next frame on
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  mog2 = cv::createBackgroundSubtractorMOG2();
  mog2->apply(frames[20]->mat, want);
  expectSameMat(imageFrom(h.run(frames[20]), h)->mat, want);

  h.set("history", "50");  // a model parameter: a new model too
  h.set("detect_shadows", "false");
  mog2 = cv::createBackgroundSubtractorMOG2(50, 16, false);
  for (int i = 0; i < 2; ++i) {
    mog2->apply(frames[i]->mat, want);
    expectSameMat(imageFrom(h.run(frames[i]), h)->mat, want);
  }
  h.set("learning_rate", "0.2");  // read per frame: the same model goes on
  mog2->apply(frames[2]->mat, want, 0.2);
  expectSameMat(imageFrom(h.run(frames[2]), h)->mat, want);
}

TEST(MotionNodes, BackgroundSubtractionKnnAgreesWithOpenCvs) {
  // KNN picks the frames it learns from with rand(), whose state the process shares: the node's
  // model and this one draw different numbers, so their masks agree on most pixels, not all.
  const auto frames = pedestrians(20);
  NodeHarness h("apex_nodes/BackgroundSubtraction", {"image"}, "mask");
  h.set("method", "knn");
  auto knn = cv::createBackgroundSubtractorKNN();
  cv::Mat want;
  std::shared_ptr<const Image> got;
  for (const auto& frame : frames) {
    knn->apply(frame->mat, want);
    got = imageFrom(h.run(frame), h);
  }
  ASSERT_EQ(got->mat.size(), want.size());
  ASSERT_EQ(got->mat.type(), CV_8UC1);
  EXPECT_GT(cv::countNonZero(want == 255), 500);
  EXPECT_GT(cv::countNonZero(got->mat == want), 0.97 * double(want.total()));
}

TEST(MotionNodes, BackgroundSubtractionRefusesWhatItCannotModel) {
  NodeHarness h("apex_nodes/BackgroundSubtraction", {"image"}, "mask");
  EXPECT_TRUE(h.run(imageOf(cv::Mat(48, 64, CV_8UC4, cv::Scalar::all(9)), "bgra8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot handle 4-channel images (encoding 'bgra8'); needs 1 or 3 channels"));
  EXPECT_TRUE(h.run(imageOf(cv::Mat(48, 64, CV_16UC1, cv::Scalar::all(9)), "mono16")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("needs an 8-bit image ('mono16')"));
  EXPECT_FALSE(h.run(imageOf(cv::Mat(48, 64, CV_8UC1, cv::Scalar::all(9)), "mono8")).isNothing());
  EXPECT_EQ(h.error(), "");
}

std::shared_ptr<const Tracks> tracksFrom(const Message& m, NodeHarness& h) {
  auto t = m.as<Tracks>();
  if (!t) ADD_FAILURE() << "expected tracks, got " << m.typeName() << ": " << h.error();
  return t;
}

TEST(MotionNodes, OpticalFlowLKEqualsOpenCvsOnBasketball) {
  const auto one = readDataImage("basketball1.png"), two = readDataImage("basketball2.png");
  const cv::Mat g1 = grayOf(*one), g2 = grayOf(*two);
  NodeHarness h("apex_nodes/OpticalFlowLK", {"image"}, "tracks");
  const auto first = tracksFrom(h.run(one), h);
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->previous.empty() && first->current.empty() && first->status.empty());  // nothing to track from yet
  EXPECT_EQ(first->header, one->header);
  EXPECT_EQ(first->image_size, one->mat.size());

  std::vector<cv::Point2f> corners, moved;
  std::vector<uchar> status;
  std::vector<float> err;
  cv::goodFeaturesToTrack(g1, corners, 200, 0.01, 10);  // the node's defaults
  cv::calcOpticalFlowPyrLK(g1, g2, corners, moved, status, err, cv::Size(21, 21), 3);
  const auto second = tracksFrom(h.run(two), h);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->previous, corners);
  EXPECT_EQ(second->current, moved);
  EXPECT_EQ(second->status, status);
  EXPECT_EQ(corners.size(), 200u);
  EXPECT_GT(cv::countNonZero(status), 150);  // most corners found again

  // when_half_lost: the points found again are tracked on, from basketball2 back to basketball1.
  NodeHarness on("apex_nodes/OpticalFlowLK", {"image"}, "tracks");
  on.set("redetect", "when_half_lost");
  on.set("max_corners", "100");
  on.set("win_size", "15");
  on.set("max_level", "2");
  ASSERT_TRUE(tracksFrom(on.run(one), on));
  cv::goodFeaturesToTrack(g1, corners, 100, 0.01, 10);
  cv::calcOpticalFlowPyrLK(g1, g2, corners, moved, status, err, cv::Size(15, 15), 2);
  const auto forth = tracksFrom(on.run(two), on);
  ASSERT_TRUE(forth);
  EXPECT_EQ(forth->current, moved);
  std::vector<cv::Point2f> kept;
  for (std::size_t i = 0; i < moved.size(); ++i)
    if (status[i]) kept.push_back(moved[i]);
  ASSERT_GE(2 * kept.size(), corners.size());  // so the node keeps them rather than detecting anew
  cv::calcOpticalFlowPyrLK(g2, g1, kept, moved, status, err, cv::Size(15, 15), 2);
  const auto back = tracksFrom(on.run(one), on);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->previous, kept);
  EXPECT_EQ(back->current, moved);
  EXPECT_EQ(back->status, status);
}

TEST(MotionNodes, OpticalFlowLKRefusesWhatItCannotTrack) {
  NodeHarness h("apex_nodes/OpticalFlowLK", {"image"}, "tracks");
  EXPECT_TRUE(h.run(imageOf(cv::Mat(48, 64, CV_16UC1, cv::Scalar::all(9)), "mono16")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("needs an 8-bit image ('mono16')"));
  EXPECT_TRUE(h.run(imageOf(cv::Mat(48, 64, CV_8UC2, cv::Scalar::all(9)), "yuv422")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot handle 2-channel images (encoding 'yuv422'); needs 1, 3 or 4 channels"));
}

TEST(MotionNodes, OpticalFlowFarnebackEqualsOpenCvsOnRubberWhale) {
  const auto one = readDataImage("rubberwhale1.png"), two = readDataImage("rubberwhale2.png");
  NodeHarness h("apex_nodes/OpticalFlowFarneback", {"image"}, "flow");
  const auto first = imageFrom(h.run(one), h);  // no previous frame: no motion
  expectSameMat(first->mat, cv::Mat::zeros(one->mat.size(), CV_32FC2));
  EXPECT_EQ(first->encoding, "32FC2");
  cv::Mat want;
  cv::calcOpticalFlowFarneback(grayOf(*one), grayOf(*two), want, 0.5, 3, 15, 3, 5, 1.2, 0);  // the node's defaults
  const auto second = imageFrom(h.run(two), h);
  expectSameMat(second->mat, want);
  EXPECT_EQ(second->encoding, "32FC2");
  EXPECT_GT(cv::norm(want, cv::NORM_L1) / want.total(), 0.05);  // the whale moved: not a test of zeros

  h.set("poly_n", "7");
  h.set("poly_sigma", "1.5");
  cv::calcOpticalFlowFarneback(grayOf(*two), grayOf(*one), want, 0.5, 3, 15, 3, 7, 1.5, 0);
  expectSameMat(imageFrom(h.run(one), h)->mat, want);
  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  expectSameMat(imageFrom(h.run(two), h)->mat, cv::Mat::zeros(one->mat.size(), CV_32FC2));
}

TEST(MotionNodes, DelaySendsAnyMessageNMessagesLater) {
  NodeHarness h("apex_nodes/Delay", {"in"}, "out");
  h.set("frames", "2");
  auto sent = [&](int v) {
    const Message m = h.run({Message::make(v)});
    return m.isNothing() ? -1 : *m.as<int>();
  };
  EXPECT_EQ(sent(1), -1);  // Nothing until two have come
  EXPECT_EQ(sent(2), -1);
  EXPECT_EQ(sent(3), 1);
  EXPECT_EQ(sent(4), 2);
  h.set("frames", "1");
  EXPECT_EQ(sent(5), 4);
  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  EXPECT_EQ(sent(6), -1);
  EXPECT_EQ(sent(7), 6);
  // The end of a sequence forgets too: the next pass does not get this one's last frame.
  object<MessageFeeder>(h.graph(), "in0")->feed(Message::endOfSequence());
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  EXPECT_EQ(sent(8), -1);
  // An image, e.g. for frame differencing: the same object, not a copy.
  const auto a = readDataImage("basketball1.png"), b = readDataImage("basketball2.png");
  EXPECT_EQ(sent(9), 8);
  const Message nine = h.run(a);
  ASSERT_TRUE(nine.as<int>());
  EXPECT_EQ(*nine.as<int>(), 9);
  EXPECT_EQ(h.run(b).raw(), a.get());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
