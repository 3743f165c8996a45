// human.c, bone by bone: body positions, capsules, frictions, filters, damping, and revolute
// joints with limits, a motor at speed 0 as joint friction and an angular spring.
#include "bench_human.hpp"

namespace impulse2d_bench {
namespace {

constexpr double kPi = impulse2d::kPi;

struct Bone {
  int parent;                                     // index in this human's bones, -1 for the hip
  double y;                                       // body origin above the feet (m)
  double damping;                                 // linear damping (1/s)
  double frictionScale;                           // of the joint's friction torque
  double capsuleLow, capsuleHigh, capsuleRadius;  // capsule along y in the body frame
  double pivotY;                                  // joint to the parent, above the feet
  double lower, upper;                            // joint limits (fractions of pi)
  double referenceAngle;                          // rad
  bool foot;
};

// hip, torso, head, upper/lower left leg, upper/lower right leg, upper/lower left arm,
// upper/lower right arm, in human.c's order.
const Bone kBones[] = {
    {-1, 0.95, 0.0, 1.0, -0.02, 0.02, 0.095, 0.0, 0.0, 0.0, 0.0, false},
    {0, 1.2, 0.0, 0.5, -0.135, 0.135, 0.09, 1.0, -0.25, 0.0, 0.0, false},
    {1, 1.475, 0.1, 0.25, -0.038, 0.039, 0.075, 1.4, -0.3, 0.1, 0.0, false},
    {0, 0.775, 0.0, 1.0, -0.125, 0.125, 0.06, 0.9, -0.05, 0.4, 0.0, false},
    {3, 0.475, 0.0, 0.5, -0.155, 0.125, 0.045, 0.625, -0.5, -0.02, 0.0, true},
    {0, 0.775, 0.0, 1.0, -0.125, 0.125, 0.06, 0.9, -0.05, 0.4, 0.0, false},
    {5, 0.475, 0.0, 0.5, -0.155, 0.125, 0.045, 0.625, -0.5, -0.02, 0.0, true},
    {1, 1.225, 0.0, 0.5, -0.125, 0.125, 0.035, 1.35, -0.1, 0.8, 0.0, false},
    {7, 0.975, 0.1, 0.1, -0.125, 0.125, 0.03, 1.1, -0.2, 0.3, 0.25 * kPi, false},
    {1, 1.225, 0.0, 0.5, -0.125, 0.125, 0.035, 1.35, -0.1, 0.8, 0.0, false},
    {9, 0.975, 0.1, 0.1, -0.125, 0.125, 0.03, 1.1, -0.2, 0.3, 0.25 * kPi, false},
};

constexpr double kJointFriction = 0.05, kJointHertz = 5.0, kJointDampingRatio = 0.5;

}  // namespace

void addHuman(SceneSpec& scene, int group, const Vec2& position, int groupIndex) {
  BenchShape limb;
  limb.kind = BenchShape::Kind::Capsule;
  limb.friction = 0.2;
  limb.filter.groupIndex = -groupIndex;
  limb.filter.categoryBits = 2;
  limb.filter.maskBits = 1 | 2;
  // The feet touch the ground only; human.c's foot hull with a 1.5 cm rounding.
  BenchShape foot = limb;
  foot.kind = BenchShape::Kind::Polygon;
  foot.friction = 0.05;
  foot.filter.maskBits = 1;
  foot.vertices = {Vec2(-0.03, -0.185), Vec2(0.11, -0.185), Vec2(0.11, -0.16), Vec2(-0.03, -0.14)};
  foot.radius = 0.015;

  const int first = static_cast<int>(scene.bodies.size());
  for (const Bone& bone : kBones) {
    BenchBody body;
    body.position = position + Vec2(0.0, bone.y);
    body.linearDamping = bone.damping;
    body.sleepThreshold = 0.1;
    body.group = group;
    BenchShape capsule = limb;
    capsule.vertices = {Vec2(0.0, bone.capsuleLow), Vec2(0.0, bone.capsuleHigh)};
    capsule.radius = bone.capsuleRadius;
    body.shapes.push_back(capsule);
    if (bone.foot) body.shapes.push_back(foot);
    centreOnMass(&body);
    scene.bodies.push_back(body);
    if (bone.parent < 0) continue;
    BenchJoint joint;
    joint.bodyA = first + bone.parent;
    joint.bodyB = static_cast<int>(scene.bodies.size()) - 1;
    joint.anchor = position + Vec2(0.0, bone.pivotY);
    joint.referenceAngle = bone.referenceAngle;
    joint.enableLimit = true;
    joint.lower = bone.lower * kPi;
    joint.upper = bone.upper * kPi;
    joint.enableMotor = true;
    joint.maxMotorTorque = bone.frictionScale * kJointFriction;
    joint.springHertz = kJointHertz;
    joint.springDampingRatio = kJointDampingRatio;
    scene.joints.push_back(joint);
  }
}

}  // namespace impulse2d_bench
