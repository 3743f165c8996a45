// The bumper's model: one body's touching contacts, and whether the bodies it touches changed.
// ROS-free; the node publishes the contacts as an impulse2d/ContactArray when they change.
#pragma once

#include <impulse2d/device_defs.hpp>
#include <impulse2d/world.hpp>

#include <vector>

namespace impulse2d {

class Bumper {
 public:
  Bumper(const BumperDef& def, BodyId body) : def_(def), body_(body) {}

  const BumperDef& def() const { return def_; }
  BodyId body() const { return body_; }

  /// Reads the body's touching contact points from the world's last step (World::contacts()),
  /// turned so that body A is always this body and the normals point away from it. True when
  /// the set of bodies touched differs from the last update's (a first update reports any set,
  /// even none, so that a listener learns the state).
  bool update(const World& world);
  /// Forgets the last update's set: the next update reports (e.g. for a new listener).
  void forget() { known_ = false; }
  const std::vector<ContactInfo>& contacts() const { return contacts_; }

 private:
  BumperDef def_;
  BodyId body_;
  std::vector<ContactInfo> contacts_;
  std::vector<int> touched_;  // slots of the bodies touched, sorted
  bool known_ = false;
};

}  // namespace impulse2d
