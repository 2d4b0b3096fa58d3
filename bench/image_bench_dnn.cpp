// apex_bench_images' cases of DnnNetwork: the node against the calls it makes (blobFromImage, setInput,
// forward), on a small convolutional network the bench writes as ONNX with python3-onnx, having none
// to ship: 3x64x64 in, Conv 8 3x3, Relu, MaxPool 2, Flatten, Gemm to 10, Softmax; weights from
// Python's random, seeded.
#include <cstdlib>
#include <fstream>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "image_cases.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Regions;

const char* const kScript = R"(
import random, sys
import onnx
from onnx import helper, TensorProto

rng = random.Random(11)


def weights(name, dims, sigma):
    n = 1
    for d in dims:
        n *= d
    return helper.make_tensor(name, TensorProto.FLOAT, dims, [rng.gauss(0.0, sigma) for _ in range(n)])


graph = helper.make_graph(
    [helper.make_node("Conv", ["image", "conv_w", "conv_b"], ["conv"], kernel_shape=[3, 3], pads=[1, 1, 1, 1]),
     helper.make_node("Relu", ["conv"], ["relu"]),
     helper.make_node("MaxPool", ["relu"], ["pool"], kernel_shape=[2, 2], strides=[2, 2]),
     helper.make_node("Flatten", ["pool"], ["flat"], axis=1),
     helper.make_node("Gemm", ["flat", "fc_w", "fc_b"], ["scores"], transB=1),
     helper.make_node("Softmax", ["scores"], ["probabilities"], axis=1)],
    "bench_classifier",
    [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 3, 64, 64])],
    [helper.make_tensor_value_info("probabilities", TensorProto.FLOAT, [1, 10])],
    [weights("conv_w", [8, 3, 3, 3], 0.2), weights("conv_b", [8], 0.1),
     weights("fc_w", [10, 8 * 32 * 32], 0.01), weights("fc_b", [10], 0.1)])
model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
onnx.checker.check_model(model)
onnx.save(model, sys.argv[1])
)";

/** The network's file in /tmp, written by the script above; empty if it could not be. */
std::string benchNetwork() {
  const std::string script = "/tmp/apex_bench_dnn.py", path = "/tmp/apex_bench_dnn.onnx";
  std::ofstream(script) << kScript;
  const std::string command = "/usr/bin/python3 " + script + " " + path;
  return std::system(command.c_str()) == 0 ? path : "";
}

/** The Otsu mask's blobs of 400 pixels or more, at most 16: the regions DnnNetwork classifies. */
std::shared_ptr<Regions> blobRegions(const Inputs& in) {
  auto regions = std::make_shared<Regions>();
  regions->header = in.bgr->header;
  regions->image_size = in.bgr->mat.size();
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(in.binary->mat, labels, stats, centroids);
  for (int i = 1; i < n && regions->regions.size() < 16; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < 400) continue;
    apex_nodes::Region r;
    r.box = cv::Rect(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3));
    regions->regions.push_back(r);
  }
  return regions;
}

}  // namespace

std::vector<NodeCase> dnnCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const std::string model = benchNetwork();
  if (model.empty()) {
    c.push_back(notMeasured("DnnNetwork", "bgr8", "blobFromImage; setInput, forward",
                            "python3-onnx cannot write the bench's network (scripts/install_deps)"));
    return c;
  }
  cv::dnn::Net net = cv::dnn::readNetFromONNX(model);  // the node's defaults: OpenCV's layers on the CPU
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  const Params params{
      {"model", model}, {"input_width", "64"}, {"input_height", "64"}, {"scale", num(1.0 / 255)}, {"swap_rb", "true"}};
  const std::string network = "a conv net 3x64x64 → 10 (ONNX, written here)";
  c.push_back(imageCase("DnnNetwork (whole image)", "apex_nodes/DnnNetwork", "bgr8; " + network, {in.bgr}, params, "regions",
                        sinkType<Regions>(), "blobFromImage 64x64, 1/255, RGB; setInput, forward",
                        [net, out = cv::Mat()](const cv::Mat& image) mutable {
                          net.setInput(cv::dnn::blobFromImage(image, 1.0 / 255, cv::Size(64, 64), cv::Scalar(), true, false));
                          out = net.forward();
                        }));
  const auto regions = blobRegions(in);
  const cv::Mat bgr = in.bgr->mat;
  c.push_back(fixedCase(
      "DnnNetwork (regions)", "apex_nodes/DnnNetwork",
      "bgr8, " + std::to_string(regions->regions.size()) + " Otsu blobs ≥ 400 px; " + network, feedType<Image, Regions>(),
      {"image", "regions"}, {msg(in.bgr), msg(regions)}, params, "regions", sinkType<Regions>(),
      "per region: blobFromImage 64x64, 1/255, RGB; setInput, forward", [net, bgr, regions, out = cv::Mat()]() mutable {
        for (const auto& r : regions->regions) {
          net.setInput(cv::dnn::blobFromImage(bgr(r.box), 1.0 / 255, cv::Size(64, 64), cv::Scalar(), true, false));
          out = net.forward();
        }
      }));
  return c;
}

}  // namespace apex_bench
