#include "contact_bundles.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <cstdlib>

#include "constraint_coloring.hpp"
#include "contact_math.hpp"

namespace impulse2d {
namespace {

// The lanes of a colour's bundles, or of the overflow's, filled in the contacts' order.
void appendBundles(const std::vector<Contact*>& contacts, std::vector<ContactBundle>& bundles,
                   std::vector<BundleExtra>& extras) {
  for (size_t first = 0; first < contacts.size(); first += kBundleLanes) {
    ContactBundle& bundle = bundles.emplace_back();
    BundleExtra& extra = extras.emplace_back();
    const size_t count = std::min<size_t>(kBundleLanes, contacts.size() - first);
    bundle.laneCount = static_cast<int>(count);
    for (size_t lane = 0; lane < kBundleLanes; ++lane) {
      extra.contact[lane] = lane < count ? contacts[first + lane] : nullptr;
    }
  }
}

// A body as a lane sees it: the row it reads (~row when it must not write it back), its inverse
// masses, its centre of mass and velocity when the step began.
struct LaneBody {
  int64_t offset;
  double invMass, invInertia;
  Vec2 center, velocity;
  double angularVelocity;
};

LaneBody laneBody(const SubstepBodies& bodies, const std::vector<Body>& items, int slot) {
  const int64_t read = bodies.readRow(slot) * kStateDoubles;
  const bool writes = bodies.writeRow(slot) >= 0;
  LaneBody out{writes ? read : ~read, 0.0, 0.0, items[slot].center, Vec2::Zero(), 0.0};
  const int entry = bodies.entryOf(slot);
  if (entry >= 0) {
    const BodyState& s = bodies.states()[entry];
    out.velocity = Vec2(s.vx, s.vy);
    out.angularVelocity = s.w;
    out.invMass = bodies.sim(entry).invMass;
    out.invInertia = bodies.sim(entry).invInertia;
  }
  return out;
}

void setPoint(BundlePoint& p, int lane, const Vec2& anchorA, const Vec2& anchorB,
              double baseSeparation, double normalMass, double tangentMass, double normalImpulse,
              double tangentImpulse) {
  p.anchorAx[lane] = anchorA.x();
  p.anchorAy[lane] = anchorA.y();
  p.anchorBx[lane] = anchorB.x();
  p.anchorBy[lane] = anchorB.y();
  p.baseSeparation[lane] = baseSeparation;
  p.normalMass[lane] = normalMass;
  p.tangentMass[lane] = tangentMass;
  p.normalImpulse[lane] = normalImpulse;
  p.tangentImpulse[lane] = tangentImpulse;
}

// A lane without a contact: it reads the identity row, writes the sink, and every impulse it
// computes is zero.
void setEmptyLane(ContactBundle& c, BundleExtra& e, int lane, int64_t identityOffset) {
  c.offsetA[lane] = c.offsetB[lane] = ~identityOffset;
  c.invMassA[lane] = c.invInertiaA[lane] = c.invMassB[lane] = c.invInertiaB[lane] = 0.0;
  c.normalX[lane] = c.normalY[lane] = c.friction[lane] = 0.0;
  c.k11[lane] = c.k12[lane] = c.k22[lane] = 0.0;
  c.inverse11[lane] = c.inverse12[lane] = c.inverse22[lane] = 0.0;
  c.sequential[lane] = c.againstStatic[lane] = 0.0;
  for (BundlePoint& p : c.points) setPoint(p, lane, Vec2::Zero(), Vec2::Zero(), 0, 0, 0, 0, 0);
  e.restitution[lane] = 0.0;
  for (int i = 0; i < 2; ++i) {
    e.approach[i][lane] = e.maxNormalImpulse[i][lane] = 0.0;
    e.totalNormalImpulse[i][lane] = e.totalTangentImpulse[i][lane] = 0.0;
  }
}

}  // namespace

void ContactBundles::build(std::vector<Contact>& contacts, const SubstepBodies& bodies) {
  ConstraintColoring coloring;
  coloring.reset(bodies.dynamicCount());
  byColor_.resize(ConstraintColoring::kMaxColors + 1);  // the last: the overflow
  for (std::vector<Contact*>& list : byColor_) list.clear();
  contactCount_ = 0;
  static std::vector<Contact*> order;
  order.clear();
  for (Contact& contact : contacts) order.push_back(&contact);
  if (std::getenv("EXP_STRIDE") && order.size() > 2) {
    const size_t n = order.size();
    size_t stride = static_cast<size_t>(0.6180339887 * n) | 1;
    while (std::gcd(stride, n) != 1) stride += 2;
    std::vector<Contact*> permuted(n);
    for (size_t i = 0, j = 0; i < n; ++i, j = (j + stride) % n) permuted[i] = order[j];
    order.swap(permuted);
  }
  if (std::getenv("EXP_HASH")) {
    auto mix = [](uint64_t x) { x ^= x >> 33; x *= 0xff51afd7ed558ccdull; x ^= x >> 33; x *= 0xc4ceb9fe1a85ec53ull; x ^= x >> 33; return x; };
    std::sort(order.begin(), order.end(), [&](Contact* p, Contact* q) { return mix(p->key) < mix(q->key); });
  }
  for (Contact* cp : order) {
    Contact& contact = *cp;
    if (contact.manifold.pointCount == 0) continue;
    const int a = bodies.entryOf(contact.bodyA), b = bodies.entryOf(contact.bodyB);
    const int dynamicA = bodies.isDynamicEntry(a) ? a : -1;
    const int dynamicB = bodies.isDynamicEntry(b) ? b : -1;
    if (dynamicA < 0 && dynamicB < 0) continue;  // asleep, or between bodies no impulse moves
    static const bool allOverflow = std::getenv("EXP_OVERFLOW") != nullptr;
    static const int spread = std::getenv("EXP_SPREAD") ? std::atoi(std::getenv("EXP_SPREAD")) : 0;
    uint64_t x = contact.key; x ^= x >> 33; x *= 0xff51afd7ed558ccdull; x ^= x >> 33;
    const int color = allOverflow ? -1 : coloring.assign(dynamicA, dynamicB, spread ? int(x % spread) : 0);
    byColor_[color == ConstraintColoring::kOverflow ? ConstraintColoring::kMaxColors : color]
        .push_back(&contact);
    ++contactCount_;
  }
  if (std::getenv("EXP_SHUFFLE")) {
    auto& o = byColor_[ConstraintColoring::kMaxColors];
    uint64_t x = 88172645463325252ull;
    for (size_t i = o.size(); i > 1; --i) { x ^= x << 13; x ^= x >> 7; x ^= x << 17; std::swap(o[i - 1], o[x % i]); }
  }
  if (std::getenv("EXP_REVERSE")) { auto& o = byColor_[ConstraintColoring::kMaxColors]; std::reverse(o.begin(), o.end()); }
  if (std::getenv("EXP_CHECK")) {
    for (int c = 0; c < ConstraintColoring::kMaxColors; ++c) {
      std::vector<char> seen(bodies.dynamicCount(), 0);
      for (Contact* k : byColor_[c]) {
        for (int slot : {k->bodyA, k->bodyB}) {
          int e = bodies.entryOf(slot);
          if (!bodies.isDynamicEntry(e)) continue;
          if (seen[e]) { fprintf(stderr, "colour %d shares entry %d\n", c, e); abort(); }
          seen[e] = 1;
        }
      }
    }
  }
  bundles_.clear();
  extras_.clear();
  colorStart_.clear();
  // First fit leaves no gaps: a colour is taken only when every lower one was.
  for (int color = 0; color < ConstraintColoring::kMaxColors && !byColor_[color].empty(); ++color) {
    colorStart_.push_back(static_cast<int>(bundles_.size()));
    appendBundles(byColor_[color], bundles_, extras_);
  }
  colorStart_.push_back(static_cast<int>(bundles_.size()));
  appendBundles(byColor_[ConstraintColoring::kMaxColors], bundles_, extras_);
  if (std::getenv("EXP_STATS")) { static int n = 0; if (++n % 100 == 0) { for (auto& l : byColor_) fprintf(stderr, "%zu ", l.size()); fprintf(stderr, "\n"); } }
}

void ContactBundles::prepare(int begin, int end, const SubstepBodies& bodies,
                             const std::vector<Body>& items, int substeps) {
  const int64_t identityOffset = bodies.identityRow() * kStateDoubles;
  for (int k = begin; k < end; ++k) {
    ContactBundle& c = bundles_[k];
    BundleExtra& e = extras_[k];
    c.anySequential = c.anyRestitution = false;
    for (int lane = 0; lane < kBundleLanes; ++lane) {
      const Contact* contact = e.contact[lane];
      if (contact == nullptr) {
        setEmptyLane(c, e, lane, identityOffset);
        continue;
      }
      const Manifold& m = contact->manifold;
      const LaneBody a = laneBody(bodies, items, contact->bodyA);
      const LaneBody b = laneBody(bodies, items, contact->bodyB);
      c.offsetA[lane] = a.offset;
      c.offsetB[lane] = b.offset;
      c.invMassA[lane] = a.invMass;
      c.invInertiaA[lane] = a.invInertia;
      c.invMassB[lane] = b.invMass;
      c.invInertiaB[lane] = b.invInertia;
      c.normalX[lane] = m.normal.x();
      c.normalY[lane] = m.normal.y();
      c.friction[lane] = contact->friction;
      c.againstStatic[lane] = a.invMass > 0.0 && b.invMass > 0.0 ? 0.0 : 1.0;
      e.restitution[lane] = contact->restitution;
      c.anyRestitution |= contact->restitution > 0.0;
      const Vec2 tangent = perp(m.normal);
      double normalArmA[2] = {0.0, 0.0}, normalArmB[2] = {0.0, 0.0};
      for (int i = 0; i < 2; ++i) {
        e.maxNormalImpulse[i][lane] = 0.0;
        e.totalNormalImpulse[i][lane] = e.totalTangentImpulse[i][lane] = 0.0;
        e.approach[i][lane] = 0.0;
        if (i >= m.pointCount) {
          setPoint(c.points[i], lane, Vec2::Zero(), Vec2::Zero(), 0, 0, 0, 0, 0);
          continue;
        }
        const ManifoldPoint& mp = m.points[i];
        const Vec2 anchorA = mp.point - a.center, anchorB = mp.point - b.center;
        normalArmA[i] = cross(anchorA, m.normal);
        normalArmB[i] = cross(anchorB, m.normal);
        const double tangentArmA = cross(anchorA, tangent), tangentArmB = cross(anchorB, tangent);
        const double k = a.invMass + b.invMass;
        const double normalK = k + a.invInertia * normalArmA[i] * normalArmA[i] +
                               b.invInertia * normalArmB[i] * normalArmB[i];
        const double tangentK = k + a.invInertia * tangentArmA * tangentArmA +
                                b.invInertia * tangentArmB * tangentArmB;
        setPoint(c.points[i], lane, anchorA, anchorB,
                 mp.separation - m.normal.dot(anchorB - anchorA),
                 normalK > 0.0 ? 1.0 / normalK : 0.0, tangentK > 0.0 ? 1.0 / tangentK : 0.0,
                 contact->normalImpulse[i] / substeps, contact->tangentImpulse[i] / substeps);
        const Vec2 relative = b.velocity + cross(b.angularVelocity, anchorB) - a.velocity -
                              cross(a.angularVelocity, anchorA);
        e.approach[i][lane] = relative.dot(m.normal);
      }
      const double k = a.invMass + b.invMass;
      c.k11[lane] = k + a.invInertia * normalArmA[0] * normalArmA[0] +
                    b.invInertia * normalArmB[0] * normalArmB[0];
      c.k12[lane] = c.k22[lane] = c.inverse12[lane] = c.inverse22[lane] = 0.0;
      c.inverse11[lane] = c.points[0].normalMass[lane];
      c.sequential[lane] = 0.0;
      if (m.pointCount == 2) {
        c.k22[lane] = k + a.invInertia * normalArmA[1] * normalArmA[1] +
                      b.invInertia * normalArmB[1] * normalArmB[1];
        c.k12[lane] = k + a.invInertia * normalArmA[0] * normalArmA[1] +
                      b.invInertia * normalArmB[0] * normalArmB[1];
        if (wellConditioned(c.k11[lane], c.k12[lane], c.k22[lane])) {
          const double det = c.k11[lane] * c.k22[lane] - c.k12[lane] * c.k12[lane];
          c.inverse11[lane] = c.k22[lane] / det;
          c.inverse12[lane] = -c.k12[lane] / det;
          c.inverse22[lane] = c.k11[lane] / det;
        } else {
          c.inverse11[lane] = 0.0;
          c.sequential[lane] = 1.0;
          c.anySequential = true;
        }
      }
    }
  }
}

void ContactBundles::store(int begin, int end) const {
  for (int k = begin; k < end; ++k) {
    const BundleExtra& e = extras_[k];
    for (int lane = 0; lane < bundles_[k].laneCount; ++lane) {
      Contact& contact = *e.contact[lane];
      for (int i = 0; i < contact.manifold.pointCount; ++i) {
        contact.normalImpulse[i] = e.totalNormalImpulse[i][lane];
        contact.tangentImpulse[i] = e.totalTangentImpulse[i][lane];
      }
    }
  }
}

}  // namespace impulse2d
