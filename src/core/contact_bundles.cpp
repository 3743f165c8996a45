#include "contact_bundles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impulse2d {
namespace {

// A body as a lane sees it: the row it reads (~row when it must not write it back), its inverse
// masses, its centre of mass and velocity when the step began. In scalars, as everything in
// fillLane: a Vec2 stored as two doubles and read back at once as one 16-byte vector stalls the
// processor's store forwarding (math.hpp), and that was most of this stage's time.
struct LaneBody {
  int32_t offset;
  double invMass, invInertia;
  double cx, cy, vx, vy, w;
};

LaneBody laneBody(const SubstepBodies& bodies, const std::vector<Body>& items, int slot) {
  const int entry = bodies.entryOf(slot);
  if (entry < 0) {  // static or asleep: the identity row, read only
    const Vec2& c = items[slot].center;
    return {~static_cast<int32_t>(bodies.identityRow() * kStateDoubles),
            0.0,
            0.0,
            c.x(),
            c.y(),
            0.0,
            0.0,
            0.0};
  }
  const BodySim& sim = bodies.sim(entry);
  const BodyState& s = bodies.states()[entry];
  const int32_t offset = static_cast<int32_t>(entry * kStateDoubles);
  return {bodies.isDynamicEntry(entry) ? offset : ~offset,
          sim.invMass,
          sim.invInertia,
          sim.center0.x(),
          sim.center0.y(),
          s.vx,
          s.vy,
          s.w};
}

void setPoint(ContactBundle& c, int i, int lane, double anchorAx, double anchorAy, double anchorBx,
              double anchorBy, double baseSeparation, double normalImpulse, double tangentImpulse) {
  BundlePoint& p = c.points[i];
  p.anchorAx[lane] = anchorAx;
  p.anchorAy[lane] = anchorAy;
  p.anchorBx[lane] = anchorBx;
  p.anchorBy[lane] = anchorBy;
  c.baseSeparation[i][lane] = static_cast<float>(baseSeparation);
  p.normalImpulse[lane] = normalImpulse;
  p.tangentImpulse[lane] = tangentImpulse;
}

// What restitution reads of a lane that does not bounce.
void clearRestitution(BundleExtra& e, int lane) {
  e.restitution[lane] = 0.0;
  for (int i = 0; i < 2; ++i) e.approach[i][lane] = e.maxNormalImpulse[i][lane] = 0.0;
}

// A lane without a contact: it reads the identity row, writes the sink, and every impulse it
// computes is zero.
void setEmptyLane(ContactBundle& c, BundleExtra& e, int lane, int32_t identityOffset) {
  c.offsetA[lane] = c.offsetB[lane] = ~identityOffset;
  c.invMassA[lane] = c.invInertiaA[lane] = c.invMassB[lane] = c.invInertiaB[lane] = 0.0;
  c.normalX[lane] = c.normalY[lane] = c.friction[lane] = 0.0;
  c.maxShift[lane] = 0.0f;
  c.k12[lane] = c.inverse11[lane] = c.inverse12[lane] = c.inverse22[lane] = 0.0;
  c.laneFlags[lane] = 0;
  e.k[0][lane] = e.k[1][lane] = 0.0;
  for (int i = 0; i < 2; ++i) {
    setPoint(c, i, lane, 0, 0, 0, 0, 0, 0, 0);
    c.normalMass[i][lane] = c.tangentMass[i][lane] = 0.0f;
    e.totalNormalImpulse[i][lane] = e.totalTangentImpulse[i][lane] = 0.0;
  }
  clearRestitution(e, lane);
}

// One contact's lane, as the step begins: what the contact and its bodies give. The masses,
// which follow from the lane alone, are prepareBundleMasses' (finishFill).
void fillLane(ContactBundle& c, BundleExtra& e, int lane, const Contact& contact, const LaneBody& a,
              const LaneBody& b, int substeps) {
  const Manifold& m = contact.manifold;
  c.offsetA[lane] = a.offset;
  c.offsetB[lane] = b.offset;
  c.invMassA[lane] = a.invMass;
  c.invInertiaA[lane] = a.invInertia;
  c.invMassB[lane] = b.invMass;
  c.invInertiaB[lane] = b.invInertia;
  c.normalX[lane] = m.normal.x();
  c.normalY[lane] = m.normal.y();
  c.friction[lane] = static_cast<float>(contact.friction);
  const bool bounces = contact.restitution > 0.0;
  uint8_t flags = a.invMass > 0.0 && b.invMass > 0.0 ? 0 : kAgainstStaticLane;
  if (m.pointCount > 1) flags |= kTwoPointLane;
  if (bounces) {
    flags |= kRestitutionLane;
    e.restitution[lane] = contact.restitution;
  }
  c.laneFlags[lane] = flags;
  const double nx = m.normal.x(), ny = m.normal.y();
  for (int i = 0; i < 2; ++i) {
    e.totalNormalImpulse[i][lane] = e.totalTangentImpulse[i][lane] = 0.0;
    if (bounces) e.maxNormalImpulse[i][lane] = e.approach[i][lane] = 0.0;
    if (i >= m.pointCount) {
      setPoint(c, i, lane, 0, 0, 0, 0, 0, 0, 0);
      continue;
    }
    const ManifoldPoint& mp = m.points[i];
    const double px = mp.point.x(), py = mp.point.y();
    const double aAx = px - a.cx, aAy = py - a.cy, aBx = px - b.cx, aBy = py - b.cy;
    setPoint(c, i, lane, aAx, aAy, aBx, aBy, mp.separation - (nx * (aBx - aAx) + ny * (aBy - aAy)),
             contact.normalImpulse[i] / substeps, contact.tangentImpulse[i] / substeps);
    // Normal speed of B relative to A at the point: v + w x r of each.
    if (bounces) {
      const double relativeX = (b.vx - b.w * aBy) - (a.vx - a.w * aAy);
      const double relativeY = (b.vy + b.w * aBx) - (a.vy + a.w * aAx);
      e.approach[i][lane] = relativeX * nx + relativeY * ny;
    }
  }
}

}  // namespace

