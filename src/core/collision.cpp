// Narrow phase: contact manifolds for circle/circle, polygon/circle and polygon/polygon.
//
// Polygons use the separating axis test over face normals followed by clipping of an incident
// edge against a reference face (Catto, "Fast and Simple Physics using Sequential Impulses",
// GDC 2006). Every manifold point reports the midpoint between the two surfaces, so that
// point - separation/2 * normal lies on A and point + separation/2 * normal lies on B.
#include <algorithm>
#include <cmath>
#include <impulse2d/collision.hpp>
#include <limits>
#include <utility>

namespace impulse2d {
namespace {

// Directions shorter than this (m) are not normalised: a fixed normal is used instead, so that
// coincident centres or a circle centre lying on a polygon never produce NaN.
constexpr double kLengthEpsilon = 1e-12;

// Feature flip-flop: when a face of each polygon separates the shapes almost equally (a stack
// of equal boxes), round-off alone would make the reference face alternate between A and B from
// one step to the next, and with it the clipping and the contact points. B's face is therefore
// chosen only when it beats A's by 0.1 * the default linear slop (0.005 m) plus 2 % of the
// depth; the relative part is Catto's 0.98 weighting, written so that it also favours A for
// positive (speculative) separations.
constexpr double kFlipAbsoluteTolerance = 0.0005;
constexpr double kFlipRelativeTolerance = 0.02;

// Feature ids. Every polygon/polygon point is a vertex of one polygon against a face of the
// other: an incident vertex kept between the side planes is (incident vertex, reference face),
// a point cut by the side plane through a reference vertex is (reference vertex, incident
// face). The id names the two features by shape, not by role:
//
//   bits  0..7   index of A's feature        bit  8   set when A's feature is a vertex
//   bits 16..23  index of B's feature        bit 24   set when B's feature is a vertex
//
// Because the roles do not enter the id, a point keeps its id when the reference face flips
// from A to B (a box resting on a much wider ground flips at a tilt of ~1e-4 rad, which the
// tolerance above cannot absorb), so the warm start survives. The vertex bits also make the two
// points of a manifold differ: they share at most one of their two features.
constexpr uint32_t kVertexFeature = 0x100;

uint32_t feature(int index, bool isVertex) {
  return static_cast<uint32_t>(index) | (isVertex ? kVertexFeature : 0u);
}

uint32_t featureId(uint32_t reference, uint32_t incident, bool flip) {
  const uint32_t featureA = flip ? incident : reference;
  const uint32_t featureB = flip ? reference : incident;
  return featureA | (featureB << 16);
}

// A polygon expressed in another shape's frame. Only its `count` vertices are written, and its
// normals stay in its own frame (the incident-edge search rotates the one reference normal
// instead): the narrow phase runs for every close pair on every step, and copying a whole
// Polygon (16 slots of vertices and of normals) cost more than the transform itself.
struct PolygonInFrame {
  int count = 0;
  Vec2 vertices[kMaxPolygonVertices];  // left uninitialised beyond count
  const Polygon* source = nullptr;
  Rot rotation;  // from the polygon's frame into the other's
};

void transformInto(const Polygon& polygon, const Transform& xf, PolygonInFrame* out) {
  out->count = polygon.count;
  out->source = &polygon;
  out->rotation = xf.q;
  for (int i = 0; i < polygon.count; ++i) out->vertices[i] = xf.apply(polygon.vertices[i]);
}

struct FaceSeparation {
  double separation;
  int edge;
};

// The face of `poly` along whose normal `other` (given in poly's frame) is separated the most.
// For convex polygons the largest such value is the signed distance when positive and minus the
// penetration depth along face normals when negative. A face beyond `speculativeDistance` already
// separates the pair, so the search stops there.
FaceSeparation maxFaceSeparation(const Polygon& poly, const PolygonInFrame& other,
                                 double speculativeDistance) {
  FaceSeparation best{-std::numeric_limits<double>::infinity(), 0};
  for (int i = 0; i < poly.count; ++i) {
    const double nx = poly.normals[i].x();
    const double ny = poly.normals[i].y();
    double deepest = std::numeric_limits<double>::infinity();
    for (int j = 0; j < other.count; ++j) {
      deepest = std::min(deepest, nx * other.vertices[j].x() + ny * other.vertices[j].y());
    }
    deepest -= nx * poly.vertices[i].x() + ny * poly.vertices[i].y();
    if (deepest > best.separation) {
      best = {deepest, i};
      if (!(deepest <= speculativeDistance)) break;
    }
  }
  return best;
}

// A box, as makeBox builds it: four faces whose opposite normals are exact negatives.
bool hasOppositeFaces(const Polygon& poly) {
  return poly.count == 4 && poly.normals[2] == -poly.normals[0] &&
         poly.normals[3] == -poly.normals[1];
}

// Lowest and highest projection of `count` vertices on (nx, ny). Written out for four
// vertices, the common case of a box, where the loop's bookkeeping would cost as much as the
// arithmetic.
void projectionRange(const Vec2* v, int count, double nx, double ny, double* lo, double* hi) {
  if (count == 4) {
    const double p0 = nx * v[0].x() + ny * v[0].y();
    const double p1 = nx * v[1].x() + ny * v[1].y();
    const double p2 = nx * v[2].x() + ny * v[2].y();
    const double p3 = nx * v[3].x() + ny * v[3].y();
    *lo = std::min(std::min(p0, p1), std::min(p2, p3));
    *hi = std::max(std::max(p0, p1), std::max(p2, p3));
    return;
  }
  *lo = std::numeric_limits<double>::infinity();
  *hi = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < count; ++j) {
    const double p = nx * v[j].x() + ny * v[j].y();
    *lo = std::min(*lo, p);
    *hi = std::max(*hi, p);
  }
}

// maxFaceSeparation for a box whose first two normals and four vertices are given in some frame,
// against `count` vertices in the same frame. Opposite faces share an axis, so one projection on
// each of the two axes gives the separations of both faces:
//
//            face 2 (normal -n)
//          +-----------+            separation of face 0 = min_j n.v_j - n.box_0
//          |    box    |  ---> n    separation of face 2 = n.box_2 - max_j n.v_j
//          +-----------+
//            face 0 (normal n)
//
// In the box's own frame this is bit for bit what the general loop computes (negation is exact),
// with half its products.
FaceSeparation maxFaceSeparationBox(const Vec2& normal0, const Vec2& normal1, const Vec2* box,
                                    const Vec2* other, int count) {
  double separations[4];
  const Vec2* normals[2] = {&normal0, &normal1};
  for (int i = 0; i < 2; ++i) {
    const double nx = normals[i]->x();
    const double ny = normals[i]->y();
    double lo, hi;
    projectionRange(other, count, nx, ny, &lo, &hi);
    separations[i] = lo - (nx * box[i].x() + ny * box[i].y());
    separations[i + 2] = (nx * box[i + 2].x() + ny * box[i + 2].y()) - hi;
  }
  FaceSeparation best{separations[0], 0};
  for (int i = 1; i < 4; ++i) {
    if (separations[i] > best.separation) best = {separations[i], i};
  }
  return best;
}

// Clipping runs in scalars: a Vec2 built from two scalars and read back at once as a 16-byte
// vector stalls the processor's store forwarding (math.hpp), and here that was most of the time.
struct ClipVertex {
  double x, y;
  uint32_t id;
};

// Keeps the part of the segment (or single point) `in` with (nx, ny) . p <= offset. A point
// created by the cut is named `cutId`.
int clipSegment(const ClipVertex* in, int count, ClipVertex* out, double nx, double ny,
                double offset, uint32_t cutId) {
  int n = 0;
  const double d0 = nx * in[0].x + ny * in[0].y - offset;
  if (d0 <= 0.0) out[n++] = in[0];
  if (count < 2) return n;
  const double d1 = nx * in[1].x + ny * in[1].y - offset;
  if ((d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0)) {
    const double t = d0 / (d0 - d1);
    out[n++] = {in[0].x + t * (in[1].x - in[0].x), in[0].y + t * (in[1].y - in[0].y), cutId};
  }
  if (d1 <= 0.0) out[n++] = in[1];
  return n;
}

// Reference face (edge r of the reference polygon, v1 -> v2, outward normal n) and the incident
// edge of the other polygon, which is clipped to the slab between the two side planes:
//
//                          n
//                          ^
//          v2 *============|===========* v1     reference face
//             |                        |
//      o------x------------------------x-----o  incident edge (here penetrating)
//             |                        |
//       side plane at v2         side plane at v1
//
// The reference face itself is not a clipping plane: the clipped points keep their depth as
// the separation, and those farther than the speculative distance are dropped. `inc` is given
// in ref's frame; `flip` says that ref is shape B.
Manifold clipIncidentEdge(const Polygon& ref, const PolygonInFrame& inc, const Transform& xfRef,
                          int r, bool flip, double speculativeDistance) {
  Manifold m;
  const double nx = ref.normals[r].x(), ny = ref.normals[r].y();

  // The incident edge is the one facing the reference face the most (most anti-parallel),
  // compared in the incident polygon's own frame: one rotation instead of one per normal.
  const Vec2 nInInc = inc.rotation.applyInverse(ref.normals[r]);
  int e = 0;
  double minDot = std::numeric_limits<double>::infinity();
  for (int j = 0; j < inc.count; ++j) {
    const Vec2& normal = inc.source->normals[j];
    const double d = nInInc.x() * normal.x() + nInInc.y() * normal.y();
    if (d < minDot) {
      minDot = d;
      e = j;
    }
  }
  const int e2 = (e + 1) % inc.count;
  const uint32_t refFace = feature(r, false);
  const uint32_t incFace = feature(e, false);
  const ClipVertex incident[2] = {
      {inc.vertices[e].x(), inc.vertices[e].y(), featureId(refFace, feature(e, true), flip)},
      {inc.vertices[e2].x(), inc.vertices[e2].y(), featureId(refFace, feature(e2, true), flip)}};

  const Vec2& v1 = ref.vertices[r];
  const int r2 = (r + 1) % ref.count;
  const Vec2& v2 = ref.vertices[r2];
  // Counter-clockwise winding: the face runs along the normal turned a quarter to the left
  // (shape.cpp builds the normal as the edge turned a quarter to the right), already unit.
  const double tx = -ny, ty = nx;
  ClipVertex clip1[2];
  ClipVertex clip2[2];
  const int count1 = clipSegment(incident, 2, clip1, -tx, -ty, -(tx * v1.x() + ty * v1.y()),
                                 featureId(feature(r, true), incFace, flip));
  if (count1 == 0) return m;
  const int count2 = clipSegment(clip1, count1, clip2, tx, ty, tx * v2.x() + ty * v2.y(),
                                 featureId(feature(r2, true), incFace, flip));

  for (int k = 0; k < count2; ++k) {
    const double separation = nx * (clip2[k].x - v1.x()) + ny * (clip2[k].y - v1.y());
    if (!(separation <= speculativeDistance)) continue;
    ManifoldPoint& mp = m.points[m.pointCount++];
    const double half = 0.5 * separation;
    mp.point = xfRef.apply(Vec2(clip2[k].x - half * nx, clip2[k].y - half * ny));
    mp.separation = separation;
    mp.id = clip2[k].id;
  }
  // Which end of the incident edge comes first depends on the reference role; a fixed order
  // lets the solver see the same ids in the same slots after a flip.
  if (m.pointCount == 2 && m.points[0].id > m.points[1].id) std::swap(m.points[0], m.points[1]);
  if (m.pointCount > 0) {
    const Vec2 world = xfRef.q.apply(ref.normals[r]);
    m.normal = flip ? Vec2(-world.x(), -world.y()) : Vec2(world.x(), world.y());
  }
  return m;
}

}  // namespace

