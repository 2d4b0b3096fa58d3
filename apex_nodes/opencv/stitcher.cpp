// Stitcher: overlapping images as one (cv::Stitcher): a panorama of photographs taken turning from
// one spot (panorama: rotations, a spherical surface), or a flat scene scanned by a moving camera
// (scans: affine). Each firing stitches its inputs anew, from their features; images that do not
// stitch are an error naming OpenCV's status and what it means.
#include <opencv2/imgproc.hpp>
#include <opencv2/stitching.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

std::string statusText(cv::Stitcher::Status status, std::size_t images) {
  switch (status) {
    case cv::Stitcher::ERR_NEED_MORE_IMGS:
      return "cv::Stitcher: ERR_NEED_MORE_IMGS: too few of the " + std::to_string(images) +
             " images match each other with the confidence asked (pano_confidence_thresh): do they overlap?";
    case cv::Stitcher::ERR_HOMOGRAPHY_EST_FAIL:
      return "cv::Stitcher: ERR_HOMOGRAPHY_EST_FAIL: no transform between the images could be estimated from their matches";
    case cv::Stitcher::ERR_CAMERA_PARAMS_ADJUST_FAIL:
      return "cv::Stitcher: ERR_CAMERA_PARAMS_ADJUST_FAIL: the cameras' bundle adjustment failed (mode scans suits a flat "
             "scene seen by a moving camera)";
    default:
      return "cv::Stitcher: status " + std::to_string(int(status));
  }
}

}  // namespace

class Stitcher : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage0{
      "image_0", "8-bit gray or colour; the inputs are image_0, image_1, ..., in any order; the panorama has image_0's header"};
  static inline const apex::InputPort<Image> kImage1{"image_1"};
  static inline const apex::OutputPort<Image> kPanorama{"panorama", "bgr8"};
  static inline const apex::ParamDecl<int> kInputs =
      param::integer("inputs").range(2, 8).step(1).init(2).describe("how many images: image_0, image_1, ...").shapesInterface();
  static inline const apex::ChoiceDecl<cv::Stitcher::Mode> kMode =
      param::choice<cv::Stitcher::Mode>(
          "mode", {{"panorama", cv::Stitcher::PANORAMA, "photographs turning from one spot: rotations, a spherical surface"},
                   {"scans", cv::Stitcher::SCANS, "a flat scene, the camera moving over it: affine, no wave correction"}})
          .describe("cv::Stitcher::create's mode");
  static inline const apex::ParamDecl<double> kRegistrationResol =
      param::number("registration_resol")
          .range(0.01, 10.0)
          .step(0.01)
          .init(0.6)
          .describe("megapixels the images are scaled to for finding and matching features (setRegistrationResol)");
  static inline const apex::ParamDecl<double> kConfidence =
      param::number("pano_confidence_thresh")
          .range(0.1, 10.0)
          .step(0.1)
          .init(1.0)
          .describe("how confident a match must be for two images to be stitched (setPanoConfidenceThresh)");
  static apex::Manifest manifest() {
    return apex::Manifest("Stitches overlapping images into a panorama (cv::Stitcher): photographs turned, or scans")
        .inCategory("cameras and stereo")
        .input(kImage0)
        .input(kImage1)
        .output(kPanorama)
        .param(kInputs)
        .param(kMode)
        .param(kRegistrationResol)
        .param(kConfidence)
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.inputs.clear();
          for (int i = 0; i < p.get<int>(kInputs.name()); ++i)
            m.input<Image>("image_" + std::to_string(i), i == 0 ? kImage0.description : "");
          return apex::Status::ok();
        });
  }

  void process() override {
    std::vector<cv::Mat> images;
    std::shared_ptr<const Image> first;
    for (const auto& port : interface().inputs) {
      auto in = input<Image>(port.name);
      requireImage(*in, "134");
      if (in->mat.depth() != CV_8U) throw std::invalid_argument("input '" + port.name + "' is not 8-bit: '" + in->encoding + "'");
      if (!first) first = in;
      images.push_back(bgrOf(*in));
    }
    cv::Ptr<cv::Stitcher> stitcher = cv::Stitcher::create(mode_.get());  // new each time: no state from the last
    stitcher->setRegistrationResol(registration_resol_.get());
    stitcher->setPanoConfidenceThresh(confidence_.get());
    cv::Mat panorama;
    const cv::Stitcher::Status status = stitcher->stitch(images, panorama);
    if (status != cv::Stitcher::OK) throw std::invalid_argument(statusText(status, images.size()));
    panorama_.publish(resultOf(*first, panorama, "bgr8"));
  }

 private:
  /** The image as cv::Stitcher composes it: 3-channel BGR (its blender takes no other). */
  static cv::Mat bgrOf(const Image& in) {
    const bool rgb = in.encoding.rfind("rgb", 0) == 0;
    cv::Mat out;
    if (in.mat.channels() == 1) cv::cvtColor(in.mat, out, cv::COLOR_GRAY2BGR);
    else if (in.mat.channels() == 4) cv::cvtColor(in.mat, out, rgb ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
    else if (rgb) cv::cvtColor(in.mat, out, cv::COLOR_RGB2BGR);
    else out = in.mat;  // read only
    return out;
  }

  apex::Output<Image> panorama_{this, kPanorama};
  apex::Choice<cv::Stitcher::Mode> mode_{this, kMode};
  apex::Param<double> registration_resol_{this, kRegistrationResol};
  apex::Param<double> confidence_{this, kConfidence};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Stitcher, "apex_nodes/Stitcher");
