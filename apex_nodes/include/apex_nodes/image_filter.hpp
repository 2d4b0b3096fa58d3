// A node shape: one image in, one image out. The shape takes the frame, checks it (not empty,
// the channel counts the filter handles), gives the filter an output that carries the frame's
// header and encoding and reuses the last output's pixels when nobody holds them
// (OutputBuffer), and publishes it. A filter is its manifest and one body:
//
//   class GaussianBlur : public ImageFilter {
//    public:
//     static inline const apex::ParamDecl<int> kKernel = apex::param::integer("kernel_size").range(1, 31).step(2).init(5);
//     static apex::Manifest manifest() { return filterManifest("Smooths an image").param(kKernel); }
//    private:
//     void filter(const Image& in, Image& out) override {
//       cv::GaussianBlur(in.mat, out.mat, cv::Size(kernel_.get(), kernel_.get()), 0);
//     }
//     apex::Param<int> kernel_{this, kKernel};
//   };
//
// A filter whose settings leave a frame as it is (Rotate by 0, Resize to the same size...) says so
// in passesThrough(): the shape then sends the frame's own message, no copy made (messages are
// immutable, so the receivers share it safely). It is asked after the checks, before filter().
#pragma once

#include <string>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class ImageFilter : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImageIn{"image", "the frame"};
  static inline const apex::OutputPort<Image> kImageOut{"image", "the frame, filtered"};

  /** @brief A filter's manifest: its description and the two ports (an output of another name,
   *  such as Canny's "edges", replaces "image"; the constructor names it too), in the category
   *  "image filters" (a filter of another kind calls inCategory() after). */
  static apex::Manifest filterManifest(std::string description, const apex::InputPort<Image>& in = kImageIn,
                                       const apex::OutputPort<Image>& out = kImageOut) {
    return apex::Manifest(std::move(description)).inCategory("image filters").input(in).output(out);
  }

 protected:
  /** `channels`: the channel counts the filter handles ("1": single-channel only); `depth8`:
   *  8-bit pixels only. Both checked before filter() runs, with an error naming the image. */
  explicit ImageFilter(std::string channels = "134", bool depth8 = false, const apex::InputPort<Image>& in = kImageIn,
                       const apex::OutputPort<Image>& out = kImageOut)
      : channels_(std::move(channels)), depth8_(depth8), in_(this, in), out_(this, out) {}

  /** @brief Fills `out.mat` from `in`; `out.encoding` starts as the input's (set it when the
   *  result's differs, e.g. "mono8"). Throwing refuses the frame: the node shows the error and
   *  sends Nothing. */
  virtual void filter(const Image& in, Image& out) = 0;

  /** @brief True when filter() would give `in` itself (the same pixels, encoding and header):
   *  the frame's message is sent as it came, filter() not called. Only where that is exact. */
  virtual bool passesThrough(const Image& /*in*/) const { return false; }

 private:
  void process() final {
    const Image& in = *in_.get();
    requireImage(in, channels_);
    if (depth8_ && in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
    if (passesThrough(in)) {  // the frame as it came: no copy
      out_.publishMessage(in_.take());
      return;
    }
    auto out = buffer_.next(in);
    out->encoding = in.encoding;
    filter(in, *out);
    out_.publish(out);
  }

  std::string channels_;
  bool depth8_;
  apex::Input<Image> in_;
  apex::Output<Image> out_;
  OutputBuffer buffer_;
};

}  // namespace apex_nodes
