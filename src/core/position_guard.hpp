// Position feedback kept only where it closes the joints it moves.
//
//     pin (static) o
//                   \  a 13 m arm                 A joint set that cannot all be met (a loop
//                    \                            that does not close, a distance joint shorter
//   [c0]-[c1]-[c2]-[c3]-[c4]-[c5]-[c6]-[c7]       than its bodies allow) has no pose for the
//     \_______________/     \__________/          feedback to converge to: each correction closes
//     weld, anchored 9 m    distance 1 m where    one joint by opening the next, and the bodies
//     away                  4 m fit               move with every step, without any velocity.
//
// Measured (issue 26): an eight-link chain hinged end to end, pinned by a long arm to a static
// ground and given random joints between its links walked up to 1,085 m from its pin (substep,
// 40 seeds; ngs 388 m, soft 452 m) and through the ground it lay on; substep without position
// passes stayed within 19 m. So the moving bodies that joints join are grouped, and each group's
// joint error (PositionError::squared) summed before the feedback and after it:
//
// - ngs, substep: a group whose error a pass's joints made larger gets its poses from before
//   them back, and its joints' impulses are forgotten: they were a tug of war between joints that
//   cannot all hold, and warm starting them on arms that moved pumped energy into such groups
//   (measured with a guard that judged every group open over 2 cm: the core soak's substep runs
//   whose energy grew, 6 of 600 seeds keeping them, 2 forgetting them);
// - soft: its bias has moved the bodies by the end of the step, with nothing to undo; a group
//   whose error grew over the step solves its next step without bias (Joint::feedbackWithheld).
//   Forgetting its impulses too let more soft runs of the soak gain energy (6 of 600 against 2,
//   measured with a guard that judged groups open over 0.2 m).
// - baumgarte: its bias is momentum, which withholding it a step does not take back (2,460 m
//   either way: the chain flew at up to 400 m/s). So a group judged at the step's start is
//   solved as ngs solves it: its joints without bias and its bodies' contacts without push (a
//   push against joints held rigid grew its impulse without bound: 3 soak runs gained energy),
//   then its joints closed by guarded passes after the positions move. Its joints' impulses are
//   kept: forgotten, the velocity iterations alone no longer held the pinned chain (2,184 m,
//   measured before its contacts were split too).
//   The sweep is made every step (below, measureStepStart): 17 m in the 40 seeds, 27 m with
//   rests; core soak, seeds 1-600: 8 runs gained energy before, 1-3 now.
//
// Only a group far open is judged (kJudgedError), so scenes whose joints can all hold run as
// before: no pinned scene's hash changed, nor any error figure of substep on v3's scenes. The
// guard costs two sweeps over the joints a pass (soft: a step) while armed, which it is only
// while a joint is open wider than kJudgedError; a step it found nothing worse in rests it for
// 1, 3, 7, then 15 steps, and so does a soft step that found no joint that wide.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace impulse2d {

class PositionGuard {
 public:
  /// A group is judged when its joints are open by this much, root mean square (m, a radian
  /// weighing as a metre), and the guard arms only while a joint is open wider: above what the
  /// solvers leave open in scenes whose joints can all hold (v3_rain: substep 0.18 m, ngs 0.53 m;
  /// v3_joint_grid, which ngs, soft and baumgarte tear 45-81 m open at worst: 0.9-1.1 m), below
  /// what the chain above walks with (1-15 m, median 5 m).
  static constexpr double kJudgedError = 1.2;
  /// The longest rest after a step the guard found nothing worse in.
  static constexpr int kMaxRestSteps = 15;

  /// Whether this step is guarded.
  bool armed() const { return armed_; }

  /// NGS solvers, after the step's passes (`widest`: the widest joint error they met): closes
  /// this step and arms the next unless it rests.
  void settle(double widest) {
    close();
    armed_ = !restOneStep() && widest > kJudgedError;
  }

  /// The soft step (and baumgarte's), as it begins: closes the last step and, unless resting,
  /// sweeps the joints (visit(note) calls note(entryA, entryB, squaredError) for each, -1 for a
  /// body the step does not move); a joint open wider than kJudgedError arms this step and
  /// measures the groups. Without one the guard rests too, so that the sweep is not made every
  /// step. Without `rests` (baumgarte) it sweeps every step: a joint made or a body teleported
  /// during a rest opens a group at once, and baumgarte's bias pumps it until the guard wakes
  /// (core soak, seeds 1-600: 4 runs gained energy with rests, 1-3 without, run to run).
  template <class Visit>
  void measureStepStart(int entryCount, const Visit& visit, bool rests = true) {
    if (rests) close();
    foundWorse_ = false;
    armed_ = false;
    if (rests && restOneStep()) return;
    record(visit, true);
    double widest = 0.0;
    for (const double error : jointErrors_) widest = std::max(widest, error);
    armed_ = widest > kJudgedError * kJudgedError;
    if (armed_) {
      sumBefore(entryCount, true);  // the sweep's errors are the step's start
    } else if (rests) {
      rest();
    }
  }

  /// After measureStepStart armed the step: judged(joint) for each joint (the joint'th that
  /// visit met) of a group open wider than kJudgedError, root mean square.
  template <class Judged>
  void forEachJudgedJoint(const Judged& judged) {
    for (size_t j = 0; j < jointGroups_.size(); ++j) {
      const int group = jointGroups_[j] >= 0 ? root(jointGroups_[j]) : -1;
      if (group >= 0 && before_[group] > kJudgedError * kJudgedError * counts_[group]) judged(j);
    }
  }

