// DnnNetwork: classifies an image, or each of its regions, with a network OpenCV's dnn module reads
// (cv::dnn::readNet tells the format by the files' extensions: ONNX .onnx, Caffe .caffemodel with
// its .prototxt, TensorFlow .pb with an optional .pbtxt, Darknet .weights with its .cfg). Each crop,
// or the whole image, becomes a blob as blobFromImage makes it (resized to the input size, the mean
// subtracted, scaled) and runs through the network alone, so that a network whose batch is fixed at
// one takes it too. The label is the index of the crop's largest output, the confidence that value:
// a probability when the network ends in a softmax, as classifiers do.
// The network is read when first needed, and again when the file changes or a parameter it is read
// with is set (ModelFile); a missing or unreadable file is an error naming it.
// Classification only: SSD/YOLO detections (boxes, NMSBoxes) and segmentation maps come later.

#include <algorithm>
#include <memory>
#include <opencv2/dnn.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/model_file.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** A network as read from its files, set to run on a backend and target. */
struct DnnModel {
  mutable cv::dnn::Net net;  // a run changes its buffers, not what was read

  static DnnModel read(const std::string& model, const std::string& config, cv::dnn::Backend backend, cv::dnn::Target target) {
    DnnModel m;
    try {
      m.net = cv::dnn::readNet(model, config);
    } catch (const cv::Exception& e) {
      throw std::invalid_argument("the model '" + model + "'" + (config.empty() ? "" : " (with '" + config + "')") +
                                  " cannot be read by OpenCV's dnn: " + e.err);
    }
    if (m.net.empty()) throw std::invalid_argument("the model '" + model + "' holds no network");
    m.net.setPreferableBackend(backend);
    m.net.setPreferableTarget(target);
    return m;
  }
};

/** The region a whole image is, for a node given no regions. */
Region wholeImage(const cv::Size& size) {
  Region r;
  r.box = cv::Rect(cv::Point(0, 0), size);
  r.area = size.area();
  r.centroid = cv::Point2d(size.width / 2.0, size.height / 2.0);
  return r;
}

}  // namespace

