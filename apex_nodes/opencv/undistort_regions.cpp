// UndistortRegions: regions found in a raw (distorted) image, moved to where they are in the
// rectified image (cv::undistortPoints with the camera's K, D, R and P, as image_geometry's
// rectifyPoint): the centroid, and the box as the bounds of its corners moved.
#include <opencv2/calib3d.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/camera_model.hpp"

namespace apex_nodes {

class UndistortRegions : public apex::Node {
 public:
  static inline const apex::InputPort<Regions> kRegions{"regions", "found in the raw image"};
  static inline const apex::InputPort<sensor_msgs::CameraInfo> kInfo{"camera_info", "the raw image's camera model"};
  static inline const apex::OutputPort<Regions> kRectified{"regions", "where they are in the rectified image"};
  static apex::Manifest manifest() {
    return apex::Manifest("Moves regions of a raw image to the rectified image (undistorted points)")
        .inCategory("cameras and stereo")
        .input(kRegions)
        .input(kInfo)
        .output(kRectified);
  }
  void process() override {
    const auto in = regions_.get();
    const auto& info = *info_.get();
    requireCameraFor(info);
    const cv::Matx33d K(info.K.data()), R(info.R.data());
    const cv::Matx34d P(info.P.data());
    std::vector<cv::Point2d> raw;  // per region: the centroid and the box's four corners
    for (const auto& r : in->regions) {
      const cv::Rect b = r.box;
      raw.insert(raw.end(), {r.centroid, cv::Point2d(b.x, b.y), cv::Point2d(b.x + b.width, b.y), cv::Point2d(b.x, b.y + b.height),
                             cv::Point2d(b.x + b.width, b.y + b.height)});
    }
    std::vector<cv::Point2d> moved;
    if (!raw.empty()) cv::undistortPoints(raw, moved, K, cv::Mat(info.D), R, P);
    auto out = std::make_shared<Regions>(*in);
    for (std::size_t i = 0; i < out->regions.size(); ++i) {
      const cv::Point2d* p = &moved[5 * i];
      out->regions[i].centroid = p[0];
      double x0 = p[1].x, y0 = p[1].y, x1 = x0, y1 = y0;
      for (int k = 2; k < 5; ++k)
        x0 = std::min(x0, p[k].x), y0 = std::min(y0, p[k].y), x1 = std::max(x1, p[k].x), y1 = std::max(y1, p[k].y);
      out->regions[i].box =
          cv::Rect(cv::Point(int(std::floor(x0)), int(std::floor(y0))), cv::Point(int(std::ceil(x1)), int(std::ceil(y1))));
    }
    rectified_.publish(std::move(out));
  }

 private:
  apex::Input<Regions> regions_{this, kRegions};
  apex::Input<sensor_msgs::CameraInfo> info_{this, kInfo};
  apex::Output<Regions> rectified_{this, kRectified};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::UndistortRegions, "apex_nodes/UndistortRegions");
