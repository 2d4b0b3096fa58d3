// The model KalmanFilter and MultiObjectTracker give cv::KalmanFilter: a point of the image (a
// region's middle) moving at a steady speed, its state x, y, vx, vy, measured where it is (x, y).
// Its speed changes by random accelerations, white noise of variance process_noise over each step;
// a measurement errs by noise of variance measurement_noise (pixels²) in x and in y.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/video/tracking.hpp>

namespace apex_nodes {

/** The variance of the speed when a filter starts: unknown (a standard deviation of 100 pixels per
 *  unit of time), so that its first measurements set it. */
constexpr double kUnknownSpeedVariance = 1e4;

/** @brief The middle of a box, as the library's regions give it (boxRegion: x + (width - 1) / 2). */
inline cv::Point2d middleOf(const cv::Rect2d& box) { return {box.x + (box.width - 1) / 2.0, box.y + (box.height - 1) / 2.0}; }

/** @brief A box of `size` whose middle (middleOf) is `p`, in whole pixels. */
inline cv::Rect boxAround(const cv::Point2d& p, const cv::Size& size) {
  return {cvRound(p.x - (size.width - 1) / 2.0), cvRound(p.y - (size.height - 1) / 2.0), size.width, size.height};
}

/** @brief A filter (CV_64F) that starts at `p`, at rest: its position as uncertain as a
 *  measurement, its speed unknown. Call setStep before each predict(). */
inline cv::KalmanFilter constantVelocityAt(const cv::Point2d& p, double measurement_noise) {
  cv::KalmanFilter kf(4, 2, 0, CV_64F);
  kf.measurementMatrix = (cv::Mat_<double>(2, 4) << 1, 0, 0, 0, 0, 1, 0, 0);
  kf.statePost = (cv::Mat_<double>(4, 1) << p.x, p.y, 0, 0);
  const double r = measurement_noise, v = kUnknownSpeedVariance;
  kf.errorCovPost = (cv::Mat_<double>(4, 4) << r, 0, 0, 0, 0, r, 0, 0, 0, 0, v, 0, 0, 0, 0, v);
  return kf;
}

/** @brief The step to the next measurement, `dt` later: x += vx dt, y += vy dt, and the noises. An
 *  acceleration a over the step moves the point by a dt²/2 and changes its speed by a dt, hence
 *  the process noise's covariance, q times (dt⁴/4, dt³/2; dt³/2, dt²) for each axis. */
inline void setStep(cv::KalmanFilter& kf, double dt, double process_noise, double measurement_noise) {
  kf.transitionMatrix = (cv::Mat_<double>(4, 4) << 1, 0, dt, 0, 0, 1, 0, dt, 0, 0, 1, 0, 0, 0, 0, 1);
  const double q = process_noise, pp = q * dt * dt * dt * dt / 4, pv = q * dt * dt * dt / 2, vv = q * dt * dt;
  kf.processNoiseCov = (cv::Mat_<double>(4, 4) << pp, 0, pv, 0, 0, pp, 0, pv, pv, 0, vv, 0, 0, pv, 0, vv);
  const double r = measurement_noise;
  kf.measurementNoiseCov = (cv::Mat_<double>(2, 2) << r, 0, 0, r);
}

/** @brief The point of a state (statePre or statePost): x, y. */
inline cv::Point2d pointOf(const cv::Mat& state) { return {state.at<double>(0), state.at<double>(1)}; }

}  // namespace apex_nodes
