// The node's request path below the message conversion: a sequence of spawn, delete, joint,
// wrench, state, scene, model (spawned from YAML text, moved, deleted), step and reset requests
// decoded from the input, applied to the ROS-free SimWorld that WorldNode serialises its
// services onto (src/ros/sim_world*.cpp, which rely on World::validate in
// src/core/validation.cpp). Requests carry any numbers (NaN, inf,
// huge), names of any bytes and lengths, and out-of-range enum values. Every request is either
// refused with a message and the world unchanged (same hash, same counts), or accepted; after
// every step the state is finite.
#include "fuzz_input.hpp"

#include "sim_world.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using impulse2d::Vec2;
using impulse2d::bridge::SimWorld;
using impulse2d::fuzz::FuzzInput;

constexpr int kMaxRequests = 24;

// The start world: a ground, a box and a ball hinged together. Built with spawn and joint
// requests rather than a YAML start scene, which would cost most of each run's time parsing.
void buildStartWorld(SimWorld& sim) {
  std::string error;
  impulse2d::BodyDef ground;
  ground.name = "ground";
  ground.type = impulse2d::BodyType::Static;
  ground.position = Vec2(0.0, -0.5);
  ground.shapes.resize(1);
  ground.shapes[0].size = Vec2(20.0, 1.0);
  impulse2d::BodyDef a;
  a.name = "a";
  a.position = Vec2(0.0, 1.0);
  a.shapes.resize(1);
  impulse2d::BodyDef b;
  b.name = "b";
  b.position = Vec2(0.5, 2.5);
  b.shapes.resize(1);
  b.shapes[0].kind = impulse2d::ShapeKind::Circle;
  b.shapes[0].radius = 0.4;
  impulse2d::JointDef j;
  j.name = "j";
  j.anchor = Vec2(0.0, 2.0);
  if (!sim.spawnBody(ground, &error) || !sim.spawnBody(a, &error) || !sim.spawnBody(b, &error) ||
      !sim.createJoint(j, "a", "b", &error)) {
    impulse2d::fuzz::fail("the start world was refused");
  }
}

// Names are drawn mostly from those in play, so that requests reach past the lookups.
std::string name(FuzzInput& in) {
  static const char* const known[] = {"ground", "a", "b", "j", "c", "k", ""};
  const uint8_t pick = in.byte();
  if (pick < 200) return known[pick % 7];
  return in.text(300);
}

impulse2d::ShapeDef shape(FuzzInput& in) {
  impulse2d::ShapeDef def;
  def.kind = static_cast<impulse2d::ShapeKind>(in.byte() % 4);  // 3 is out of range
  def.size = Vec2(in.number(-1.0, 3.0), in.number(-1.0, 3.0));
  def.radius = in.number(-1.0, 2.0);
  const int vertices = in.byte() % 20;
  for (int i = 0; i < vertices; ++i) def.vertices.emplace_back(in.number(-2, 2), in.number(-2, 2));
  def.offset = Vec2(in.number(-2.0, 2.0), in.number(-2.0, 2.0));
  def.angle = in.number(-4.0, 4.0);
  def.density = in.number(-1.0, 10.0);
  def.friction = in.number(-1.0, 2.0);
  def.restitution = in.number(-0.5, 1.5);
  return def;
}

impulse2d::BodyDef body(FuzzInput& in) {
  impulse2d::BodyDef def;
  def.name = name(in);
  def.type = static_cast<impulse2d::BodyType>(in.byte() % 4);
  def.position = Vec2(in.number(-20.0, 20.0), in.number(-20.0, 20.0));
  def.angle = in.number(-4.0, 4.0);
  def.linearVelocity = Vec2(in.number(-50.0, 50.0), in.number(-50.0, 50.0));
  def.angularVelocity = in.number(-50.0, 50.0);
  def.linearDamping = in.number(-1.0, 5.0);
  def.angularDamping = in.number(-1.0, 5.0);
  def.bullet = in.byte() & 1;
  def.mass = in.number(-1.0, 10.0);
  const int shapes = in.byte() % 4 == 0 ? in.byte() % 80 : 1 + in.byte() % 3;
  for (int i = 0; i < shapes; ++i) def.shapes.push_back(shape(in));
  return def;
}

impulse2d::JointDef joint(FuzzInput& in) {
  impulse2d::JointDef def;
  def.name = name(in);
  def.type = static_cast<impulse2d::JointType>(in.byte() % 5);
  def.anchor = Vec2(in.number(-5.0, 5.0), in.number(-5.0, 5.0));
  def.axis = Vec2(in.number(-1.0, 1.0), in.number(-1.0, 1.0));
  def.enableLimit = in.byte() & 1;
  def.lower = in.number(-3.0, 3.0);
  def.upper = in.number(-3.0, 3.0);
  def.enableMotor = in.byte() & 1;
  def.motorSpeed = in.number(-10.0, 10.0);
  def.maxMotorTorque = in.number(-10.0, 100.0);
  def.length = in.number(-1.0, 5.0);
  def.useAnchorB = in.byte() & 1;
  def.anchorB = Vec2(in.number(-5.0, 5.0), in.number(-5.0, 5.0));
  def.frequency = in.number(-1.0, 30.0);
  def.dampingRatio = in.number(-1.0, 2.0);
  def.minLength = in.number(-1.0, 5.0);
  def.maxLength = in.number(-1.0, 10.0);
  def.collideConnected = in.byte() & 1;
  return def;
}

// What a refused request must leave alone.
struct Fingerprint {
  size_t bodies;
  size_t joints;
  std::vector<impulse2d::bridge::BodySnapshot> states;

