// The warm start of jointed bodies, kept from pumping energy. Warm starting applies the impulses
// joints and contacts kept from the last step; for a set of constraints that can all be met they
// nearly cancel (a chain holding a load: each link's two joints pull opposite ways), and the
// iterations only refine them. A joint that cannot be met (pinned to a body a wall stops, part
// of a loop that does not close) meets a contact or another joint that undoes its impulse every
// iteration: both grow, step after step, and whatever is left of their difference flings the
// bodies (the core soak saw a welded cluster kicked to 17 rad/s with a 15 m arm). So, once a step
// before the first warm start, each group of bodies joined by joints, with the contacts that touch
// them, is given its warm start on trial copies of its velocities: where the group's kinetic
// energy would more than double (plus what two steps of gravity give, and 0.1 m/s), all of the
// group's impulses are scaled down to what stays within that. Groups whose constraints can be
// met are not touched, nor is anything without a joint.
//
// Impulses can also grow while they cancel: a joint to a still body that pulls a body into a
// static wall (a set that cannot be met) and the wall's contact each undo the other, their
// impulses growing step after step with the bodies at rest (the core soak, baumgarte seed 434:
// a welded pair of 0.43 kg, its prismatic joint's angle row at 118,000 N m s and its contact
// with the wall at 9,000 N s, 7 % more each step).
// Balanced, they add no energy, until the balance breaks (a contact comes or goes, the iterations
// round off a thousandth of them) and the group leaves at the speed limit: there, at 232 m/s.
// So each constraint's warm start is also weighed alone, the energy it would give its bodies
// from rest, and where a group's sum of those exceeds what would move the whole group at the
// speed limit, its impulses shrink to that. Held so, a standoff stays a standoff; a light link
// holding 1,000 times its own mass against gravity at 60 Hz stays 6,000 times below it.
//
// And a joint anchored far out on a moving body (kFarAnchor) and found open wider than
// kOpenJointLimit as the step begins is not warm started at all: it cannot be met within the
// step, and what it kept is what it pushed against whatever holds it open, through a long lever.
// Handed on, that grew a little each step without doubling anything: the core soak's
// sub-stepping runs gained energy so in the quiet phase (seeds 224, 469, 514, 671: small bodies
// on hinges anchored 5-15 m out and open 0.1-0.3 m, shaken to 17-38 m/s in a few dozen steps).
// Near anchors are left alone: a heavily loaded grid of short links opens 0.24 m at its worst
// (v3_joint_grid), and without their warm start its joints opened 24 m instead. So are the soft
// step's joints: they are springs, and what they kept is their pull, which holds a set that
// cannot be met near its pin (the pinned chain of test_hard_cases_robust.cpp, seed 18: 162 m
// from its pin without it).
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "contact.hpp"
#include "joint.hpp"
#include "step_workers.hpp"

