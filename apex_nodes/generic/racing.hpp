// The Optimizer's racing: a candidate's pass is cut short once it cannot count (beat what the
// search needs of it), by one of two rules:
// - bound: even the best score a frame can have, on every frame left, could not make it count. A
//   cut pass counts as that bound, so the search takes the course it would have taken on whole
//   passes.
// - paired: it is clearly worse, frame by frame, than the evaluation it must beat (its rival: the
//   member it competes with, or the best so far), whose frame scores were kept: the upper end of a
//   one-sided confidence interval for its whole pass's mean, from the differences on the frames so
//   far (a paired t-test, as irace's races compare candidates on the same instances), is below
//   what it needs. A cut pass counts as its estimate. Far fewer frames, nearly the same course.
// The bound rule always applies; where the paired rule has no rival's frames (the first
// population, a remote worker's or a resumed run's evaluation) only the bound does. Where the
// bound would not hold (a mean beyond it, passes of different lengths, no mean so far coming)
// racing turns itself off for the rest of the run and says why. ROS-free.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace apex_nodes {
namespace tuning {

enum class RacingRule { kBound, kPaired };

/** @brief The one-sided quantile `p` of Student's t with `dof` degrees of freedom (within 1% for
 *  dof >= 3 and p in [0.5, 0.999]). */
double tQuantile(double p, int dof);

class Racing {
 public:
  /** @brief Frames a paired comparison needs before it may cut. */
  static constexpr int kMinPairedFrames = 5;

  /** @brief A run starts: racing if `on` by `rule` at `confidence` (paired), a frame scoring at
   *  best `frame_bound` (at least, with `minimize`), `workers` passes at once. */
  void start(bool on, RacingRule rule, double confidence, double frame_bound, bool minimize, std::size_t workers);
  /** @brief Every pass forgotten (the run ended). */
  void reset(std::size_t workers);

  /** @brief Worker `w`'s pass scored one more frame, its mean so far `mean`: true if the pass is
   *  to be cut now, as it cannot reach `needed` (as the search counts: larger is better), the
   *  fitness of evaluation `rival` (-1: none). */
  bool frame(std::size_t w, double mean, double needed, int rival);

  /** @brief Worker `w`'s pass of evaluation `id` ended with the mean `f`: what its candidate
   *  scored, as told to the search (a cut pass: the value it was cut at). A whole pass's frame
   *  scores are kept for the passes that will compete with it. */
  double ended(std::size_t w, int id, double f);

  /** @brief Why racing turned itself off since the last call; "" if it did not. */
  std::string takeWhyOff();
  /** @brief Racing was asked for when the run started. */
  bool asked() const { return asked_; }
  /** @brief Passes cut in this run. */
  int cuts() const { return cuts_; }
  /** @brief The share of the frames the run's passes here scored, of what they would have whole
   *  (1 before any whole pass). */
  double framesShare() const {
    return full_frames_ > 0 && passes_ended_ > 0
               ? static_cast<double>(frames_) / (static_cast<double>(full_frames_) * passes_ended_)
               : 1;
  }
  /** @brief For the Optimizer's state: e.g. "racing paired: 118 cut short, 56% of the frames
   *  scored". */
  std::string summary() const;

 private:
  struct Pass {
    std::vector<double> scores;  // per frame so far
    double mean = 0;  // their mean
    bool cut = false;
    double counted = 0;  // when cut: the value told, as the search counts it
  };
  /** The most the pass could score (as the search counts it) with the frames left at their best. */
  double bound(const Pass& p) const;
  /** As the search counts it: the estimate of the pass's whole mean, and the upper end of its
   *  one-sided interval, from its frames' differences to `rival`'s; false if there are too few. */
  bool paired(const Pass& p, const std::vector<double>& rival, double& estimate, double& upper) const;
  void off(std::string why);

  std::vector<Pass> passes_;  // per worker
  std::map<int, std::vector<double>> kept_;  // per evaluation: its whole pass's frame scores
  bool on_ = false, asked_ = false;
  RacingRule rule_ = RacingRule::kBound;
  double confidence_ = 0.95;
  bool minimize_ = false;
  double frame_bound_ = 1;
  int full_frames_ = 0;  // frames of a whole pass (0: none seen yet; racing waits for one)
  int cuts_ = 0;
  long long frames_ = 0;  // scored in the run's passes, here
  int passes_ended_ = 0;  // the run's passes here
  std::string why_off_;
};

}  // namespace tuning
}  // namespace apex_nodes