Manifold collideCircles(const Circle& a, const Transform& xfA, const Circle& b,
                        const Transform& xfB, double speculativeDistance) {
  Manifold m;
  const Vec2 ca = xfA.apply(a.center);
  const Vec2 cb = xfB.apply(b.center);
  const Vec2 d = cb - ca;
  const double distance = d.norm();
  const double separation = distance - a.radius - b.radius;
  if (!(separation <= speculativeDistance)) return m;
  m.normal = distance > kLengthEpsilon ? Vec2(d / distance) : Vec2(0.0, 1.0);
  m.pointCount = 1;
  m.points[0].point = 0.5 * ((ca + a.radius * m.normal) + (cb - b.radius * m.normal));
  m.points[0].separation = separation;
  m.points[0].id = 0;
  return m;
}

// The closest feature of the polygon to the circle centre decides the normal:
//
//        vertex  |  face region  |  vertex
//        region  |               |  region
//       ---------*===============*---------   face of max separation, outward normal up
//              v1|   polygon A   |v2
//
// Inside the polygon the face of max separation (least penetration) is used.
Manifold collidePolygonCircle(const Polygon& a, const Transform& xfA, const Circle& b,
                              const Transform& xfB, double speculativeDistance) {
  Manifold m;
  if (a.count < 3) return m;
  const Vec2 c = xfA.applyInverse(xfB.apply(b.center));  // centre in A's frame

  double maxSeparation = -std::numeric_limits<double>::infinity();
  int face = 0;
  for (int i = 0; i < a.count; ++i) {
    const double s = a.normals[i].dot(c - a.vertices[i]);
    if (s > maxSeparation) {
      maxSeparation = s;
      face = i;
    }
  }
  // The face separation is a lower bound of the distance, so this rejects early and safely.
  if (!(maxSeparation - b.radius <= speculativeDistance)) return m;

  const Vec2& v1 = a.vertices[face];
  const Vec2& v2 = a.vertices[(face + 1) % a.count];
  Vec2 normal = a.normals[face];
  Vec2 surfaceA = c - maxSeparation * normal;
  double distance = maxSeparation;
  // A centre on or within kLengthEpsilon of the boundary takes the face normal: the vertex
  // direction would be too short to normalise, and the two differ by a negligible amount.
  if (maxSeparation > kLengthEpsilon) {
    const Vec2* vertex = nullptr;
    if ((c - v1).dot(v2 - v1) <= 0.0) {
      vertex = &v1;
    } else if ((c - v2).dot(v1 - v2) <= 0.0) {
      vertex = &v2;
    }
    if (vertex != nullptr) {
      // |c - vertex| >= maxSeparation > kLengthEpsilon, so the division is safe.
      const Vec2 d = c - *vertex;
      distance = d.norm();
      normal = d / distance;
      surfaceA = *vertex;
    }
  }
  const double separation = distance - b.radius;
  if (!(separation <= speculativeDistance)) return m;

  const Vec2 surfaceB = c - b.radius * normal;
  m.normal = xfA.q.apply(normal);
  m.pointCount = 1;
  m.points[0].point = xfA.apply(0.5 * (surfaceA + surfaceB));
  m.points[0].separation = separation;
  // One point only: a constant id keeps the warm start when the centre moves from a face
  // region into a vertex region (a ball rolling over a corner).
  m.points[0].id = 0;
  return m;
}