namespace impulse2d {

class WarmStartGuard {
 public:
  static constexpr double kOpenJointLimit = 0.1;  ///< m, twenty linear slops
  static constexpr double kFarAnchor = 1.5;       ///< m from a moving body's centre of mass
  /// `joints` are the step's active joints, `contacts` the step's contacts (impulses not yet
  /// handed to the solver); rowOf(slot) is the solver row of a dynamic body (members of a welded
  /// cluster share one) or -1, below `rows`; view(slot) a joint's view of the body (its row's
  /// velocity, masses and centre of mass), and prefetchBody(slot) asks ahead for what view(slot)
  /// reads (a hint; nullptr for none). The joints' arms are those of their last pass (this
  /// step's or the last step's): close enough to weigh an energy, and no joint is prepared twice.
  /// `colorStart`, when given, cuts `joints` into colours, [colorStart[c], colorStart[c + 1]),
  /// whose joints share no row, the last of them the overflow; a colour's trial then runs in
  /// blocks on `workers`, which may run them at once. `rigidJoints`: the step solves its joints
  /// without springs (all but the soft step), so far-open ones start from zero (above).
  template <class RowOf, class View, class PrefetchBody>
  void run(const std::vector<Joint*>& joints, std::vector<Contact>& contacts, int rows, RowOf rowOf,
           View view, PrefetchBody prefetchBody, const std::vector<int>* colorStart,
           StepWorkers* workers, double gravityStep, double maxSpeed, bool rigidJoints) {
    if (joints.empty()) return;
    localOfRow_.assign(static_cast<size_t>(rows), -1);
    bodies_.clear();
    parent_.clear();
    ends_.clear();
    guardedContacts_.clear();
    auto local = [&](int slot) {
      const int row = rowOf(slot);
      if (row < 0) return -1;
      int& index = localOfRow_[static_cast<size_t>(row)];
      if (index < 0) {
        index = static_cast<int>(bodies_.size());
        const SolverBody v = view(slot);
        Local b;
        b.v = v.linearVelocity;
        b.w = v.angularVelocity;
        b.trial = v;  // its velocity and masses
        b.center = v.center;
        bodies_.push_back(b);
        parent_.push_back(index);
      }
      return index;
    };
    auto unite = [&](int a, int b) {
      if (a >= 0 && b >= 0) parent_[static_cast<size_t>(find(a))] = find(b);
    };
    for (size_t k = 0; k < joints.size(); ++k) {
      prefetchAhead(joints, k, 1, prefetchBody, joints.size());
      const Joint* joint = joints[k];
      const int a = local(joint->bodyA), b = local(joint->bodyB);
      ends_.push_back({a, b});
      unite(a, b);
    }
    // The contacts that touch a jointed body, and whatever they join it to.
    for (size_t i = 0; i < contacts.size(); ++i) {
      const Contact& c = contacts[i];
      if (c.manifold.pointCount == 0) continue;
      const int rowA = rowOf(c.bodyA), rowB = rowOf(c.bodyB);
      const bool jointedA = rowA >= 0 && localOfRow_[static_cast<size_t>(rowA)] >= 0;
      const bool jointedB = rowB >= 0 && localOfRow_[static_cast<size_t>(rowB)] >= 0;
      if (!jointedA && !jointedB) continue;
      if (rowA == rowB) continue;  // two members of one welded cluster
      const int a = local(c.bodyA), b = local(c.bodyB);
      unite(a, b);
      guardedContacts_.push_back({static_cast<int>(i), a, b});
    }
    // Each local's group, once: the sums below go in local order whichever member is the root.
    const size_t n = bodies_.size();
    root_.resize(n);
    for (size_t i = 0; i < n; ++i) root_[i] = find(static_cast<int>(i));
    before_.assign(n, 0.0);
    mass_.assign(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      const size_t root = static_cast<size_t>(root_[i]);
      before_[root] += energy(bodies_[i], bodies_[i].v, bodies_[i].w);
      const double invMass = bodies_[i].trial.invMass;
      mass_[root] += invMass > 0.0 ? 1.0 / invMass : 0.0;
    }
    // The trial: the joints' warm start, then the contacts', as the solvers apply them.
    // A warm start only adds impulses: what it gives one body does not depend on the other, so
    // an end with no trial copy (a body the step does not move) is a stand-in whose change is
    // dropped. The copies carry what the rows read (reading a whole view of each end instead
    // cost v3_joint_grid about 2 % of its step).
    // Each body takes its joints' impulses in joint order on any number of threads: a colour's
    // joints touch a row each at most once, and colours go one after the other.
    const auto trialOf = [&](size_t first, size_t last) {
      for (size_t k = first; k < last; ++k) {
        prefetchAhead(joints, k, kJointLines, nullptr, last);
        Joint& joint = *joints[k];
        const auto [la, lb] = ends_[k];
        if (rigidJoints && farAndOpen(joint, la >= 0, lb >= 0, view))
          scaleJointImpulses(joint, 0.0);
        BodyVelocity a = la >= 0 ? bodies_[la].trial : BodyVelocity();
        BodyVelocity b = lb >= 0 ? bodies_[lb].trial : BodyVelocity();
        applyJointWarmStart(joint, a, b);  // reads the joint only
        if (la >= 0) addAlone(bodies_[la], a);
        if (lb >= 0) addAlone(bodies_[lb], b);
      }
    };
    const size_t colors = colorStart != nullptr ? colorStart->size() - 2 : 0;
    for (size_t color = 0; color < colors; ++color) {
      const int first = (*colorStart)[color];
      workers->forRanges(
          (*colorStart)[color + 1] - first, kTrialJointsPerBlock, [&](int begin, int end, int) {
            trialOf(static_cast<size_t>(first + begin), static_cast<size_t>(first + end));
          });
    }
    trialOf(colors > 0 ? static_cast<size_t>((*colorStart)[colors]) : 0, joints.size());
    for (const GuardedContact& g : guardedContacts_) {
      const Contact& c = contacts[static_cast<size_t>(g.contact)];
      const Vec2 n = c.manifold.normal, t = perp(n);
      for (int i = 0; i < c.manifold.pointCount; ++i) {
        const Vec2 p = c.normalImpulse[i] * n + c.tangentImpulse[i] * t;
        const Vec2& point = c.manifold.points[i].point;
        if (g.a >= 0) push(bodies_[static_cast<size_t>(g.a)], point, -p);
        if (g.b >= 0) push(bodies_[static_cast<size_t>(g.b)], point, p);
      }
    }
    after_.assign(n, 0.0);
    alone_.assign(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      after_[static_cast<size_t>(root_[i])] +=
          energy(bodies_[i], bodies_[i].trial.linearVelocity, bodies_[i].trial.angularVelocity);
      alone_[static_cast<size_t>(root_[i])] += bodies_[i].alone;
    }
    // Where a group's energy would more than double, all its impulses shrink: the energy a warm
    // start adds grows with their square.
    auto scaleOf = [&](int end) {
      if (end < 0) return 1.0;
      const size_t root = static_cast<size_t>(root_[static_cast<size_t>(end)]);
      const double allowed =
          2.0 * before_[root] + 0.5 * mass_[root] * (4.0 * gravityStep * gravityStep + 0.01);
      const double allowedAlone = 0.5 * mass_[root] * maxSpeed * maxSpeed;
      double scale = 1.0;
      if (after_[root] > allowed) {
        scale = std::isfinite(after_[root]) ? std::sqrt(allowed / after_[root]) : 0.0;
      }
      if (alone_[root] > allowedAlone) {
        scale = std::min(
            scale, std::isfinite(alone_[root]) ? std::sqrt(allowedAlone / alone_[root]) : 0.0);
      }
      return scale;
    };
    for (size_t k = 0; k < joints.size(); ++k) {
      const double scale = scaleOf(ends_[k].first >= 0 ? ends_[k].first : ends_[k].second);
      if (scale < 1.0) scaleJointImpulses(*joints[k], scale);
    }
    for (const GuardedContact& g : guardedContacts_) {
      const double scale = scaleOf(g.a >= 0 ? g.a : g.b);
      if (!(scale < 1.0)) continue;
      Contact& c = contacts[static_cast<size_t>(g.contact)];
      for (int i = 0; i < 2; ++i) {
        c.normalImpulse[i] *= scale;
        c.tangentImpulse[i] *= scale;
      }
    }
  }