void ContactBundles::assign(const std::vector<Contact>& contacts, const StepColors& colors) {
  // Each colour's bundles, colour after colour, the overflow's last.
  const int colorCount = colors.colorCount();
  colorStart_.assign(1, 0);
  for (int color = 0; color <= colorCount; ++color) {
    colorStart_.push_back(colorStart_.back() +
                          (colors.contactsOf(color) + kBundleLanes - 1) / kBundleLanes);
  }
  colorStart_.pop_back();  // the overflow's bundles run to the end
  const int bundles =
      colorStart_.back() + (colors.contactsOf(colorCount) + kBundleLanes - 1) / kBundleLanes;
  bundles_.resize(static_cast<size_t>(bundles));
  extras_.resize(static_cast<size_t>(bundles));
  // Each contact its lane: the next free one of its colour, in the contacts' order.
  laneOf_.resize(contacts.size());
  rank_.assign(static_cast<size_t>(colorCount) + 1, 0);
  contactCount_ = 0;
  for (size_t i = 0; i < contacts.size(); ++i) {
    const int color = colors.colorOfContact(i);
    laneOf_[i] = -1;
    if (color < 0) continue;
    const int r = rank_[static_cast<size_t>(color)]++;
    laneOf_[i] = (colorStart_[color] + r / kBundleLanes) * kBundleLanes + r % kBundleLanes;
    ++contactCount_;
  }
  for (int color = 0; color <= colorCount; ++color) {
    const int lanes = colors.contactsOf(color);
    for (int r = 0; r < lanes; r += kBundleLanes) {
      bundles_[colorStart_[color] + r / kBundleLanes].laneCount = std::min(kBundleLanes, lanes - r);
    }
  }
}

void ContactBundles::fill(std::vector<Contact>& contacts, size_t first, size_t last,
                          const SubstepBodies& bodies, const std::vector<Body>& items, int substeps,
                          const CrushedBodies* crushed) {
  const auto rowOf = [&](int slot) { return bodies.dynamicEntryOf(slot); };
  const bool anyCrushed = crushed != nullptr && crushed->any();
  for (size_t i = first; i < last; ++i) {
    if (laneOf_[i] < 0) continue;
    const Contact& contact = contacts[i];
    const int k = laneOf_[i] / kBundleLanes, lane = laneOf_[i] % kBundleLanes;
    fillLane(bundles_[k], extras_[k], lane, contact, laneBody(bodies, items, contact.bodyA),
             laneBody(bodies, items, contact.bodyB), substeps);
    if (anyCrushed && crushed->pressesCrushed(contact, rowOf)) {
      bundles_[k].laneFlags[lane] |= kNoPushLane;
    }
  }
}

void ContactBundles::finishFill(int begin, int end, const SubstepBodies& bodies, bool soft) {
  const int32_t identityOffset = static_cast<int32_t>(bodies.identityRow() * kStateDoubles);
  for (int k = begin; k < end; ++k) {
    for (int lane = bundles_[k].laneCount; lane < kBundleLanes; ++lane)
      setEmptyLane(bundles_[k], extras_[k], lane, identityOffset);
  }
  prepareBundleMasses(bundles_.data(), extras_.data(), begin, end, soft);
  for (int k = begin; k < end; ++k) {
    ContactBundle& c = bundles_[k];
    BundleExtra& e = extras_[k];
    uint8_t any = 0;
    for (int lane = 0; lane < c.laneCount; ++lane) any |= c.laneFlags[lane];
    c.anySequential = (any & kSequentialLane) != 0;
    c.anyRestitution = (any & kRestitutionLane) != 0;
    c.anyNoPush = (any & kNoPushLane) != 0;
    // Lanes of a bouncing bundle that do not bounce still go through its restitution rows.
    for (int lane = 0; c.anyRestitution && lane < c.laneCount; ++lane) {
      if (!(c.laneFlags[lane] & kRestitutionLane)) clearRestitution(e, lane);
    }
  }
}

void ContactBundles::collectBouncing() {
  bouncing_.clear();
  for (int k = 0; k < bundleCount(); ++k) {
    if (bundles_[k].anyRestitution) bouncing_.push_back(k);
  }
}

void ContactBundles::store(std::vector<Contact>& contacts, size_t first, size_t last) const {
  for (size_t i = first; i < last; ++i) {
    if (laneOf_[i] < 0) continue;
    Contact& contact = contacts[i];
    const BundleExtra& e = extras_[laneOf_[i] / kBundleLanes];
    const int lane = laneOf_[i] % kBundleLanes;
    for (int p = 0; p < contact.manifold.pointCount; ++p) {
      contact.normalImpulse[p] = e.totalNormalImpulse[p][lane];
      contact.tangentImpulse[p] = e.totalTangentImpulse[p][lane];
    }
  }
}

}  // namespace impulse2d