  /// Before the feedback (armed only): groups the entries [0, entryCount) and sums each group's
  /// error; visit as for measureStepStart. Without `regroup` (a later pass of the same step) the
  /// groups stay and only the errors are measured anew.
  template <class Visit>
  void measureBefore(int entryCount, const Visit& visit, bool regroup = true) {
    record(visit, regroup);
    sumBefore(entryCount, regroup);
  }

  /// One guarded pass of the NGS solvers: measures the groups (regrouping on a step's first pass),
  /// lets snapshot() save the poses and moveJoints() run the joints' part of the pass, then
  /// keepOrRestore(visit, restore, forget).
  template <class Visit, class Snapshot, class MoveJoints, class Restore, class Forget>
  void guardPass(int entryCount, const Visit& visit, bool firstPass, const Snapshot& snapshot,
                 const MoveJoints& moveJoints, const Restore& restore, const Forget& forget) {
    measureBefore(entryCount, visit, firstPass);
    snapshot();
    moveJoints();
    keepOrRestore(visit, restore, forget);
  }

  /// After the feedback: visit as above (the same joints, in the same order). A group whose error
  /// grew gets restore(entry) for each of its entries and forget(joint) for each of its joints
  /// (the joint'th that visit met).
  template <class Visit, class Restore, class Forget>
  void keepOrRestore(const Visit& visit, const Restore& restore, const Forget& forget) {
    after_.assign(before_.size(), 0.0);
    size_t j = 0;
    visit([&](int, int, double error) {
      if (jointGroups_[j] >= 0) after_[root(jointGroups_[j])] += error;
      ++j;
    });
    bool any = false;
    for (int e = 0; e < static_cast<int>(before_.size()); ++e) {
      if (worse(root(e))) restore(e), any = true;
    }
    for (j = 0; j < jointGroups_.size(); ++j) {
      if (jointGroups_[j] >= 0 && worse(root(jointGroups_[j]))) forget(j), any = true;
    }
    foundWorse_ = foundWorse_ || any;
  }

 private:
  // One sweep: each joint's error and, when regrouping, its two entries.
  template <class Visit>
  void record(const Visit& visit, bool regroup) {
    jointErrors_.clear();
    if (regroup) jointEntries_.clear();
    visit([&](int a, int b, double error) {
      if (regroup) jointEntries_.emplace_back(a, b);
      jointErrors_.push_back(error);
    });
  }
  // Groups the recorded joints' entries [0, entryCount) when regrouping (linked first, counted
  // after: a joint's group is known only once every joint is linked), then sums each group's
  // recorded error.
  void sumBefore(int entryCount, bool regroup) {
    if (regroup) {
      parent_.resize(static_cast<size_t>(entryCount));
      for (int e = 0; e < entryCount; ++e) parent_[e] = e;
      jointGroups_.clear();
      for (const auto& [a, b] : jointEntries_) {
        if (a >= 0 && b >= 0) link(a, b);
        jointGroups_.push_back(a >= 0 ? a : b);
      }
      counts_.assign(static_cast<size_t>(entryCount), 0);
      for (const int e : jointGroups_) {
        if (e >= 0) ++counts_[root(e)];
      }
    }
    before_.assign(static_cast<size_t>(entryCount), 0.0);
    for (size_t j = 0; j < jointGroups_.size(); ++j) {
      if (jointGroups_[j] >= 0) before_[root(jointGroups_[j])] += jointErrors_[j];
    }
  }
  // After a guarded step: one that found a group worse keeps the guard on; one that did not rests
  // it for longer each time.
  void close() {
    if (armed_ && foundWorse_) {
      restLength_ = restSteps_ = 0;
    } else if (armed_) {
      rest();
    }
    foundWorse_ = false;
  }
  void rest() {
    restLength_ = std::min(2 * restLength_ + 1, kMaxRestSteps);
    restSteps_ = restLength_;
  }
  // Whether this step rests (and counts it).
  bool restOneStep() {
    if (restSteps_ == 0) return false;
    --restSteps_;
    return true;
  }
  // A group is judged only when open wider than the arming error: the sweeps of Gauss-Seidel, or
  // a chain swinging, may widen a group by a hair, and undoing that leaves it uncorrected.
  bool worse(int group) const {
    return before_[group] > kJudgedError * kJudgedError * counts_[group] &&
           after_[group] > before_[group];
  }
  int root(int e) {
    while (parent_[e] != e) e = parent_[e] = parent_[parent_[e]];
    return e;
  }
  void link(int a, int b) {
    const int ra = root(a), rb = root(b);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

  bool armed_ = false, foundWorse_ = false;
  int restSteps_ = 0, restLength_ = 0;  // steps left in the rest, and its length
  std::vector<int> parent_;             // union-find over the entries
  // By joint: its entries (-1: a body the step does not move), an entry of its group (-1: it
  // moves no body), its error.
  std::vector<std::pair<int, int>> jointEntries_;
  std::vector<int> jointGroups_;
  std::vector<double> jointErrors_;
  std::vector<double> before_, after_;  // by group root: the summed error
  std::vector<int> counts_;             // by group root: its joints
};

}  // namespace impulse2d