Manifold collidePolygons(const Polygon& a, const Transform& xfA, const Polygon& b,
                         const Transform& xfB, double speculativeDistance) {
  if (a.count < 3 || b.count < 3) return Manifold();
  PolygonInFrame bInA;
  transformInto(b, xfA.inverseTimes(xfB), &bInA);
  const FaceSeparation faceA =
      hasOppositeFaces(a)
          ? maxFaceSeparationBox(a.normals[0], a.normals[1], a.vertices, bInA.vertices, b.count)
          : maxFaceSeparation(a, bInA, speculativeDistance);
  if (!(faceA.separation <= speculativeDistance)) return Manifold();
  // A box B is measured in A's frame too, where its vertices already are: two normals rotated
  // instead of A's vertices moved into B's frame, which only a clip against B's face needs.
  PolygonInFrame aInB;
  const auto moveAIntoB = [&] {
    if (aInB.source == nullptr) transformInto(a, xfB.inverseTimes(xfA), &aInB);
  };
  FaceSeparation faceB;
  if (hasOppositeFaces(b)) {
    faceB =
        maxFaceSeparationBox(bInA.rotation.apply(b.normals[0]), bInA.rotation.apply(b.normals[1]),
                             bInA.vertices, a.vertices, a.count);
  } else {
    moveAIntoB();
    faceB = maxFaceSeparation(b, aInB, speculativeDistance);
  }
  if (!(faceB.separation <= speculativeDistance)) return Manifold();

  const bool flip = faceB.separation > faceA.separation + kFlipAbsoluteTolerance +
                                           kFlipRelativeTolerance * std::abs(faceA.separation);
  if (flip) moveAIntoB();
  Manifold m = flip ? clipIncidentEdge(b, aInB, xfB, faceB.edge, true, speculativeDistance)
                    : clipIncidentEdge(a, bInA, xfA, faceA.edge, false, speculativeDistance);
  // Two corners within the speculative distance but facing no face (diagonal corner-to-corner)
  // give no points from either face; they are picked up once they touch.
  if (m.pointCount == 0) {
    // Deeply overlapping, a short reference face (the end of a thin bar) can miss the incident
    // edge altogether, which then lies beyond a side plane; the other polygon's best face is
    // the next best choice. Seen about once in 10^5 random deep overlaps, never when shallow.
    moveAIntoB();
    m = flip ? clipIncidentEdge(a, bInA, xfA, faceA.edge, false, speculativeDistance)
             : clipIncidentEdge(b, aInB, xfB, faceB.edge, true, speculativeDistance);
  }
  return m;
}

Manifold collideShapes(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                       double speculativeDistance) {
  if (a.type == ShapeType::Circle) {
    if (b.type == ShapeType::Circle) {
      return collideCircles(a.circle, xfA, b.circle, xfB, speculativeDistance);
    }
    // Only polygon-vs-circle exists; its normal points from the polygon (B) to the circle (A).
    Manifold m = collidePolygonCircle(b.polygon, xfB, a.circle, xfA, speculativeDistance);
    m.normal = -m.normal;
    return m;
  }
  if (b.type == ShapeType::Circle) {
    return collidePolygonCircle(a.polygon, xfA, b.circle, xfB, speculativeDistance);
  }
  return collidePolygons(a.polygon, xfA, b.polygon, xfB, speculativeDistance);
}

}  // namespace impulse2d