  explicit Fingerprint(const SimWorld& sim)
      : bodies(sim.bodyCount()), joints(sim.joints().size()), states(sim.bodies(false)) {}
  bool operator==(const Fingerprint& o) const {
    if (bodies != o.bodies || joints != o.joints || states.size() != o.states.size()) return false;
    for (size_t i = 0; i < states.size(); ++i) {
      const auto &x = states[i], &y = o.states[i];
      if (x.name != y.name || x.position != y.position || x.angle != y.angle ||
          x.linearVelocity != y.linearVelocity || x.angularVelocity != y.angularVelocity) {
        return false;
      }
    }
    return true;
  }
};

void checkFinite(const SimWorld& sim) {
  for (const auto& b : sim.bodies(false)) {
    if (!impulse2d::isFinite(b.position) || !impulse2d::isFinite(b.linearVelocity)) {
      std::fprintf(stderr, "body '%s': position %g %g velocity %g %g\n", b.name.c_str(),
                   b.position.x(), b.position.y(), b.linearVelocity.x(), b.linearVelocity.y());
    }
    IMPULSE2D_FUZZ_CHECK(impulse2d::isFinite(b.position) && std::isfinite(b.angle));
    IMPULSE2D_FUZZ_CHECK(impulse2d::isFinite(b.linearVelocity) && std::isfinite(b.angularVelocity));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzInput in(data, size);
  // IMPULSE2D_FUZZ_TRACE=1 prints the requests and the state after each, to read a crash.
  static const bool trace = std::getenv("IMPULSE2D_FUZZ_TRACE") != nullptr;
  SimWorld sim;
  std::string error;
  buildStartWorld(sim);
  for (int request = 0; request < kMaxRequests && !in.empty(); ++request) {
    const Fingerprint before(sim);
    error.clear();
    bool ok = true;
    bool changesWorld = true;
    const int kind = in.byte() % 13;
    if (trace) std::fprintf(stderr, "request %d: kind %d\n", request, kind);
    switch (kind) {
      case 0:
        ok = sim.spawnBody(body(in), &error);
        break;
      case 1:
        ok = sim.deleteBody(name(in), &error);
        break;
      case 2: {
        const impulse2d::JointDef def = joint(in);
        const std::string a = name(in), b = name(in);
        ok = sim.createJoint(def, a, b, &error);
        break;
      }
      case 3:
        ok = sim.deleteJoint(name(in), &error);
        break;
      case 4: {
        const std::string target = name(in);
        const Vec2 force(in.number(-1e3, 1e3), in.number(-1e3, 1e3));
        const double torque = in.number(-1e3, 1e3);
        const Vec2 point(in.number(-5, 5), in.number(-5, 5));
        const double duration = in.number(-1.0, 2.0);
        if (trace) {
          std::fprintf(stderr, "  wrench on '%s': force %g %g torque %g point %g %g for %g s\n",
                       target.c_str(), force.x(), force.y(), torque, point.x(), point.y(),
                       duration);
        }
        ok = sim.applyWrench(target, force, torque, point, duration, &error);
        changesWorld = false;  // pending until the next step
        break;
      }
      case 5: {
        const std::string target = name(in);
        const Vec2 position(in.number(-20, 20), in.number(-20, 20));
        const double angle = in.number(-4, 4);
        const Vec2 velocity(in.number(-50, 50), in.number(-50, 50));
        ok = sim.setBodyState(target, position, angle, velocity, in.number(-50, 50), &error);
        break;
      }
      case 6: {
        impulse2d::bridge::BodySnapshot state;
        ok = sim.getBodyState(name(in), &state, &error);
        changesWorld = false;
        break;
      }
      case 7:
        ok = sim.addScene(in.text(255), &error);
        break;
      case 9: {
        impulse2d::bridge::ModelRequest model;
        model.where.name = name(in);
        model.where.ns = name(in);
        model.where.position = Vec2(in.number(-20, 20), in.number(-20, 20));
        model.where.angle = in.number(-4, 4);
        model.yaml = in.text(255);
        ok = sim.spawnModel(model, nullptr, &error);
        break;
      }
      case 10:
        ok = sim.deleteModel(name(in), &error);
        break;
      case 11: {
        const std::string target = name(in);
        const Vec2 position(in.number(-20, 20), in.number(-20, 20));
        ok = sim.moveModel(target, position, in.number(-4, 4), &error);
        break;
      }
      case 8:
        for (int i = 1 + in.byte() % 8; i > 0; --i) sim.step();
        checkFinite(sim);
        continue;
      default:
        sim.reset();  // back to the empty start: no start scene was loaded
        continue;
    }
    if (trace) {
      std::fprintf(stderr, "  -> %s %s\n", ok ? "ok" : "refused", error.c_str());
      for (const auto& b : sim.bodies(false)) {
        std::fprintf(stderr, "  %s p %.17g %.17g a %.17g v %.17g %.17g w %.17g\n", b.name.c_str(),
                     b.position.x(), b.position.y(), b.angle, b.linearVelocity.x(),
                     b.linearVelocity.y(), b.angularVelocity);
      }
    }
    if (!ok) {
      IMPULSE2D_FUZZ_CHECK(!error.empty());
      IMPULSE2D_FUZZ_CHECK(Fingerprint(sim) == before);
    } else if (!changesWorld) {
      IMPULSE2D_FUZZ_CHECK(Fingerprint(sim) == before);
    }
  }
  sim.step();
  checkFinite(sim);
  return 0;
}
