// The laser scanner's model: beam geometry, ranges from one fan of ray casts, seeded Gaussian
// noise and a schedule in simulated time. ROS-free; the node turns a scan into a LaserScan.
#pragma once

#include <impulse2d/device_defs.hpp>
#include <impulse2d/world.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace impulse2d {

/// Beams from angle_min in steps of angle_increment up to angle_max (within 1e-9 rad of it), as
/// sensor_msgs/LaserScan counts them: floor((max - min) / increment) + 1. A negative increment
/// (with angle_max <= angle_min) sweeps clockwise.
int laserBeamCount(const LaserDef& def);

/// A hit `distance` m away (or none) as a LaserScan range, by REP 117: nearer than range_min
/// -inf, beyond range_max or no hit +inf; `noise` (m) is added to hits before the comparison.
float laserRange(const LaserDef& def, bool hit, double distance, double noise);

/// The seed a device uses without a `seed` key: FNV-1a of its name, so that two scanners differ.
uint32_t seedFromName(const std::string& name);

/// Standard normal numbers from a seed, the same on every platform (mt19937_64 and Box-Muller;
/// std::normal_distribution's algorithm is the library's choice).
class GaussianNoise {
 public:
  explicit GaussianNoise(uint64_t seed) : engine_(seed) {}
  double next();

 private:
  std::mt19937_64 engine_;
  bool hasSpare_ = false;
  double spare_ = 0.0;
};

/// Scan k is due at k / update_rate s of simulated time; one step may cover at most one scan.
class ScanSchedule {
 public:
  ScanSchedule(double rate, double now);
  /// Whether a scan falls due by `now` (the end of the step just taken); moves on past it.
  bool due(double now);

 private:
  double rate_;
  int64_t next_;  // index of the next scan
};

/// A scanner on a body. scan() casts its beams from where the body is now.
class Laser {
 public:
  Laser(const LaserDef& def, BodyId body, uint32_t seed);

  const LaserDef& def() const { return def_; }
  BodyId body() const { return body_; }
  int beamCount() const { return static_cast<int>(directions_.size()); }

  /// Ranges (m) of every beam, REP 117 as laserRange, and the intensity of each: the reflectance
  /// of the shape it hit, 0 where it hit nothing within range. Its own body is not seen.
  void scan(const World& world, std::vector<float>* ranges, std::vector<float>* intensities);
  /// The ranges only.
  void scan(const World& world, std::vector<float>* ranges) { scan(world, ranges, &unread_); }

 private:
  LaserDef def_;
  BodyId body_;
  std::vector<Vec2> directions_;  // unit, in the scanner's frame
  GaussianNoise noise_;
  std::vector<Vec2> ends_;  // reused: no allocation once warm
  std::vector<RayHit> hits_;
  std::vector<float> unread_;  // intensities nobody asked for
  RayFilter filter_;
};

}  // namespace impulse2d
