// impulse2d_sim: runs a scene file headless for a number of steps, optionally writing body
// states and contacts as CSV and the final state's hash. No ROS master is involved.
#include <impulse2d/devices.hpp>
#include <impulse2d/scene.hpp>
#include <impulse2d/simd.hpp>
#include <impulse2d/world.hpp>

#include "csv_output.hpp"
#include "options.hpp"

#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <exception>
#include <string>

namespace impulse2d {
namespace sim {
namespace {

constexpr int kExitRunFailed = 1;
constexpr int kExitUsage = 2;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "impulse2d_sim: %s\n", message.c_str());
  return code;
}

// A one-line progress report on a terminal, redrawn in place. Short runs print nothing and
// redirected stderr is never cluttered with carriage returns.
class Progress {
 public:
  Progress(uint64_t total, Clock::time_point start)
      : total_(total), start_(start), enabled_(isatty(STDERR_FILENO) != 0) {}

  void update(uint64_t step, double simulated) {
    if (!enabled_) return;
    const double wall = secondsSince(start_);
    constexpr double kQuietStart = 1.0;  // s; runs shorter than this show nothing
    constexpr double kInterval = 0.1;    // s between redraws
    if (wall < kQuietStart || wall < lastDraw_ + kInterval) return;
    lastDraw_ = wall;
    shown_ = true;
    std::fprintf(
        stderr, "\rimpulse2d_sim: step %" PRIu64 "/%" PRIu64 " (%3.0f%%), %.2f s simulated", step,
        total_, 100.0 * static_cast<double>(step) / static_cast<double>(total_), simulated);
    std::fflush(stderr);
  }

  void finish() {
    if (shown_) std::fprintf(stderr, "\r\033[K");
  }

 private:
  uint64_t total_;
  Clock::time_point start_;
  bool enabled_;
  bool shown_ = false;
  double lastDraw_ = 0.0;
};

const char* causeName(RemovalCause cause) {  // as ~removed_bodies names them
  switch (cause) {
    case RemovalCause::LeftWorldExtent:
      return "LEFT_WORLD";
    case RemovalCause::Overflow:
      return "OVERFLOW";
    case RemovalCause::LostForGood:
      return "LOST_FOR_GOOD";
  }
  return "UNKNOWN";
}

// Each body the step removed, and each it found lost for good, one line on stderr: which, when,
// where and why. Returns how many were removed.
uint64_t reportLosses(World& world, uint64_t step) {
  const std::vector<RemovedBody> removed = world.takeRemovedBodies();
  for (const RemovedBody& r : removed) {
    std::fprintf(stderr,
                 "impulse2d_sim: step %" PRIu64
                 " (t = %.6g s): removed body '%s' (%s) at "
                 "(%.6g, %.6g): %s\n",
                 step, world.time(), r.name.c_str(), causeName(r.cause), r.position.x(),
                 r.position.y(), r.reason.c_str());
  }
  for (const LostBody& l : world.takeLostBodies()) {
    std::fprintf(stderr,
                 "impulse2d_sim: step %" PRIu64
                 " (t = %.6g s): body '%s' is lost for good at "
                 "(%.6g, %.6g): %s\n",
                 step, world.time(), l.name.c_str(), l.position.x(), l.position.y(),
                 l.reason.c_str());
  }
  return removed.size();
}

// The stages' mean times, one per line, and the step's; stages that took no time are left out
// (the solver has none such).
void printProfile(const StepProfile& sum, uint64_t steps) {
  const double n = steps > 0 ? static_cast<double>(steps) : 1.0;
  std::printf("profile (ms per step, mean of %" PRIu64 " steps):\n", steps);
  for (const auto& [name, ms] : sum.stages()) {
    if (ms > 0.0) std::printf("  %-13s %9.4f  %5.1f %%\n", name, ms / n, 100.0 * ms / sum.total);
  }
  std::printf("  %-13s %9.4f\n", "step", sum.total / n);
}

int run(const Options& options) {
  Scene scene;
  std::string error;
  ScenePaths paths;
  paths.findPackage = findPackageOnPath;  // package:// through $ROS_PACKAGE_PATH, without ROS
  if (!loadSceneFile(options.scenePath, paths, &scene, &error)) return fail(kExitUsage, error);
  World world(applyOverrides(options, scene.world));
  if (!addScene(scene, world, &error)) return fail(kExitUsage, options.scenePath + ": " + error);
  // Devices are checked as the node checks them. Without ROS nothing commands a drive, so each
  // holds its body still, as in the node before cmd_vel arrives; lasers and bumpers are not run.
  DeviceSet devices;
  DeviceContext context;
  context.plane = scene.plane;
  context.worldFrame = scene.frameId;
  if (!devices.add(scene.devices, world, context, 0.0, &error)) {
    return fail(kExitUsage, options.scenePath + ": " + error);
  }
  uint64_t steps = 0;
  if (!stepsToRun(options, world.settings().timeStep, &steps, &error)) {
    return fail(kExitUsage, error);
  }

  CsvFile bodiesCsv, contactsCsv;
  if (!options.csvPath.empty() && !bodiesCsv.open(options.csvPath, kBodyHeader, &error)) {
    return fail(kExitRunFailed, error);
  }
  if (!options.contactsPath.empty() &&
      !contactsCsv.open(options.contactsPath, kContactHeader, &error)) {
    return fail(kExitRunFailed, error);
  }

  const Clock::time_point start = Clock::now();
  Progress progress(steps, start);
  if (bodiesCsv.isOpen()) bodiesCsv.writeBodies(world, 0);
  uint64_t removed = 0;
  world.setProfiling(options.profile);
  StepProfile profile;  // summed over the steps
  for (uint64_t k = 1; k <= steps; ++k) {
    devices.beforeStep(world, world.time());
    world.step();
    if (options.profile) profile += world.profile();
    devices.afterStep(world, world.time());
    removed += reportLosses(world, k);
    if (k % options.every == 0 || k == steps) {
      if (bodiesCsv.isOpen()) bodiesCsv.writeBodies(world, k);
      if (contactsCsv.isOpen()) contactsCsv.writeContacts(world, k);
    }
    progress.update(k, world.time());
  }
  const double wall = secondsSince(start);
  progress.finish();

  if (!bodiesCsv.close(&error) || !contactsCsv.close(&error)) {
    return fail(kExitRunFailed, error);
  }
  std::printf("steps: %" PRIu64 ", simulated: %.6g s, wall: %.3f s, bodies: %zu, contacts: %zu",
              steps, world.time(), wall, world.bodyCount(), world.contactCount());
  if (removed > 0) std::printf(", removed: %" PRIu64 " (listed on stderr)", removed);
  std::printf("\n");
  if (options.hash) std::printf("hash: %016" PRIx64 "\n", world.hash());
  if (options.profile) printProfile(profile, steps);
  if (std::fflush(stdout) != 0) return fail(kExitRunFailed, "cannot write to stdout");
  return 0;
}

}  // namespace
}  // namespace sim
}  // namespace impulse2d

int main(int argc, char** argv) {
  using namespace impulse2d::sim;
  Options options;
  std::string error;
  if (!parseOptions(argc, argv, &options, &error)) return fail(kExitUsage, error);
  const std::string simd = impulse2d::useSimdTargetFromEnvironment();
  if (!simd.empty()) std::fprintf(stderr, "impulse2d_sim: %s\n", simd.c_str());
  if (options.help) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    return fail(kExitRunFailed, e.what());
  }
}
