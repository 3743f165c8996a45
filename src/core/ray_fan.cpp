// A fan of rays from one origin (World::rayCastFan), as a scanner casts them: one tree query
// gathers the shapes within reach, each shape goes to the beams whose direction its box covers,
// and each beam tries its shapes nearest first, stopping once the rest lie beyond its best hit.
// The answers are castRay's, bit for bit: the same exact test on every shape that could be hit,
// the same rule among equally near ones.
//
//                     . beam k
//          [box]   .'          a shape's box, seen from the origin, covers the beams between
//           \  .'              the angles of its outermost corners; the box's distance bounds
//   origin  *'------- beam 0   every hit on the shape from below
#include "world_rays.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// rad: a beam along a box's outermost corner is still in (atan2 rounds in the last bits).
constexpr double kAngleMargin = 1e-9;
// m: an origin this close to a box sees it in every direction (angles lose their meaning).
constexpr double kNearBox = 1e-6;

struct Candidate {
  int slot = 0;
  int shape = 0;
  double minDistance = 0.0;   // from the origin to the shape's box
  bool everywhere = false;    // the origin is in or at the box: every beam may hit it
  double lo = 0.0, hi = 0.0;  // the angles it covers, lo <= hi, within (-2 pi, 2 pi)
};

double wrapped(double angle) {
  if (angle > kPi) return angle - 2.0 * kPi;
  if (angle <= -kPi) return angle + 2.0 * kPi;
  return angle;
}

Candidate candidateFor(int slot, int shape, const Aabb& box, const Vec2& origin) {
  Candidate c;
  c.slot = slot;
  c.shape = shape;
  const Vec2 nearest = origin.cwiseMax(box.lower).cwiseMin(box.upper);
  c.minDistance = (nearest - origin).norm();
  if (c.minDistance < kNearBox) {
    c.everywhere = true;
    return c;
  }
  // Seen from outside, a box spans less than a half turn about the direction to its centre.
  const Vec2 center = 0.5 * (box.lower + box.upper) - origin;
  const double mid = std::atan2(center.y(), center.x());
  double lo = 0.0, hi = 0.0;
  for (const Vec2& corner : {box.lower, box.upper, Vec2(box.lower.x(), box.upper.y()),
                             Vec2(box.upper.x(), box.lower.y())}) {
    const Vec2 d = corner - origin;
    const double offset = wrapped(std::atan2(d.y(), d.x()) - mid);
    lo = std::min(lo, offset);
    hi = std::max(hi, offset);
  }
  c.lo = mid + lo - kAngleMargin;
  c.hi = mid + hi + kAngleMargin;
  return c;
}

// Calls visit(first, last) for the ranges of `angles` (sorted, in (-pi, pi]) that the candidate
// covers; an interval across -pi/pi is two ranges.
template <class Visit>
void coveredBeams(const Candidate& c, const std::vector<double>& angles, Visit&& visit) {
  if (c.everywhere) {
    visit(size_t(0), angles.size());
    return;
  }
  auto range = [&](double lo, double hi) {
    const size_t first = std::lower_bound(angles.begin(), angles.end(), lo) - angles.begin();
    const size_t last = std::upper_bound(angles.begin(), angles.end(), hi) - angles.begin();
    if (first < last) visit(first, last);
  };
  if (c.lo < -kPi) {
    range(c.lo + 2.0 * kPi, kPi);
    range(-kPi, c.hi);
  } else if (c.hi > kPi) {
    range(c.lo, kPi);
    range(-kPi, c.hi - 2.0 * kPi);
  } else {
    range(c.lo, c.hi);
  }
}

// A little more than x: a bound compared with a computed distance must not cut off a tie.
double above(double x) { return x * (1.0 + 1e-12) + 1e-12; }

}  // namespace

void castFan(const WorldImpl& w, const Vec2& origin, const std::vector<Vec2>& ends,
             const RayFilter& filter, std::vector<RayHit>* hits) {
  hits->assign(ends.size(), RayHit());
  // The beams, by angle; a beam of no length has none and is cast alone.
  std::vector<std::pair<double, int>> beams;
  beams.reserve(ends.size());
  Aabb reach{origin, origin};
  for (size_t i = 0; i < ends.size(); ++i) {
    if (!isFinite(ends[i])) continue;
    const Vec2 d = ends[i] - origin;
    if (d.x() == 0.0 && d.y() == 0.0) {
      (*hits)[i] = castRay(w, origin, ends[i], filter);
      continue;
    }
    beams.emplace_back(std::atan2(d.y(), d.x()), static_cast<int>(i));
    reach = reach.united(Aabb{ends[i], ends[i]});
  }
  if (beams.empty()) return;
  std::sort(beams.begin(), beams.end());
  std::vector<double> angles(beams.size());
  for (size_t k = 0; k < beams.size(); ++k) angles[k] = beams[k].first;

  // The shapes within reach, nearest first (ties in slot and shape order, for castRay's rule).
  std::vector<Candidate> candidates;
  w.tree.query(reach, [&](int proxy) {
    const int slot = proxySlot(w.tree.userData(proxy)), shape = proxyShape(w.tree.userData(proxy));
    const Body& body = w.bodies.items[slot];
    if (filter.ignores(body.id)) return;
    candidates.push_back(
        candidateFor(slot, shape, computeAabb(body.shapes[shape], body.xf), origin));
  });
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.minDistance != b.minDistance) return a.minDistance < b.minDistance;
    return a.slot != b.slot ? a.slot < b.slot : a.shape < b.shape;
  });

  // Each beam's candidates, in that order: counted, then filled (one array, offsets per beam).
  std::vector<int> first(beams.size() + 1, 0);
  for (const Candidate& c : candidates) {
    coveredBeams(c, angles, [&](size_t a, size_t b) {
      for (size_t k = a; k < b; ++k) ++first[k + 1];
    });
  }
  for (size_t k = 0; k < beams.size(); ++k) first[k + 1] += first[k];
  std::vector<int> entries(first.back());
  std::vector<int> next(first.begin(), first.end() - 1);
  for (size_t ci = 0; ci < candidates.size(); ++ci) {
    coveredBeams(candidates[ci], angles, [&](size_t a, size_t b) {
      for (size_t k = a; k < b; ++k) entries[next[k]++] = static_cast<int>(ci);
    });
  }

  for (size_t k = 0; k < beams.size(); ++k) {
    const Vec2& end = ends[beams[k].second];
    const double length = (end - origin).norm();
    RayHit best;
    for (int e = first[k]; e < first[k + 1]; ++e) {
      const Candidate& c = candidates[entries[e]];
      if (c.minDistance > above(best.hit() ? best.fraction * length : length)) break;
      const Body& body = w.bodies.items[c.slot];
      const ShapeRayHit hit = rayCastShape(body.shapes[c.shape], body.xf, origin, end);
      if (!hit.hit() || !nearerHit(hit.fraction, c.slot, c.shape, best)) continue;
      best.body = body.id;
      best.shape = c.shape;
      best.fraction = hit.fraction;
      best.normal = hit.normal;
      best.point = origin + hit.fraction * (end - origin);
    }
    (*hits)[beams[k].second] = best;
  }
}

}  // namespace impulse2d
