// impulse2d_device_bench: what the devices cost, without ROS. A top-down room of 200 bodies (walls,
// pillars, crates, barrels) with a round robot driving a slow circle through it; times
//   - one scan of 1081 beams (the laser's defaults: 270 degrees at 0.25 degrees, 10 m),
//   - a step without devices, with the drive only, with every device but nobody listening (the
//     node's state when no one subscribes to the scan or the bumper), and with the laser
//     scanning at 10 Hz and the bumper read every step.
// The step variants run in turns from the same start, and each figure is the median of the turns,
// so that a machine shared with other work slows them alike. Times only; nothing is checked.
//   impulse2d_device_bench [--steps N] [--repeats R] [--scans N]
#include <impulse2d/devices.hpp>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace impulse2d;
using Clock = std::chrono::steady_clock;

constexpr double kHalfRoom = 9.0;  // m: the room is 18 m x 18 m inside
constexpr int kBodies = 200;       // walls included, the robot not

BodyDef shapeBody(const std::string& name, BodyType type, const Vec2& position, double angle,
                  const ShapeDef& shape) {
  BodyDef def;
  def.name = name;
  def.type = type;
  def.position = position;
  def.angle = angle;
  def.linearDamping = def.angularDamping = type == BodyType::Dynamic ? 3.0 : 0.0;
  def.shapes.push_back(shape);
  return def;
}

// The room: 4 walls, then pillars, crates and barrels spread over a jittered grid, clear of the
// robot's circle (radius 3 m about the centre). The same every time (seeded).
void buildRoom(World& world) {
  auto box = [](double w, double h) {
    ShapeDef s;
    s.size = Vec2(w, h);
    s.density = 20.0;
    return s;
  };
  auto circle = [](double r) {
    ShapeDef s;
    s.kind = ShapeKind::Circle;
    s.radius = r;
    s.density = 20.0;
    return s;
  };
  const double wall = 2.0 * kHalfRoom + 0.4;
  world.createBody(
      shapeBody("wall_s", BodyType::Static, Vec2(0, -kHalfRoom - 0.1), 0, box(wall, 0.2)));
  world.createBody(
      shapeBody("wall_n", BodyType::Static, Vec2(0, kHalfRoom + 0.1), 0, box(wall, 0.2)));
  world.createBody(
      shapeBody("wall_w", BodyType::Static, Vec2(-kHalfRoom - 0.1, 0), 0, box(0.2, wall)));
  world.createBody(
      shapeBody("wall_e", BodyType::Static, Vec2(kHalfRoom + 0.1, 0), 0, box(0.2, wall)));
  // Grid points clear of the robot's circle, then an even pick of as many as are wanted.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), turn(-kPi, kPi);
  std::vector<Vec2> spots;
  for (double y = -kHalfRoom + 0.8; y < kHalfRoom - 0.5; y += 1.1) {
    for (double x = -kHalfRoom + 0.8; x < kHalfRoom - 0.5; x += 1.1) {
      if (Vec2(x, y).norm() >= 3.4) spots.push_back(Vec2(x, y));
    }
  }
  const int wanted = kBodies - 4;
  for (int i = 0; i < wanted; ++i) {
    const Vec2 at = spots[i * spots.size() / wanted] + Vec2(jitter(rng), jitter(rng));
    const std::string name = "b" + std::to_string(i);
    if (i % 10 == 0) {
      world.createBody(shapeBody(name, BodyType::Static, at, 0, circle(0.25)));  // pillar
    } else if (i % 10 < 8) {
      world.createBody(shapeBody(name, BodyType::Dynamic, at, turn(rng), box(0.5, 0.5)));
    } else {
      world.createBody(shapeBody(name, BodyType::Dynamic, at, 0, circle(0.2)));  // barrel
    }
  }
}

struct Run {
  World world;
  BodyId robot;
  DeviceSet devices;
  double now = 0.0;

