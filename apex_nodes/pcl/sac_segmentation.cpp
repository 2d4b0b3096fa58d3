// SACSegmentation: one model (plane, line, circle, sphere, cylinder...) fitted by a sample
// consensus method: its inliers and outliers, whole points, and its coefficients. The models that
// weigh normals read the cloud's normal_x..z (NormalEstimation). ProjectInliers: a cloud's points
// moved onto such a model, every other field kept.
#include <pcl/filters/project_inliers.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/sample_consensus/sac_model_circle3d.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud.hpp"
#include "three_numbers.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

struct Model {
  const char* name;
  pcl::SacModel type;
  std::size_t coefficients;  // how many PCL gives and takes
  bool normals;  // weighs each point's normal (SACSegmentationFromNormals)
};
const Model kModels[] = {
    {"plane", pcl::SACMODEL_PLANE, 4, false},
    {"line", pcl::SACMODEL_LINE, 6, false},
    {"circle2d", pcl::SACMODEL_CIRCLE2D, 3, false},
    {"circle3d", pcl::SACMODEL_CIRCLE3D, 7, false},
    {"sphere", pcl::SACMODEL_SPHERE, 4, false},
    {"cylinder", pcl::SACMODEL_CYLINDER, 7, true},
    {"parallel_line", pcl::SACMODEL_PARALLEL_LINE, 6, false},
    {"parallel_plane", pcl::SACMODEL_PARALLEL_PLANE, 4, false},
    {"perpendicular_plane", pcl::SACMODEL_PERPENDICULAR_PLANE, 4, false},
    {"normal_plane", pcl::SACMODEL_NORMAL_PLANE, 4, true},
    {"normal_parallel_plane", pcl::SACMODEL_NORMAL_PARALLEL_PLANE, 4, true},
    {"normal_sphere", pcl::SACMODEL_NORMAL_SPHERE, 4, true},
};
const apex::Option<int> kMethods[] = {{"ransac", pcl::SAC_RANSAC},   {"lmeds", pcl::SAC_LMEDS}, {"msac", pcl::SAC_MSAC},
                                      {"rransac", pcl::SAC_RRANSAC}, {"rmsac", pcl::SAC_RMSAC}, {"mlesac", pcl::SAC_MLESAC},
                                      {"prosac", pcl::SAC_PROSAC}};

/** The models named (all of them if none is): a choice's options, each valued by its Model. */
std::vector<apex::Option<const Model*>> models(const std::vector<std::string>& names = {}) {
  std::vector<apex::Option<const Model*>> out;
  for (const Model& m : kModels)
    if (names.empty() || std::find(names.begin(), names.end(), m.name) != names.end()) out.push_back({m.name, &m});
  return out;
}

/** The cloud's normal_x, normal_y, normal_z and curvature (float32; a normal plane weighs the
 *  normals less where it is high), one per point; curvature 0 if the cloud has none. */
pcl::PointCloud<pcl::Normal>::Ptr normalsOf(const Cloud& in, const std::string& model) {
  const Blob& p = *in.points;
  const char* const names[4] = {"normal_x", "normal_y", "normal_z", "curvature"};
  const pcl::PCLPointField* fields[4];
  for (int k = 0; k < 4; ++k) {
    auto f = std::find_if(p.fields.begin(), p.fields.end(), [&](const auto& f) { return f.name == names[k]; });
    fields[k] = f != p.fields.end() && f->datatype == pcl::PCLPointField::FLOAT32 ? &*f : nullptr;
    if (!fields[k] && k < 3)
      throw std::invalid_argument("the model '" + model + "' needs each point's normal, and the cloud has no float32 field '" +
                                  names[k] + "' (its fields: " + fieldNames(p) +
                                  "): put a NormalEstimation before the SACSegmentation");
  }
  auto out = std::make_shared<pcl::PointCloud<pcl::Normal>>(p.width, p.height);  // curvature 0
  for (std::size_t i = 0; i < out->size(); ++i) {
    const std::uint8_t* point = &p.data[(i / p.width) * p.row_step + (i % p.width) * p.point_step];
    pcl::Normal& n = (*out)[i];
    float* const to[4] = {&n.normal_x, &n.normal_y, &n.normal_z, &n.curvature};
    for (int k = 0; k < 4; ++k)
      if (fields[k]) std::memcpy(to[k], point + fields[k]->offset, sizeof(float));
  }
  return out;
}

}  // namespace

