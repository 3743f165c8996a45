// The laser scanner (laser.hpp): beams, ranges, noise and schedule.
#include <impulse2d/laser.hpp>

#include <cmath>
#include <limits>

namespace impulse2d {

int laserBeamCount(const LaserDef& def) {
  return static_cast<int>(std::floor((def.angleMax - def.angleMin) / def.angleIncrement + 1e-9)) +
         1;
}

float laserRange(const LaserDef& def, bool hit, double distance, double noise) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (!hit) return kInf;
  const double range = distance + noise;
  if (range < def.rangeMin) return -kInf;
  if (range > def.rangeMax) return kInf;
  return static_cast<float>(range);
}

uint32_t seedFromName(const std::string& name) {
  uint32_t h = 2166136261u;  // FNV-1a, 32 bits
  for (const char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 16777619u;
  }
  return h;
}

// Box-Muller: two uniforms in (0, 1] give two independent standard normals.
double GaussianNoise::next() {
  if (hasSpare_) {
    hasSpare_ = false;
    return spare_;
  }
  constexpr double kScale = 1.0 / 9007199254740992.0;  // 2^-53
  const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * kScale;
  const double u2 = static_cast<double>(engine_() >> 11) * kScale;
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(2.0 * kPi * u2);
  hasSpare_ = true;
  return r * std::cos(2.0 * kPi * u2);
}

// Scan k is due at k / rate; a scan index rather than an accumulated time keeps the schedule
// free of drift. Comparing within 1e-9 of a scan period lets a step that ends on the due time
// (up to rounding) take it.
ScanSchedule::ScanSchedule(double rate, double now)
    : rate_(rate), next_(static_cast<int64_t>(std::floor(now * rate + 1e-9)) + 1) {}

bool ScanSchedule::due(double now) {
  const double position = now * rate_ + 1e-9;  // in scan periods
  if (position < static_cast<double>(next_)) return false;
  next_ = static_cast<int64_t>(std::floor(position)) + 1;
  return true;
}

Laser::Laser(const LaserDef& def, BodyId body, uint32_t seed)
    : def_(def), body_(body), noise_(seed) {
  const int count = laserBeamCount(def);
  directions_.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double angle = def.angleMin + i * def.angleIncrement;
    // Upside down, the scan's y axis points the other way: beam angle a lies at -a.
    directions_.emplace_back(std::cos(angle), def.flip ? -std::sin(angle) : std::sin(angle));
  }
  filter_.ignore.push_back(body);
}

void Laser::scan(const World& world, std::vector<float>* ranges, std::vector<float>* intensities) {
  ranges->assign(directions_.size(), std::numeric_limits<float>::infinity());
  intensities->assign(directions_.size(), 0.0f);
  if (!world.isValid(body_)) return;
  const Transform sensor = [&] {
    const Transform& xf = world.body(body_).xf;
    return Transform(xf.apply(def_.offset), xf.q * Rot(def_.offsetAngle));
  }();
  ends_.resize(directions_.size());
  for (size_t i = 0; i < directions_.size(); ++i) {
    ends_[i] = sensor.p + def_.rangeMax * sensor.q.apply(directions_[i]);
  }
  world.rayCastFan(sensor.p, ends_, filter_, &hits_);
  for (size_t i = 0; i < hits_.size(); ++i) {
    const double noise = def_.noiseStddev > 0.0 ? def_.noiseStddev * noise_.next() : 0.0;
    const float range = laserRange(def_, hits_[i].hit(), hits_[i].fraction * def_.rangeMax, noise);
    (*ranges)[i] = range;
    if (std::isfinite(range)) {
      const Body& hit = world.body(hits_[i].body);
      (*intensities)[i] = static_cast<float>(hit.shapes[hits_[i].shape].reflectance);
    }
  }
}

}  // namespace impulse2d