 private:
  // The joints (600 bytes each, v3_joint_grid's 20,000 do not stay in cache) are read in order
  // but far apart: `perf` put a fifth of the guard on the first load of each. So the first
  // `lines` of joint k + 8 and the bodies of joint k + 4 (whose line arrived by then) are asked
  // for ahead; hints only.
  static constexpr int kJointLines = 4;  // what a warm start reads (world_substeps.cpp)
  // Anchored further than kFarAnchor from a moving end's centre (its last pass's arm) and open
  // wider than kOpenJointLimit (see the top).
  template <class View>
  static bool farAndOpen(const Joint& joint, bool movesA, bool movesB, const View& view) {
    constexpr double farSquared = kFarAnchor * kFarAnchor;
    const bool far = (movesA && joint.rA.squaredNorm() > farSquared) ||
                     (movesB && joint.rB.squaredNorm() > farSquared);
    return far &&
           jointPositionError(joint, view(joint.bodyA), view(joint.bodyB)).linear > kOpenJointLimit;
  }
  static constexpr int kTrialJointsPerBlock = 256;
  template <class PrefetchBody>
  static void prefetchAhead(const std::vector<Joint*>& joints, size_t k, int lines,
                            const PrefetchBody& prefetchBody, size_t end) {
    constexpr size_t kJointsAhead = 8, kBodiesAhead = 4;
    if (k + kJointsAhead < end) {
      const char* bytes = reinterpret_cast<const char*>(joints[k + kJointsAhead]);
      for (int line = 0; line < lines; ++line) __builtin_prefetch(bytes + 64 * line);
    }
    if constexpr (!std::is_same_v<PrefetchBody, std::nullptr_t>) {
      if (k + kBodiesAhead < end) {
        prefetchBody(joints[k + kBodiesAhead]->bodyA);
        prefetchBody(joints[k + kBodiesAhead]->bodyB);
      }
    }
  }

  struct Local {
    Vec2 v = Vec2::Zero(), center = Vec2::Zero();  // as the step found it
    double w = 0.0;
    BodyVelocity trial;  // the velocity the trial warm start gives it, and its masses
    double alone = 0.0;  // the sum of the energies each impulse alone would give it from rest
  };
  struct GuardedContact {
    int contact, a, b;  // its index, its bodies' locals (-1: not moving)
  };
  static double energy(const Local& b, const Vec2& v, double w) {
    const double invMass = b.trial.invMass, invInertia = b.trial.invInertia;
    return (invMass > 0.0 ? 0.5 * v.squaredNorm() / invMass : 0.0) +
           (invInertia > 0.0 ? 0.5 * w * w / invInertia : 0.0);
  }
  static void push(Local& b, const Vec2& point, const Vec2& p) {
    const Vec2 dv = b.trial.invMass * p;
    const double dw = b.trial.invInertia * cross(Vec2(point - b.center), p);
    b.trial.linearVelocity += dv;
    b.trial.angularVelocity += dw;
    b.alone += energy(b, dv, dw);
  }
  // A joint's warm start gave the body `after`: its velocity change, weighed alone.
  static void addAlone(Local& b, const BodyVelocity& after) {
    b.alone += energy(b, Vec2(after.linearVelocity - b.trial.linearVelocity),
                      after.angularVelocity - b.trial.angularVelocity);
    b.trial = after;
  }
  // The union-find's parents apart from the locals: a find walks 4 bytes a step, not a local.
  int find(int i) {
    while (parent_[static_cast<size_t>(i)] != i) {
      int& up = parent_[static_cast<size_t>(i)];
      up = parent_[static_cast<size_t>(up)];
      i = up;
    }
    return i;
  }

  std::vector<int> localOfRow_;
  std::vector<Local> bodies_;
  std::vector<int> parent_, root_;         // by local: the union-find's, and each one's group
  std::vector<std::pair<int, int>> ends_;  // by joint: its bodies' locals
  std::vector<GuardedContact> guardedContacts_;
  std::vector<double> before_, after_, mass_, alone_;
};

}  // namespace impulse2d