class SACSegmentation : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud"};
  static inline const apex::OutputPort<Cloud> kInliers{"inliers", "the model's points"};
  static inline const apex::OutputPort<Cloud> kOutliers{"outliers", "everything else"};
  static inline const apex::OutputPort<std::vector<double>> kCoefficients{
      "coefficients",
      "as PCL gives them: plane a, b, c, d; line point, direction; circle2d x, y, r; circle3d centre, r, "
      "normal; sphere centre, r; cylinder point on the axis, direction, r"};
  static inline const apex::OutputPort<int> kCount{"count", "inliers"};
  static inline const apex::ChoiceDecl<const Model*> kModel =
      param::choice<const Model*>("model", models()).describe("cylinder and the normal_ models need normals (NormalEstimation)");
  static inline const apex::ChoiceDecl<int> kMethod = param::choice<int>("method", {std::begin(kMethods), std::end(kMethods)});
  static inline const apex::ParamDecl<double> kDistanceThreshold =
      param::number("distance_threshold").range(0.0001, 1.0).step(0.0001).init(0.02).describe("metres");
  static inline const apex::ParamDecl<int> kMaxIterations = param::integer("max_iterations").range(1, 100000).step(1).init(200);
  static inline const apex::ParamDecl<bool> kOptimize =
      param::flag("optimize_coefficients").init(true).describe("refit the model to its inliers");
  static inline const apex::ParamDecl<apex::Interval> kRadius =
      param::interval("radius")
          .range(0.0, 100.0)
          .step(0.001)
          .init({0.0, 10.0})
          .describe("metres: a circle's, sphere's or cylinder's radius");
  static inline const apex::ParamDecl<std::vector<double>> kAxis =
      param::list("axis").init({0, 0, 1}).describe("x, y, z: the direction parallel/perpendicular models and cylinders keep to");
  static inline const apex::ParamDecl<double> kEpsAngle =
      param::angle("eps_angle")
          .range(0.0, 1.5707963267948966)
          .init(0.0)
          .describe("how far from `axis` the model's axis or normal may turn; 0: any direction (PCL's default)");
  static inline const apex::ParamDecl<double> kNormalDistanceWeight =
      param::number("normal_distance_weight")
          .range(0.0, 1.0)
          .step(0.01)
          .init(0.1)
          .describe("cylinder and normal_ models: weight of the normals' angle against the distance");
  static apex::Manifest manifest() {
    return apex::Manifest("Fits a model (plane, line, circle, sphere, cylinder...) by sample consensus")
        .inCategory("cloud segmentation")
        .input(kCloud)
        .output(kInliers)
        .output(kOutliers)
        .output(kCoefficients)
        .output(kCount)
        .param(kModel)
        .param(kMethod)
        .param(kDistanceThreshold)
        .param(kMaxIterations)
        .param(kOptimize)
        .param(kRadius)
        .param(kAxis)
        .param(kEpsAngle)
        .param(kNormalDistanceWeight);
  }
  void process() override {
    const auto in = cloud_.get();
    const auto xyz = xyzOf(*in);
    const Model& model = *model_.get();
    pcl::PointIndices inliers;
    pcl::ModelCoefficients coefficients;
    if (model.normals) {
      pcl::SACSegmentationFromNormals<pcl::PointXYZ, pcl::Normal> seg;
      seg.setInputNormals(normalsOf(*in, model.name));
      seg.setNormalDistanceWeight(normal_distance_weight_.get());
      fit(seg, xyz, model, inliers, coefficients);
    } else {
      pcl::SACSegmentation<pcl::PointXYZ> seg;
      fit(seg, xyz, model, inliers, coefficients);
    }
    if (inliers.indices.empty()) {
      std::ostringstream why;
      why << "no " << model.name << " found in " << xyz->size() << " points (" << method_.text() << ", distance_threshold "
          << distance_threshold_.get() << ")";
      throw std::invalid_argument(why.str());
    }
    inliers_.publish(cloudResult(*in, selectPoints(*in->points, inliers.indices)));
    outliers_.publish(cloudResult(*in, selectPoints(*in->points, complement(inliers.indices, xyz->size()))));
    coefficients_.publish(std::vector<double>(coefficients.values.begin(), coefficients.values.end()));
    count_.publish(static_cast<int>(inliers.indices.size()));
  }

 private:
  template <class Segmentation>
  void fit(Segmentation& seg, const std::shared_ptr<const XyzCloud>& xyz, const Model& model, pcl::PointIndices& inliers,
           pcl::ModelCoefficients& coefficients) const {
    seg.setOptimizeCoefficients(optimize_.get());
    seg.setModelType(model.type);
    seg.setMethodType(method_.get());
    seg.setDistanceThreshold(distance_threshold_.get());
    seg.setMaxIterations(max_iterations_.get());
    seg.setRadiusLimits(radius_.get().low, radius_.get().high);
    seg.setAxis(threeNumbers(axis_.get(), "axis"));
    seg.setEpsAngle(eps_angle_.get());
    seg.setInputCloud(xyz);
    seg.segment(inliers, coefficients);
  }
  apex::Input<Cloud> cloud_{this, kCloud};
  apex::Output<Cloud> inliers_{this, kInliers};
  apex::Output<Cloud> outliers_{this, kOutliers};
  apex::Output<std::vector<double>> coefficients_{this, kCoefficients};
  apex::Output<int> count_{this, kCount};
  apex::Choice<const Model*> model_{this, kModel};
  apex::Choice<int> method_{this, kMethod};
  apex::Param<double> distance_threshold_{this, kDistanceThreshold};
  apex::Param<int> max_iterations_{this, kMaxIterations};
  apex::Param<bool> optimize_{this, kOptimize};
  apex::Param<apex::Interval> radius_{this, kRadius};
  apex::Param<std::vector<double>> axis_{this, kAxis};
  apex::Param<double> eps_angle_{this, kEpsAngle};
  apex::Param<double> normal_distance_weight_{this, kNormalDistanceWeight};
};

