// apex_bench_images' cases of the segmentation nodes: each against the OpenCV (ximgproc) calls it
// makes, with what the node sends besides made alike (image_bench.cpp has the table).
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "image_cases.hpp"

namespace apex_bench {

std::vector<NodeCase> segmentationCases(const Inputs& in) {
  std::vector<NodeCase> c;
  const std::string sink = sinkType<Image>();
  cv::Mat seeds;  // the Otsu mask's components as markers, as the watershed tutorial seeds it
  cv::connectedComponents(in.binary->mat, seeds, 8, CV_32S);
  const ImagePtr markers = image(seeds, "32SC1");
  c.push_back(fixedCase("Watershed", "apex_nodes/Watershed", "bgr8, the Otsu mask's components as markers",
                        feedType<Image, Image>(), {"image", "markers"}, {msg(in.bgr), msg(markers)}, {}, "markers", sink,
                        "copy the markers, watershed", [bgr = in.bgr->mat, seeds, out = cv::Mat()]() mutable {
                          seeds.copyTo(out);
                          cv::watershed(bgr, out);
                        }));
  c.push_back(imageCase("GrabCut", "apex_nodes/GrabCut", "bgr8", {in.bgr},
                        {{"x", "100"}, {"y", "80"}, {"width", "400"}, {"height", "300"}, {"iter_count", "1"}}, "mask", sink,
                        "setRNGSeed, grabCut 1 round from a rectangle, the object's mask",
                        [model = cv::Mat(), bgd = cv::Mat(), fgd = cv::Mat(), out = cv::Mat()](const cv::Mat& m) mutable {
                          cv::setRNGSeed(1);
                          cv::grabCut(m, model, cv::Rect(100, 80, 400, 300), bgd, fgd, 1, cv::GC_INIT_WITH_RECT);
                          out = (model == cv::GC_FGD) | (model == cv::GC_PR_FGD);
                        }));
  c.push_back(imageCase(
      "KMeansColours", "apex_nodes/KMeansColours", "bgr8", {in.bgr}, {{"k", "4"}, {"attempts", "1"}, {"max_count", "10"}},
      "image", sink, "pixels as floats, setRNGSeed, kmeans 4 (k-means++), each pixel its centre's colour",
      [samples = cv::Mat(), labels = cv::Mat(), centres = cv::Mat(), colours = cv::Mat(),
       out = cv::Mat()](const cv::Mat& m) mutable {
        m.convertTo(samples, CV_32F);
        cv::setRNGSeed(1);
        cv::kmeans(samples.reshape(1, int(m.total())), 4, labels,
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 10, 1.0), 1, cv::KMEANS_PP_CENTERS, centres);
        centres.convertTo(colours, CV_8U);
        out.create(m.size(), m.type());
        const int* label = labels.ptr<int>();
        for (std::size_t i = 0; i < m.total(); ++i) std::copy_n(colours.ptr<uchar>(label[i]), 3, out.data + 3 * i);
      }));
  c.push_back(imageCase("ConnectedComponents", "apex_nodes/ConnectedComponents", "binary (Otsu)", {in.binary}, {}, "labels", sink,
                        "connectedComponentsWithStats 8",
                        [labels = cv::Mat(), stats = cv::Mat(), centroids = cv::Mat()](const cv::Mat& m) mutable {
                          cv::connectedComponentsWithStats(m, labels, stats, centroids, 8, CV_32S);
                        }));
  c.push_back(imageCase("Superpixels", "apex_nodes/Superpixels", "bgr8", {in.bgr},
                        {{"algorithm", "slico"}, {"region_size", "20"}, {"num_iterations", "4"}}, "labels", sink,
                        "createSuperpixelSLIC SLICO 20, iterate 4, enforceLabelConnectivity, labels and contour mask",
                        [labels = cv::Mat(), mask = cv::Mat()](const cv::Mat& m) mutable {
                          auto s = cv::ximgproc::createSuperpixelSLIC(m, cv::ximgproc::SLICO, 20, 10.0f);
                          s->iterate(4);
                          s->enforceLabelConnectivity(25);
                          s->getLabels(labels);
                          s->getLabelContourMask(mask, false);
                        }));
  return c;
}

}  // namespace apex_bench