class DnnNetwork : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit or float pixels, of the channels the network takes"};
  static inline const apex::InputPort<Regions> kRegions{
      "regions", "if connected: each region's crop is classified; else the whole image", true};
  static inline const apex::OutputPort<Regions> kLabelled{
      "regions",
      "the regions (or one, the whole image) with label (the largest output's index; -1 below min_confidence or outside "
      "the image) and confidence (that output)"};
  static inline const apex::OutputPort<Image> kOutput{
      "output", "the network's output, 32FC1: a row per region (zeros for one outside the image), its values in order"};
  static inline const apex::ParamDecl<std::string> kModel =
      param::path("model")
          .describe("the network: .onnx, .caffemodel, .pb or .weights (readNet tells the format by the extension)")
          .mode(apex::PathMode::Read)
          .files({"*.onnx", "*.caffemodel", "*.pb", "*.weights"});
  static inline const apex::ParamDecl<std::string> kConfig =
      param::path("config")
          .describe("the model's description where its format has one: .prototxt (Caffe), .pbtxt (TensorFlow), .cfg (Darknet)")
          .mode(apex::PathMode::Read)
          .files({"*.prototxt", "*.pbtxt", "*.cfg"});
  static inline const apex::ParamDecl<int> kWidth =
      param::integer("input_width").range(1, 4096).init(224).describe("pixels: each crop is resized to the network's input");
  static inline const apex::ParamDecl<int> kHeight = param::integer("input_height").range(1, 4096).init(224).describe("pixels");
  static inline const apex::ParamDecl<std::vector<double>> kMean = param::list("mean").init({0, 0, 0}).describe(
      "subtracted from each channel, in the blob's channel order (after swap_rb), before scaling; up to 4 numbers");
  static inline const apex::ParamDecl<double> kScale =
      param::number("scale").range(0.0, 1000.0).step(0.0001).init(1.0).describe("each value times it (1/255: 0.00392157)");
  static inline const apex::ParamDecl<bool> kSwapRb =
      param::flag("swap_rb").describe("swap the first and third channels: BGR images for a network trained on RGB");
  static inline const apex::ParamDecl<bool> kCrop =
      param::flag("crop").describe("resize keeping the aspect ratio and cut out the middle; else stretch to the input size");
  static inline const apex::ChoiceDecl<cv::dnn::Backend> kBackend =
      param::choice<cv::dnn::Backend>(
          "backend", {{"opencv", cv::dnn::DNN_BACKEND_OPENCV,
                       "OpenCV's own layers, the one Debian's OpenCV has (built without CUDA, OpenVINO, Vulkan or Halide)"}})
          .describe("what runs the layers");
  static inline const apex::ChoiceDecl<cv::dnn::Target> kTarget =
      param::choice<cv::dnn::Target>(
          "target", {{"cpu", cv::dnn::DNN_TARGET_CPU},
                     {"opencl", cv::dnn::DNN_TARGET_OPENCL, "a GPU through OpenCL; OpenCV falls back to the CPU without one"},
                     {"opencl_fp16", cv::dnn::DNN_TARGET_OPENCL_FP16, "the same in half precision"}})
          .describe("the device");
  static inline const apex::ParamDecl<double> kMinConfidence =
      param::number("min_confidence")
          .range(0.0, 1.0)
          .step(0.01)
          .init(0.0)
          .describe("a region whose largest output is less gets label -1");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Classifies an image, or each region's crop, with a network OpenCV's dnn reads (ONNX, Caffe, "
               "TensorFlow, Darknet)")
        .inCategory("learning")
        .input(kImage)
        .input(kRegions)
        .output(kLabelled)
        .output(kOutput)
        .param(kModel)
        .param(kConfig)
        .param(kWidth)
        .param(kHeight)
        .param(kMean)
        .param(kScale)
        .param(kSwapRb)
        .param(kCrop)
        .param(kBackend)
        .param(kTarget)
        .param(kMinConfidence);
  }
  void parameterChanged(const std::string& name) override {
    for (const std::string& read_with : {kModel.name(), kConfig.name(), kBackend.name(), kTarget.name()})
      if (name == read_with) model_.forget();
  }
  void process() override {
    const Image& image = *image_.get();
    requireImage(image);
    if (image.mat.depth() != CV_8U && image.mat.depth() != CV_32F)
      throw std::invalid_argument("cannot classify '" + image.encoding + "' images: blobFromImage takes 8-bit or float pixels");
    if (mean_.get().size() > 4)
      throw std::invalid_argument("mean has " + std::to_string(mean_.get().size()) + " numbers: give one per channel, up to 4");
    auto out = std::make_shared<Regions>();
    if (const auto in = regions_.get()) {
      *out = *in;
    } else {
      out->header = image.header, out->image_size = image.mat.size();
      out->regions = {wholeImage(image.mat.size())};
    }
    const DnnModel& model = load();
    const cv::Rect frame(0, 0, image.mat.cols, image.mat.rows);
    const int n = static_cast<int>(out->regions.size());
    cv::Mat rows;  // a row per region, sized at the first output
    for (int i = 0; i < n; ++i) {
      Region& r = out->regions[i];
      r.label = -1, r.confidence = 0;
      const cv::Rect box = r.box & frame;
      if (box.empty()) continue;
      const cv::Mat values = run(model, image.mat(box));
      if (rows.empty()) rows = cv::Mat::zeros(n, values.cols, CV_32F);
      values.copyTo(rows.row(i));
      const float* v = values.ptr<float>();
      const int best = static_cast<int>(std::max_element(v, v + values.cols) - v);
      r.confidence = v[best];
      if (v[best] >= min_confidence_.get()) r.label = best;
    }
    if (!rows.empty()) output_.publish(resultOf(image, rows, "32FC1"));
    regions_out_.publish(std::move(out));
  }

 private:
  /** The network's output for one crop, as one row of floats (a copy: the next run reuses the net's buffers). */
  cv::Mat run(const DnnModel& model, const cv::Mat& crop) const {
    const std::vector<double>& m = mean_.get();
    cv::Scalar mean;
    for (std::size_t c = 0; c < m.size(); ++c) mean[static_cast<int>(c)] = m[c];
    const cv::Size size(width_.get(), height_.get());
    cv::Mat out;
    try {
      model.net.setInput(cv::dnn::blobFromImage(crop, scale_.get(), size, mean, swap_rb_.get(), crop_.get()));
      out = model.net.forward();
    } catch (const cv::Exception& e) {
      throw std::invalid_argument("the network '" + model_path_.get() + "' cannot run on a " + std::to_string(crop.cols) + "x" +
                                  std::to_string(crop.rows) + " crop of " + std::to_string(crop.channels()) + " channels at " +
                                  std::to_string(size.width) + "x" + std::to_string(size.height) + ": " + e.err);
    }
    cv::Mat row;
    out.reshape(1, 1).convertTo(row, CV_32F);
    return row;
  }
  const DnnModel& load() {
    const std::string& path = model_path_.get();
    if (path.empty()) throw std::invalid_argument("no model: set 'model' to a network file (.onnx, .caffemodel, .pb, .weights)");
    bool fresh = false;
    const DnnModel& model = model_.get(
        path, [&](const std::string& p) { return DnnModel::read(p, config_.get(), backend_.get(), target_.get()); }, fresh);
    if (fresh) log(apex::LogLevel::Info, "loaded the network '" + path + "'");
    return model;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Regions> regions_out_{this, kLabelled};
  apex::Output<Image> output_{this, kOutput};
  apex::Param<std::string> model_path_{this, kModel};
  apex::Param<std::string> config_{this, kConfig};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};
  apex::Param<std::vector<double>> mean_{this, kMean};
  apex::Param<double> scale_{this, kScale};
  apex::Param<bool> swap_rb_{this, kSwapRb};
  apex::Param<bool> crop_{this, kCrop};
  apex::Choice<cv::dnn::Backend> backend_{this, kBackend};
  apex::Choice<cv::dnn::Target> target_{this, kTarget};
  apex::Param<double> min_confidence_{this, kMinConfidence};
  ModelFile<DnnModel> model_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DnnNetwork, "apex_nodes/DnnNetwork");