class ProjectInliers : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud"};
  static inline const apex::InputPort<std::vector<double>> kCoefficients{"coefficients", "the model's (SACSegmentation's)"};
  static inline const apex::OutputPort<Cloud> kCloudOut{"cloud", "every point, moved onto the model"};
  static inline const apex::ChoiceDecl<const Model*> kModel =
      param::choice<const Model*>("model", models({"plane", "line", "circle2d", "circle3d", "sphere", "cylinder"}))
          .describe("the coefficients' model; a parallel, perpendicular or normal_ plane's are a plane's");
  static apex::Manifest manifest() {
    return apex::Manifest("Moves each point onto a model (its nearest point on a plane, line, sphere...)")
        .inCategory("cloud segmentation")
        .input(kCloudIn)
        .input(kCoefficients)
        .output(kCloudOut)
        .param(kModel);
  }
  void process() override {
    const auto in = cloud_in_.get();
    const auto& values = *coefficients_.get();
    const Model& model = *model_.get();
    if (values.size() != model.coefficients)
      throw std::invalid_argument("a " + std::string(model.name) + " has " + std::to_string(model.coefficients) +
                                  " coefficients, the input has " + std::to_string(values.size()));
    const auto xyz = xyzOf(*in, xyz_.next());
    XyzCloud& projected = projected_;
    projected.clear();  // PCL leaves it as it was if it cannot start
    if (model.type == pcl::SACMODEL_CIRCLE3D) {  // pcl::ProjectInliers has no circle3d
      pcl::SampleConsensusModelCircle3D<pcl::PointXYZ> circle(xyz);
      pcl::Indices all(xyz->size());
      std::iota(all.begin(), all.end(), 0);
      Eigen::VectorXf c(values.size());
      for (std::size_t i = 0; i < values.size(); ++i) c[Eigen::Index(i)] = static_cast<float>(values[i]);
      circle.projectPoints(all, c, projected, true);
    } else {
      pcl::ProjectInliers<pcl::PointXYZ> project;
      auto c = std::make_shared<pcl::ModelCoefficients>();
      c->values.assign(values.begin(), values.end());
      project.setModelType(model.type);
      project.setModelCoefficients(c);
      project.setCopyAllData(true);
      project.setInputCloud(xyz);
      project.filter(projected);
    }
    if (projected.size() != xyz->size())
      throw std::invalid_argument("PCL could not project onto the " + std::string(model.name) +
                                  " (its coefficients are invalid)");
    cloud_out_.publish(cloudResult(*in, withXyz(*in->points, projected, points_.next())));
  }

 private:
  /** A copy of `points` in `out` with x, y, z from `xyz` (organised as `points`). */
  static std::shared_ptr<Blob> withXyz(const Blob& points, const XyzCloud& xyz, std::shared_ptr<Blob> out) {
    *out = points;  // a reused Blob keeps its bytes' memory
    std::uint32_t offsets[3] = {0, 0, 0};  // xyzOf found all three
    for (const auto& f : points.fields)
      if (f.name.size() == 1 && f.name[0] >= 'x' && f.name[0] <= 'z') offsets[f.name[0] - 'x'] = f.offset;
    std::size_t i = 0;
    for (std::size_t row = 0; row < points.height; ++row) {
      std::uint8_t* point = &out->data[row * points.row_step];
      for (std::size_t col = 0; col < points.width; ++col, ++i, point += points.point_step)
        for (int k = 0; k < 3; ++k) std::memcpy(point + offsets[k], &xyz[i].data[k], sizeof(float));
    }
    return out;
  }
  Reused<XyzCloud> xyz_;  // the x, y, z view, its projection and the points sent: reused per frame
  XyzCloud projected_;
  Reused<Blob> points_;
  apex::Input<Cloud> cloud_in_{this, kCloudIn};
  apex::Input<std::vector<double>> coefficients_{this, kCoefficients};
  apex::Output<Cloud> cloud_out_{this, kCloudOut};
  apex::Choice<const Model*> model_{this, kModel};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::SACSegmentation, "apex_nodes/SACSegmentation");
APEX_REGISTER_NODE(apex_nodes::ProjectInliers, "apex_nodes/ProjectInliers");
