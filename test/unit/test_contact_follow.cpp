// The narrow phase's shortcut (contact.cpp): while B has moved less than kFollowDistance
// relative to A since a contact's manifold was computed, the manifold's points are followed with
// the bodies instead of computed again. Following must agree with computing, to far below the
// solver's tolerances, for every pair of shape types.
#include <gtest/gtest.h>
#include <impulse2d/collision.hpp>

#include <cmath>
#include <random>

#include "contact.hpp"
#include "test_scenes.hpp"

namespace impulse2d {
namespace {

Body bodyWith(const Shape& shape, const Vec2& position, double angle) {
  Body body;
  body.shapes.push_back(shape);
  body.xf = Transform(position, Rot(angle));
  body.angle = angle;
  body.center = position;
  body.maxExtent = shape.type == ShapeType::Circle ? shape.circle.radius : 0.75;
  return body;
}

// A pair resting on each other: B on top of A, touching to within a millimetre.
void placePair(std::mt19937& rng, Body* a, Body* b) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const bool circleB = rng() % 3 == 0;
  *a = bodyWith(test::boxShape(2.0, 1.0), Vec2(0.0, 0.0), 0.002 * unit(rng));
  const Shape top = circleB ? test::circleShape(0.4) : test::boxShape(1.0, 0.5);
  const double height = circleB ? 0.9 : 0.75;
  *b = bodyWith(top, Vec2(0.6 * unit(rng), height - 0.001 * (1.0 + unit(rng))), 0.004 * unit(rng));
}

// Moves B by at most `reach` at any of its points (a shift and a turn about its origin).
void nudge(std::mt19937& rng, Body* b, double reach) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double turn = 0.5 * reach / b->maxExtent * unit(rng);
  const Vec2 shift = 0.35 * reach * Vec2(unit(rng), unit(rng));
  b->angle += turn;
  b->xf = Transform(b->xf.p + shift, Rot(b->angle));
  b->center = b->xf.p;
}

TEST(ContactFollow, FollowedManifoldMatchesTheComputedOne) {
  std::mt19937 rng(7);
  double worstSeparation = 0.0, worstNormal = 0.0, worstPoint = 0.0;
  int followed = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Body a, b;
    placePair(rng, &a, &b);
    Contact contact;
    contact.shapeA = contact.shapeB = 0;
    updateContact(contact, a, b, 0.02, 0.0, true);  // computes and remembers
    ASSERT_GT(contact.manifold.pointCount, 0);
    for (int step = 0; step < 5; ++step) {  // several small moves, all within the distance
      nudge(rng, &b, 0.9 * kFollowDistance / 5.0);
      updateContact(contact, a, b, 0.02, 0.0, true);
      const Manifold fresh = collideShapes(a.shapes[0], a.xf, b.shapes[0], b.xf, 0.02);
      ASSERT_EQ(contact.manifold.pointCount, fresh.pointCount) << "trial " << trial;
      worstNormal = std::max(worstNormal, (contact.manifold.normal - fresh.normal).norm());
      for (int i = 0; i < fresh.pointCount; ++i) {
        // Points are matched by feature id, as the solver carries impulses over.
        int j = 0;
        while (j < fresh.pointCount && fresh.points[j].id != contact.manifold.points[i].id) ++j;
        ASSERT_LT(j, fresh.pointCount) << "trial " << trial << ": a feature changed";
        worstSeparation = std::max(worstSeparation, std::abs(contact.manifold.points[i].separation -
                                                             fresh.points[j].separation));
        worstPoint =
            std::max(worstPoint, (contact.manifold.points[i].point - fresh.points[j].point).norm());
      }
      ++followed;
    }
  }
  // Following errs by about the square of the motion over the size: kFollowDistance^2 / 0.5 m,
  // 1.3e-7 m; a clipped point may lag its edge by the motion itself along the surface.
  EXPECT_LT(worstSeparation, 1e-6);
  EXPECT_LT(worstNormal, 1e-3);
  EXPECT_LT(worstPoint, kFollowDistance);
  std::printf(
      "contact follow: %d followed manifolds: separation %.2e m, normal %.2e, point %.2e m\n",
      followed, worstSeparation, worstNormal, worstPoint);
}

TEST(ContactFollow, ALargerMoveComputesTheManifoldAgain) {
  std::mt19937 rng(11);
  Body a, b;
  placePair(rng, &a, &b);
  Contact contact;
  contact.shapeA = contact.shapeB = 0;
  updateContact(contact, a, b, 0.02, 0.0, true);
  nudge(rng, &b, 20.0 * kFollowDistance);
  b.xf.p.x() += 3.0 * kFollowDistance;  // beyond, whatever the random part did
  updateContact(contact, a, b, 0.02, 0.0, true);
  const Manifold fresh = collideShapes(a.shapes[0], a.xf, b.shapes[0], b.xf, 0.02);
  ASSERT_EQ(contact.manifold.pointCount, fresh.pointCount);
  for (int i = 0; i < fresh.pointCount; ++i) {
    EXPECT_EQ(contact.manifold.points[i].separation, fresh.points[i].separation);
  }
}

}  // namespace
}  // namespace impulse2d