  // devices: 0 none, 1 the drive, 2 every device, 3 every device with the laser and bumper active
  explicit Run(int devicesMode) : world(settings()) {
    buildRoom(world);
    BodyDef robotDef = shapeBody("robot", BodyType::Dynamic, Vec2(0, -2.0), 0, ShapeDef());
    robotDef.shapes[0].kind = ShapeKind::Circle;
    robotDef.shapes[0].radius = 0.25;
    robotDef.mass = 10.0;
    robot = world.createBody(robotDef);
    std::vector<DeviceDef> defs;
    if (devicesMode >= 1) defs.push_back(device(DeviceType::DiffDrive, "drive"));
    if (devicesMode >= 2) {
      defs.push_back(device(DeviceType::Laser, "laser"));
      defs.push_back(device(DeviceType::Bumper, "bumper"));
    }
    DeviceContext context;
    context.plane = "xy";
    std::string error;
    if (!devices.add(defs, world, context, 0.0, &error)) {
      std::fprintf(stderr, "impulse2d_device_bench: %s\n", error.c_str());
      std::exit(1);
    }
    for (Device& d : devices.devices()) d.active = devicesMode >= 3;
  }
  static WorldDef settings() {
    WorldDef def;
    def.gravity = Vec2::Zero();
    def.timeStep = 0.01;
    return def;
  }
  static DeviceDef device(DeviceType type, const std::string& name) {
    DeviceDef def;
    def.type = type;
    def.name = name;
    def.body = "robot";
    def.drive.cmdTimeout = 0.0;
    return def;
  }
  void step() {
    // Without a drive the robot is pushed round the same circle (the physics stays comparable).
    Device* drive = devices.find("drive");
    if (drive) {
      drive->drive->command(0.5, 0.25, now);
    } else {
      const Body& b = world.body(robot);
      world.setVelocity(robot, 0.5 * Vec2(std::cos(b.angle), std::sin(b.angle)), 0.25);
    }
    devices.beforeStep(world, now);
    world.step();
    now += world.settings().timeStep;
    devices.afterStep(world, now);
    for (Device& d : devices.devices()) d.fresh = false;
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 1000, repeats = 5, scans = 200;
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (std::strcmp(argv[i], "--steps") == 0 && hasValue) {
      steps = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--repeats") == 0 && hasValue) {
      repeats = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--scans") == 0 && hasValue) {
      scans = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: impulse2d_device_bench [--steps N] [--repeats R] [--scans N]\n");
      return 2;
    }
  }
  if (steps < 1 || repeats < 1 || scans < 1) {
    std::fprintf(stderr, "impulse2d_device_bench: --steps, --repeats and --scans must be >= 1\n");
    return 2;
  }

  // One scan, from the robot in the settled room.
  std::vector<double> scanMs;
  {
    Run run(2);
    for (int i = 0; i < 200; ++i) run.step();
    Laser laser(LaserDef(), run.robot, 1);
    std::vector<float> ranges;
    int hits = 0;
    for (int r = 0; r < repeats; ++r) {
      const Clock::time_point start = Clock::now();
      for (int i = 0; i < scans; ++i) laser.scan(run.world, &ranges);
      scanMs.push_back(msSince(start) / scans);
    }
    for (float range : ranges) hits += range < 1e30f ? 1 : 0;
    std::printf("scan: %d beams, %zu bodies: %.4f ms per scan (median of %d x %d; %d beams hit)\n",
                laser.beamCount(), run.world.bodyCount(), median(scanMs), repeats, scans, hits);
  }

  // Steps, the variants in turns.
  const char* names[4] = {"no devices", "drive only", "all devices, nobody listening",
                          "all devices, laser 10 Hz and bumper read"};
  std::vector<double> stepMs[4];
  for (int r = 0; r < repeats; ++r) {
    for (int mode = 0; mode < 4; ++mode) {
      Run run(mode);
      const Clock::time_point start = Clock::now();
      for (int i = 0; i < steps; ++i) run.step();
      stepMs[mode].push_back(msSince(start) / steps);
    }
  }
  for (int mode = 0; mode < 4; ++mode) {
    std::printf("step: %-40s %.4f ms (median of %d runs of %d steps)\n", names[mode],
                median(stepMs[mode]), repeats, steps);
  }
  return 0;
}
