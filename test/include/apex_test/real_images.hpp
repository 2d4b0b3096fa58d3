// What the node tests on real images share: opencv-doc's example images read from disk, made into
// the Image messages a node receives (stamp 42.000000007, frame "camera"), fed to a NodeHarness,
// and the image a node sends compared pixel-exactly with the direct OpenCV call's.
#pragma once

#include <gmock/gmock.h>

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

namespace apex_test {

/** opencv-doc's example data (scripts/install_deps installs opencv-doc). */
inline const std::string kOpenCvData = "/usr/share/doc/opencv-doc/examples/data";

/** `name` in kOpenCvData, read with `flags`; empty, and a failure saying so, if it cannot be read. */
inline cv::Mat readData(const std::string& name, int flags = cv::IMREAD_COLOR) {
  cv::Mat m = cv::imread(kOpenCvData + "/" + name, flags);
  if (m.empty()) ADD_FAILURE() << "cannot read " << kOpenCvData << "/" << name << ": is opencv-doc installed?";
  return m;
}

/** `name` in kOpenCvData as an 8-bit gray image. */
inline cv::Mat readGrayData(const std::string& name) { return readData(name, cv::IMREAD_GRAYSCALE); }

/** `mat` as the image a node receives: `encoding`, stamp 42.000000007, frame `frame`. */
inline std::shared_ptr<const apex_nodes::Image> imageOf(cv::Mat mat, const std::string& encoding,
                                                        const std::string& frame = "camera") {
  auto i = std::make_shared<apex_nodes::Image>();
  i->header.stamp = ros::Time(42, 7);
  i->header.frame_id = frame;
  i->encoding = encoding;
  i->mat = std::move(mat);
  return i;
}

/** `name` in kOpenCvData as a bgr8 image in frame `frame` (imageOf's stamp). */
inline std::shared_ptr<const apex_nodes::Image> readDataImage(const std::string& name, const std::string& frame = "camera") {
  return imageOf(readData(name), "bgr8", frame);
}

/** Feeds one image per input of the node, in order, and returns what it sent. */
inline Message runImages(NodeHarness& h, const std::vector<std::shared_ptr<const apex_nodes::Image>>& images) {
  std::vector<Message> messages;
  for (const auto& i : images) messages.push_back(Message::share<apex_nodes::Image>(i));
  return h.run(messages);
}

/** Expects the header imageOf gives by default: stamp 42.000000007, frame "camera". */
inline void expectCameraHeader(const std_msgs::Header& header) {
  EXPECT_EQ(header.stamp, ros::Time(42, 7));
  EXPECT_EQ(header.frame_id, "camera");
}

/** Expects `got` to be `want`: the same size, type and pixels (two empty ones of a type are the same). */
inline void expectSameMat(const cv::Mat& got, const cv::Mat& want) {
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(got.type(), want.type());
  if (!got.empty()) EXPECT_EQ(cv::norm(got, want, cv::NORM_INF), 0.0);
}

/** Expects `m`, what `h`'s node sent, to be the image `want` with `encoding` and imageOf's header. */
inline void expectImage(NodeHarness& h, const Message& m, const cv::Mat& want, const std::string& encoding) {
  ASSERT_TRUE(m.as<apex_nodes::Image>()) << "the node sent no image: " << h.error();
  const apex_nodes::Image& got = *m.as<apex_nodes::Image>();
  expectCameraHeader(got.header);
  EXPECT_EQ(got.encoding, encoding);
  expectSameMat(got.mat, want);
}

/** Expects `m`, what `h`'s node sent, to be Nothing, and the node's error to say `text`. */
inline void expectNothing(NodeHarness& h, const Message& m, const std::string& text) {
  EXPECT_TRUE(m.isNothing());
  EXPECT_THAT(h.error(), ::testing::HasSubstr(text));
}

}  // namespace apex_test
