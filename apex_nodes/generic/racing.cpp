#include "racing.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "apex/core/param.hpp"

namespace apex_nodes {
namespace tuning {

double tQuantile(double p, int dof) {
  double lo = 0, hi = 10;  // the normal quantile z: Phi(z) = p, by bisection
  for (int i = 0; i < 60; ++i) {
    const double mid = (lo + hi) / 2;
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  const double z = lo, z3 = z * z * z, z5 = z3 * z * z, v = std::max(dof, 1);
  // Cornish-Fisher: t from z in powers of 1/dof
  return z + (z3 + z) / (4 * v) + (5 * z5 + 16 * z3 + 3 * z) / (96 * v * v);
}

void Racing::start(bool on, RacingRule rule, double confidence, double frame_bound, bool minimize, std::size_t workers) {
  on_ = asked_ = on;
  rule_ = rule;
  confidence_ = confidence;
  frame_bound_ = frame_bound;
  minimize_ = minimize;
  full_frames_ = cuts_ = 0;
  frames_ = 0;
  passes_ended_ = 0;
  kept_.clear();
  reset(workers);
}

void Racing::reset(std::size_t workers) { passes_.assign(workers, Pass{}); }

bool Racing::frame(std::size_t w, double mean, double needed, int rival) {
  Pass& p = passes_.at(w);
  if (!on_ || p.cut) return false;
  if (minimize_ ? mean < frame_bound_ : mean > frame_bound_) {
    off("a mean so far of " + apex::toText(mean) + " is beyond frame_score_bound " + apex::toText(frame_bound_) +
        ": set it to the best a frame can score");
    return false;
  }
  const double n = static_cast<double>(p.scores.size()) + 1;
  p.scores.push_back(n * mean - (n - 1) * p.mean);  // this frame's score, from the two means
  p.mean = mean;
  const int frames = static_cast<int>(p.scores.size());
  if (full_frames_ == 0 || frames >= full_frames_) return false;
  double counted = bound(p);
  bool cut = counted < needed;
  const auto kept = rule_ == RacingRule::kPaired ? kept_.find(rival) : kept_.end();
  double estimate = 0, upper = 0;
  if (!cut && kept != kept_.end() && paired(p, kept->second, estimate, upper) && upper < needed)
    cut = true, counted = std::min(counted, estimate);
  if (!cut) return false;
  p.cut = true;
  p.counted = counted;
  ++cuts_;
  return true;
}

double Racing::ended(std::size_t w, int id, double f) {
  Pass p = std::exchange(passes_.at(w), Pass{});
  frames_ += static_cast<long long>(p.scores.size());
  ++passes_ended_;
  if (p.cut) return minimize_ ? -p.counted : p.counted;
  const int frames = static_cast<int>(p.scores.size());
  if (on_ && frames == 0) off("no frame's mean so far arrived: connect the mean's running to running");
  if (on_ && full_frames_ == 0) full_frames_ = frames;
  if (on_ && frames != full_frames_)
    off("passes scored " + std::to_string(full_frames_) + " and " + std::to_string(frames) +
        " frames: the bound needs the same number each time");
  if (on_ && rule_ == RacingRule::kPaired) kept_[id] = std::move(p.scores);
  return f;
}

std::string Racing::summary() const {
  return std::string("racing ") + (rule_ == RacingRule::kPaired ? "paired" : "bound") + ": " + std::to_string(cuts_) +
         " cut short, " + std::to_string(static_cast<int>(std::lround(100 * framesShare()))) + "% of the frames scored";
}

std::string Racing::takeWhyOff() { return std::exchange(why_off_, std::string()); }

double Racing::bound(const Pass& p) const {
  const int frames = static_cast<int>(p.scores.size());
  const int left = std::max(0, full_frames_ - frames);
  const double most = (frames * p.mean + left * frame_bound_) / std::max(full_frames_, frames);
  return minimize_ ? -most : most;
}

bool Racing::paired(const Pass& p, const std::vector<double>& rival, double& estimate, double& upper) const {
  const int n = static_cast<int>(p.scores.size());
  if (n < kMinPairedFrames || static_cast<int>(rival.size()) != full_frames_) return false;
  const double sign = minimize_ ? -1 : 1;  // as the search counts: larger is better
  double sum = 0, rival_sum = 0;
  for (int i = 0; i < n; ++i) sum += sign * (p.scores[i] - rival[i]);
  for (double r : rival) rival_sum += sign * r;
  const double m = sum / n;
  double squares = 0;
  for (int i = 0; i < n; ++i) squares += std::pow(sign * (p.scores[i] - rival[i]) - m, 2);
  const double sd = std::sqrt(squares / (n - 1));
  const double left = full_frames_ - n;
  // the frames left: their sum of differences, estimated from the mean so far, with its spread
  // (each frame's own, and the mean's uncertainty over all of them)
  const double spread = tQuantile(confidence_, n - 1) * sd * std::sqrt(left + left * left / n);
  estimate = (rival_sum + sum + left * m) / full_frames_;
  upper = estimate + spread / full_frames_;
  return true;
}

void Racing::off(std::string why) {
  on_ = false;
  why_off_ = std::move(why);
}

}  // namespace tuning
}  // namespace apex_nodes
