// The bumper (bumper.hpp).
#include <impulse2d/bumper.hpp>

#include <algorithm>
#include <utility>

namespace impulse2d {

bool Bumper::update(const World& world) {
  contacts_.clear();
  std::vector<int> touched;
  if (world.isValid(body_)) {
    for (ContactInfo c : world.contacts()) {
      if (c.bodyB == body_) {
        std::swap(c.bodyA, c.bodyB);
        c.normal = -c.normal;
      } else if (c.bodyA != body_) {
        continue;
      }
      touched.push_back(c.bodyB.index);
      contacts_.push_back(c);
    }
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  const bool changed = !known_ || touched != touched_;
  touched_ = std::move(touched);
  known_ = true;
  return changed;
}

}  // namespace impulse2d
