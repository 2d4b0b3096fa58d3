// The Optimizer's racing: a candidate's pass is cut once even the best score a frame can have,
// on every frame left, could not make it count (beat what the search needs of it). A cut pass
// counts as that bound, so the search takes the course it would have taken on whole passes.
// Where the bound would not hold (a mean beyond it, passes of different lengths, no mean so far
// coming) racing turns itself off for the rest of the run and says why. ROS-free.
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/param.hpp"

namespace apex_nodes {
namespace tuning {

class Racing {
 public:
  /** @brief A run starts: racing if `on`, a frame scoring at best `frame_bound` (at least, with
   *  `minimize`), `workers` passes at once. */
  void start(bool on, double frame_bound, bool minimize, std::size_t workers) {
    on_ = asked_ = on;
    frame_bound_ = frame_bound;
    minimize_ = minimize;
    full_frames_ = cuts_ = 0;
    reset(workers);
  }
  /** @brief Every pass forgotten (the run ended). */
  void reset(std::size_t workers) { passes_.assign(workers, Pass{}); }

  /** @brief Worker `w`'s pass scored one more frame, its mean so far `mean`: true if the pass is
   *  to be cut now, as it cannot reach `needed` (as the search counts: larger is better). */
  bool frame(std::size_t w, double mean, double needed) {
    Pass& p = passes_.at(w);
    if (!on_ || p.cut) return false;
    if (minimize_ ? mean < frame_bound_ : mean > frame_bound_) {
      off("a mean so far of " + apex::toText(mean) + " is beyond frame_score_bound " + apex::toText(frame_bound_) +
          ": set it to the best a frame can score");
      return false;
    }
    ++p.frames, p.mean = mean;
    if (full_frames_ == 0 || p.frames >= full_frames_) return false;
    p.bound = bound(p);
    if (p.bound >= needed) return false;
    p.cut = true;
    ++cuts_;
    return true;
  }

  /** @brief Worker `w`'s pass ended with the mean `f`: what its candidate scored, as told to the
   *  search (a cut pass: the bound it was cut at, the most it could have scored). */
  double ended(std::size_t w, double f) {
    const Pass p = std::exchange(passes_.at(w), Pass{});
    if (p.cut) return minimize_ ? -p.bound : p.bound;
    if (on_ && p.frames == 0) off("no frame's mean so far arrived: connect the mean's running to running");
    if (on_ && full_frames_ == 0) full_frames_ = p.frames;
    if (on_ && p.frames != full_frames_)
      off("passes scored " + std::to_string(full_frames_) + " and " + std::to_string(p.frames) +
          " frames: the bound needs the same number each time");
    return f;
  }

  /** @brief Why racing turned itself off since the last call; "" if it did not. */
  std::string takeWhyOff() { return std::exchange(why_off_, std::string()); }
  /** @brief Racing was asked for when the run started. */
  bool asked() const { return asked_; }
  /** @brief Passes cut in this run. */
  int cuts() const { return cuts_; }

 private:
  struct Pass {
    int frames = 0;  // scored so far
    double mean = 0;  // their mean
    bool cut = false;
    double bound = 0;  // the most it could score, as the search counts it (when cut: the value told)
  };
  /** The most the pass could score (as the search counts it) with the frames left at their best. */
  double bound(const Pass& p) const {
    const int left = std::max(0, full_frames_ - p.frames);
    const double most = (p.frames * p.mean + left * frame_bound_) / std::max(full_frames_, p.frames);
    return minimize_ ? -most : most;
  }
  void off(std::string why) {
    on_ = false;
    why_off_ = std::move(why);
  }

  std::vector<Pass> passes_;  // per worker
  bool on_ = false, asked_ = false;
  bool minimize_ = false;
  double frame_bound_ = 1;
  int full_frames_ = 0;  // frames of a whole pass (0: none seen yet; racing waits for one)
  int cuts_ = 0;
  std::string why_off_;
};

}  // namespace tuning
}  // namespace apex_nodes
