// apex_bench_images' cases of the ximgproc nodes (ximgproc_filters.cpp, ximgproc_shapes.cpp): each
// node against the cv::ximgproc call it makes with the same parameters (image_bench.cpp has the
// table). Inputs the 640x480 frames do not give as they are (strokes to thin, a patch small enough
// for EdgePreservingFilter) are made of them and said in the row.
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "apex_nodes/shapes.hpp"
#include "image_cases.hpp"

namespace apex_bench {

std::vector<NodeCase> ximgprocCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const std::string sink = sinkType<Image>();
  namespace xi = cv::ximgproc;
  c.push_back(imageCase("GuidedFilter", "apex_nodes/GuidedFilter", "bgr8, its own guide", {in.bgr},
                        {{"radius", "4"}, {"eps", "400"}, {"ddepth", "same"}}, "image", sink,
                        "guidedFilter 4, 400, itself as guide",
                        [out = cv::Mat()](const cv::Mat& m) mutable { xi::guidedFilter(m, m, out, 4, 400.0, -1); }));
  c.push_back(imageCase("AnisotropicDiffusion", "apex_nodes/AnisotropicDiffusion", "bgr8", {in.bgr},
                        {{"alpha", "0.1"}, {"k", "0.02"}, {"niters", "10"}}, "image", sink, "anisotropicDiffusion 0.1, 0.02, 10",
                        [out = cv::Mat()](const cv::Mat& m) mutable { xi::anisotropicDiffusion(m, out, 0.1f, 0.02f, 10); }));
  // A 9x9 window blurred around every pixel, on one thread: the middle 160x120, or a 640x480 frame takes long per frame.
  const ImagePtr patch = image(in.bgr->mat(cv::Rect(240, 180, 160, 120)).clone(), "bgr8");
  c.push_back(imageCase("EdgePreservingFilter", "apex_nodes/EdgePreservingFilter", "bgr8, its middle 160x120", {patch},
                        {{"d", "9"}, {"threshold", "20"}}, "image", sink, "edgePreservingFilter 9, 20",
                        [out = cv::Mat()](const cv::Mat& m) mutable { xi::edgePreservingFilter(m, out, 9, 20.0); }));
  c.push_back(imageCase(
      "NiblackThreshold", "apex_nodes/NiblackThreshold", "mono8", {in.gray},
      {{"max_value", "255"}, {"type", "binary"}, {"block_size", "25"}, {"k", "-0.2"}, {"binarization_method", "niblack"}},
      "image", sink, "niBlackThreshold binary, 25, -0.2, Niblack", [out = cv::Mat()](const cv::Mat& m) mutable {
        xi::niBlackThreshold(m, out, 255, cv::THRESH_BINARY, 25, -0.2, xi::BINARIZATION_NIBLACK, 128);
      }));
  cv::Mat strokes;  // lines a few pixels wide to thin to one: the Canny edges dilated 3x3
  cv::dilate(in.edges->mat, strokes, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  c.push_back(imageCase("Thinning", "apex_nodes/Thinning", "Canny edges dilated 3x3", {image(strokes, "mono8")},
                        {{"thinning_type", "zhangsuen"}}, "image", sink, "thinning Zhang-Suen",
                        [out = cv::Mat()](const cv::Mat& m) mutable { xi::thinning(m, out, xi::THINNING_ZHANGSUEN); }));
  c.push_back(imageCase("FastLineDetector", "apex_nodes/FastLineDetector", "mono8", {in.gray},
                        {{"length_threshold", "10"},
                         {"distance_threshold", "1.414213562"},
                         {"canny_th1", "50"},
                         {"canny_th2", "50"},
                         {"canny_aperture_size", "3"},
                         {"do_merge", "false"}},
                        "lines", sinkType<apex_nodes::Lines>(), "createFastLineDetector 10, 1.41, 50, 50, 3; detect",
                        [lines = std::vector<cv::Vec4f>()](const cv::Mat& m) mutable {
                          xi::createFastLineDetector(10, 1.414213562f, 50.0, 50.0, 3, false)->detect(m, lines);
                        }));
  return c;
}

}  // namespace apex_bench
