// What the registration nodes (ICP, NDT) share: PCL's registration runs on the x, y, z views of
// source and target; the result is the source with every field moved onto the target, the
// transform as a stamped ROS transform, the fitness and whether it converged.
#pragma once

#include <pcl/common/point_tests.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "apex/core/registry.hpp"

#include "apex_nodes/cloud_transform.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {

/** @brief What a registration found. */
struct Registered {
  std::shared_ptr<Cloud> aligned;  ///< the source's points, every field, moved: in the target's frame
  std::shared_ptr<geometry_msgs::TransformStamped> transform;  ///< source frame -> target frame, at the source's stamp
  double fitness = 0;  ///< PCL's fitness score: mean squared distance to the nearest target point (m^2)
  bool converged = false;
};

/** @brief The cloud's finite points, x, y, z (registration needs no NaN); the view itself if dense. */
inline std::shared_ptr<const XyzCloud> finiteXyz(const Cloud& cloud) {
  auto xyz = xyzOf(cloud);
  if (xyz->is_dense) return xyz;
  auto out = std::make_shared<XyzCloud>();
  for (const auto& p : *xyz)
    if (pcl::isFinite(p)) out->push_back(p);
  return out;
}

/** @brief Runs `reg` (parameters set) with `source` onto `target`, from `initial` if given (it
 *  must map the source's frame into the target's: child_frame_id and frame_id are checked if set). */
template <class Registration>
Registered registerClouds(Registration& reg, const Cloud& source, const Cloud& target,
                          const geometry_msgs::TransformStamped* initial) {
  reg.setInputSource(finiteXyz(source));
  reg.setInputTarget(finiteXyz(target));
  XyzCloud moved;
  if (initial) {
    if (!initial->child_frame_id.empty() && initial->child_frame_id != source.header.frame_id)
      throw std::invalid_argument("the initial transform maps frame '" + initial->child_frame_id + "', the source is in '" +
                                  source.header.frame_id + "'");
    if (!initial->header.frame_id.empty() && initial->header.frame_id != target.header.frame_id)
      throw std::invalid_argument("the initial transform maps into frame '" + initial->header.frame_id + "', the target is in '" +
                                  target.header.frame_id + "'");
    reg.align(moved, toEigen(initial->transform).matrix());
  } else {
    reg.align(moved);
  }
  const Eigen::Matrix4f m = reg.getFinalTransformation();
  Registered r;
  r.aligned = cloudResult(source, transformPoints(*source.points, Eigen::Affine3f(m)));
  r.aligned->header.frame_id = target.header.frame_id;
  r.transform = std::make_shared<geometry_msgs::TransformStamped>();
  r.transform->header.stamp = source.header.stamp;
  r.transform->header.frame_id = target.header.frame_id;
  r.transform->child_frame_id = source.header.frame_id;
  r.transform->transform = toTransform(m);
  r.fitness = reg.getFitnessScore();
  r.converged = reg.hasConverged();
  return r;
}

/** The ports of every registration node (not in the template: a class template's static members
 *  may be initialised after the registration lines that read them). */
struct RegistrationPorts {
  static inline const apex::InputPort<Cloud> kSource{"source", "the cloud to move"};
  static inline const apex::InputPort<Cloud> kTarget{"target", "the cloud to move it onto"};
  static inline const apex::InputPort<geometry_msgs::TransformStamped> kInitial{
      "initial", "if connected: the guess to start from (source frame -> target frame)", true};
  static inline const apex::OutputPort<Cloud> kAligned{"aligned", "the source, every field, moved: in the target's frame"};
  static inline const apex::OutputPort<geometry_msgs::TransformStamped> kTransform{
      "transform", "maps the source's frame into the target's (e.g. for TransformCloud); the source's stamp"};
  static inline const apex::OutputPort<double> kFitness{"fitness", "mean squared distance to the nearest target point (m^2)"};
  static inline const apex::OutputPort<bool> kConverged{"converged"};
  /** @brief A registration node's manifest: its description and the ports, in the category
   *  "cloud registration"; add the parameters. */
  static apex::Manifest registrationManifest(std::string description) {
    return apex::Manifest(std::move(description))
        .inCategory("cloud registration")
        .input(kSource)
        .input(kTarget)
        .input(kInitial)
        .output(kAligned)
        .output(kTransform)
        .output(kFitness)
        .output(kConverged);
  }
};

/** A node shape: source and target in, PCL's `Registration` (parameters set by configure()) run by
 *  registerClouds, the aligned cloud, transform, fitness and convergence out. */
template <class Registration>
class RegistrationNode : public apex::Node, public RegistrationPorts {
 protected:
  /** @brief Sets the registration's parameters for this firing. */
  virtual void configure(Registration& registration) = 0;

 private:
  void process() final {
    Registration registration;
    configure(registration);
    const auto initial = initial_.get();
    const Registered r = registerClouds(registration, *source_.get(), *target_.get(), initial.get());
    aligned_.publish(r.aligned);
    transform_.publish(r.transform);
    fitness_.publish(r.fitness);
    converged_.publish(r.converged);
  }
  apex::Input<Cloud> source_{this, kSource};
  apex::Input<Cloud> target_{this, kTarget};
  apex::Input<geometry_msgs::TransformStamped> initial_{this, kInitial};
  apex::Output<Cloud> aligned_{this, kAligned};
  apex::Output<geometry_msgs::TransformStamped> transform_{this, kTransform};
  apex::Output<double> fitness_{this, kFitness};
  apex::Output<bool> converged_{this, kConverged};
};

}  // namespace apex_nodes
