// impulse2d_bench: speed against error, impulse2d side by side with Box2D and Chipmunk when they
// were compiled in. Writes one CSV row per (engine, solver, scene, settings) and a memory CSV.
#include <unistd.h>

#include <impulse2d/simd.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine_adapter.hpp"
#include "memory_probe.hpp"
#include "metrics.hpp"

namespace impulse2d_bench {
namespace {

const char* kUsage =
    "usage: impulse2d_bench [--quick | --full] [--scenes A,B] [--engines A,B] [--solvers A,B]\n"
    "                       [--repeats N] [--sweep-repeats N] [--steps N] [--csv FILE]\n"
    "                       [--memory-csv FILE] [--also SOLVER:VEL:POS[:HZ],...]\n"
    "                       [--threads N[,M...]]\n"
    "  (default)         every scene, each engine and solver at the engine's defaults (60 Hz)\n"
    "  --quick           short runs and a small scaling series (CI smoke test, < 2 min)\n"
    "  --full            sweep velocity iterations, position iterations and the time step\n"
    "  --scenes A,B      only scenes whose name starts with A or B (e.g. pyramid100,scaling)\n"
    "  --engines A,B     only these engines (impulse2d, box2d, chipmunk, box2d_v3)\n"
    "  --solvers A,B     only these solvers (e.g. ngs,default)\n"
    "  --repeats N       timed runs per row; ms/step is their median (default 3, quick 1)\n"
    "  --sweep-repeats N timed runs of each swept (non-default) row (default 1)\n"
    "  --steps N         run N steps instead of each scene's duration (for profiling)\n"
    "  --csv FILE        results (default bench.csv)\n"
    "  --memory-csv FILE peak heap per body and per contact on pyramid100 (default\n"
    "                    <csv without .csv>_memory.csv; skipped when pyramid100 is filtered out)\n"
    "  --also S:V:P[:HZ] impulse2d rows at these settings (solver, velocity and position\n"
    "                    iterations, steps per second, default 60), timed in the same round\n"
    "                    robin as the engines' defaults (sweep 'chosen'), e.g. "
    "ngs:8:0,substep:2:3\n"
    "  --threads N,M     worker threads of each row (default 1): every engine and setting runs\n"
    "                    once per count, in the same round robin. Box2D v3 uses them as its\n"
    "                    workers; a single-threaded engine refuses counts above 1 (its rows\n"
    "                    are skipped with the reason)\n";

struct Options {
  bool quick = false, full = false;
  std::vector<std::string> scenes, engines, solvers;
  int repeats = 0;  // 0: the mode's default
  int sweepRepeats = 1;
  int steps = 0;  // 0: each scene's duration
  std::string csv = "bench.csv", memoryCsv;
  std::vector<EngineSettings> also;  // impulse2d settings timed beside the defaults
  std::vector<int> threads{1};
};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// "solver:vel:pos[:hz]" -> settings, or the reason it is refused.
std::string parseSettings(const std::string& text, EngineSettings* out) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ':')) parts.push_back(part);
  if (parts.size() != 3 && parts.size() != 4) return "--also takes SOLVER:VEL:POS[:HZ]";
  const EngineInfo engine = impulse2dEngine();
  if (std::find(engine.solvers.begin(), engine.solvers.end(), parts[0]) == engine.solvers.end()) {
    return "--also: unknown solver '" + parts[0] + "'";
  }
  out->solver = parts[0];
  long numbers[3] = {0, 0, 60};
  const long limits[3][2] = {{1, 1000}, {0, 1000}, {1, 10000}};
  for (size_t k = 1; k < parts.size(); ++k) {
    char* end = nullptr;
    numbers[k - 1] = std::strtol(parts[k].c_str(), &end, 10);
    if (parts[k].empty() || *end != '\0' || numbers[k - 1] < limits[k - 1][0] ||
        numbers[k - 1] > limits[k - 1][1]) {
      return "--also: '" + text + "': iterations 1..1000 and 0..1000, steps per second 1..10000";
    }
  }
  out->velocityIterations = static_cast<int>(numbers[0]);
  out->positionIterations = static_cast<int>(numbers[1]);
  out->timeStep = 1.0 / static_cast<double>(numbers[2]);
  return "";
}

// Returns an empty string or the reason the arguments are refused.
std::string parseOptions(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string* out) -> bool {
      if (i + 1 >= argc) return false;
      *out = argv[++i];
      return !out->empty();
    };
    std::string v;
    if (arg == "--quick") {
      o->quick = true;
    } else if (arg == "--full") {
      o->full = true;
    } else if (arg == "--scenes") {
      if (!value(&v)) return "--scenes needs a comma-separated list";
      o->scenes = splitList(v);
    } else if (arg == "--engines") {
      if (!value(&v)) return "--engines needs a comma-separated list";
      o->engines = splitList(v);
    } else if (arg == "--solvers") {
      if (!value(&v)) return "--solvers needs a comma-separated list";
      o->solvers = splitList(v);
    } else if (arg == "--repeats") {
      if (!value(&v)) return "--repeats needs a number";
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 100) return "--repeats must be 1..100";
      o->repeats = static_cast<int>(n);
    } else if (arg == "--sweep-repeats") {
      if (!value(&v)) return "--sweep-repeats needs a number";
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 100) return "--sweep-repeats must be 1..100";
      o->sweepRepeats = static_cast<int>(n);
    } else if (arg == "--steps") {
      if (!value(&v)) return "--steps needs a number";
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 1000000) return "--steps must be 1..1000000";
      o->steps = static_cast<int>(n);
    } else if (arg == "--csv") {
      if (!value(&o->csv)) return "--csv needs a file name";
    } else if (arg == "--memory-csv") {
      if (!value(&o->memoryCsv)) return "--memory-csv needs a file name";
    } else if (arg == "--threads") {
      if (!value(&v)) return "--threads needs a count or a comma-separated list of counts";
      o->threads.clear();
      for (const std::string& item : splitList(v)) {
        char* end = nullptr;
        const long n = std::strtol(item.c_str(), &end, 10);
        if (*end != '\0' || n < 1 || n > 256) return "--threads: each count must be 1..256";
        o->threads.push_back(static_cast<int>(n));
      }
      if (o->threads.empty()) return "--threads needs a count or a comma-separated list of counts";
    } else if (arg == "--also") {
      if (!value(&v)) return "--also needs SOLVER:VEL:POS[:HZ],...";
      for (const std::string& item : splitList(v)) {
        EngineSettings settings;
        const std::string why = parseSettings(item, &settings);
        if (!why.empty()) return why;
        o->also.push_back(settings);
      }
    } else {
      return "unknown argument '" + arg + "'";
    }
  }
  if (o->quick && o->full) return "--quick and --full exclude each other";
  if (o->repeats == 0) o->repeats = o->quick ? 1 : 3;
  if (o->memoryCsv.empty()) {
    const std::string stem = o->csv.size() > 4 && o->csv.compare(o->csv.size() - 4, 4, ".csv") == 0
                                 ? o->csv.substr(0, o->csv.size() - 4)
                                 : o->csv;
    o->memoryCsv = stem + "_memory.csv";
  }
  return "";
}

bool selected(const std::vector<std::string>& filter, const std::string& name) {
  if (filter.empty()) return true;
  for (const std::string& prefix : filter) {
    if (name.compare(0, prefix.size(), prefix) == 0) return true;
  }
  return false;
}

struct Job {
  const EngineInfo* engine;
  const SceneSpec* scene;
  EngineSettings settings;
  std::string sweep;  // default | chosen (--also) | velocity | position | time_step
};

// The settings to run for one engine and solver on one scene: its defaults, and with --full one
// parameter at a time swept around them.
std::vector<Job> jobsFor(const EngineInfo& engine, const std::string& solver,
                         const SceneSpec& scene, bool full) {
  EngineSettings base = engine.defaults;
  base.solver = solver;
  std::vector<Job> jobs{{&engine, &scene, base, "default"}};
  if (!full || scene.scaling) return jobs;
  for (const int k : {1, 2, 3, 4, 6, 10, 12, 16, 20}) {
    if (k == base.velocityIterations) continue;
    Job job{&engine, &scene, base, "velocity"};
    job.settings.velocityIterations = k;
    jobs.push_back(job);
  }
  const auto& noPosition = engine.solversWithoutPositionIterations;
  if (engine.hasPositionIterations &&
      std::find(noPosition.begin(), noPosition.end(), solver) == noPosition.end()) {
    for (const int k : {0, 1, 2, 4, 6, 8}) {
      if (k == base.positionIterations) continue;
      Job job{&engine, &scene, base, "position"};
      job.settings.positionIterations = k;
      jobs.push_back(job);
    }
  }
  for (const int hz : {30, 120, 240}) {
    Job job{&engine, &scene, base, "time_step"};
    job.settings.timeStep = 1.0 / hz;
    jobs.push_back(job);
  }
  return jobs;
}

struct RunResult {
  int steps = 0;
  double msPerStep = 0.0;
  size_t contacts = 0;
  ErrorFigures errors;
};

int stepsOf(const Job& job, int fixedSteps) {
  if (fixedSteps > 0) return fixedSteps;
  return std::max(1, static_cast<int>(std::lround(job.scene->duration / job.settings.timeStep)));
}

// Runs a job once on a fresh world; only the stepping loop is timed. With `measure`, the run is
// also sampled for the error figures (every engine here is deterministic, so one measured run per
// job is enough; further runs only add times).
RunResult runOnce(const Job& job, int fixedSteps, bool measure) {
  const SceneSpec& scene = *job.scene;
  RunResult result;
  result.steps = stepsOf(job, fixedSteps);
  const int sampleEvery = std::max(1, static_cast<int>(std::lround(0.25 / job.settings.timeStep)));
  std::vector<BodyState> states;
  std::unique_ptr<EngineAdapter> adapter = job.engine->make();
  adapter->build(scene, job.settings);
  ErrorMeter meter(scene);
  double seconds = 0.0;
  int timedSteps = 0;
  size_t nextEvent = 0;
  for (int s = 1; s <= result.steps; ++s) {
    const auto start = std::chrono::steady_clock::now();
    if (scene.steering.body >= 0) {  // before the step, timed with it, as v3's app steers
      const Steering& steer = scene.steering;
      const double dt = job.settings.timeStep;
      const Vec2 at = adapter->position(steer.body);
      const Vec2 target(steer.amplitude * std::sin(steer.rate * (s - 1) * dt),
                        scene.bodies[steer.body].position.y());
      adapter->setVelocity(steer.body, (target - at) / dt);
    }
    // The scene's events happen before their step, timed with it (as in Box2D v3's app).
    for (; nextEvent < scene.events.size() && scene.events[nextEvent].step == s - 1; ++nextEvent) {
      const SceneEvent& event = scene.events[nextEvent];
      if (event.create) {
        adapter->createGroup(event.group);
      } else {
        adapter->destroyGroup(event.group);
      }
    }
    adapter->step();
    if (s > 1 || scene.timeFirstStep || result.steps == 1) {
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++timedSteps;
    }
    if (measure && s % sampleEvery == 0 && s < result.steps) {
      adapter->read(&states);
      meter.sample(states);
    }
  }
  result.msPerStep = 1000.0 * seconds / timedSteps;
  if (measure) {
    adapter->read(&states);
    result.errors = meter.finish(states);
    result.contacts = adapter->contactCount();
  }
  return result;
}

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

const char* kCsvHeader =
    "engine,solver,scene,sweep,time_step,velocity_iterations,position_iterations,threads,bodies,"
    "joints,steps,ms_per_step,contacts,penetration_mean,penetration_max,drift_max,sink_max,"
    "joint_gap_mean,joint_gap_max,energy_drift,escaped,momentum_drift,stood";

// Each scene kind fills the figures that mean something for it; the others stay empty.
std::string csvRow(const Job& job, const RunResult& r) {
  const SceneSpec& scene = *job.scene;
  const ErrorFigures& e = r.errors;
  const bool resting = scene.kind == SceneKind::Resting;
  const bool jointed = !scene.joints.empty();
  std::ostringstream row;
  row << job.engine->name << ',' << job.settings.solver << ',' << scene.name << ',' << job.sweep
      << ',' << number(job.settings.timeStep) << ',' << job.settings.velocityIterations << ','
      << (job.engine->hasPositionIterations ? std::to_string(job.settings.positionIterations) : "")
      << ',' << job.settings.threads << ',' << scene.bodies.size() << ',' << scene.joints.size()
      << ',' << r.steps << ',' << number(r.msPerStep) << ',' << r.contacts << ','
      << number(e.penetrationMean) << ',' << number(e.penetrationMax) << ','
      << (resting ? number(e.driftMax) : "") << ',' << (resting ? number(e.sinkMax) : "") << ','
      << (jointed ? number(e.jointGapMean) : "") << ',' << (jointed ? number(e.jointGapMax) : "")
      << ',' << (e.energyMeaningful ? number(e.energyDrift) : "") << ','
      << (scene.kind == SceneKind::Contained ? std::to_string(e.escaped) : "") << ','
      << (scene.kind == SceneKind::Impact ? number(e.momentumDrift) : "") << ','
      << (e.stood ? "true" : "false");
  return row.str();
}

// Peak heap per body and per contact while the engine builds and steps the scene at its
// defaults: bytes after building / bodies, and (peak while stepping - after building) / contacts.
std::string memoryRow(const EngineInfo& engine, const SceneSpec& scene, int steps) {
  const size_t baseline = heapBytesInUse();
  size_t built = 0, peak = 0, contacts = 0;
  {
    std::unique_ptr<EngineAdapter> adapter = engine.make();
    adapter->build(scene, engine.defaults);
    built = heapBytesInUse() - baseline;
    peak = built;
    for (int s = 0; s < steps; ++s) {
      adapter->step();
      const size_t now = heapBytesInUse() - baseline;
      if (now > peak) {
        peak = now;
      }
    }
    contacts = adapter->contactCount();
  }
  std::ostringstream row;
  const double perContact = contacts ? double(peak - built) / contacts : 0.0;
  row << engine.name << ',' << scene.name << ',' << scene.bodies.size() << ',' << contacts << ','
      << built << ',' << peak << ',' << number(double(built) / scene.bodies.size()) << ','
      << number(perContact) << ',' << number(double(peak) / scene.bodies.size());
  return row.str();
}

int run(const Options& options) {
  const std::vector<SceneSpec> scenes = makeScenes(options.quick);
  const std::vector<EngineInfo> allEngines = availableEngines();
  std::vector<const EngineInfo*> engines;
  for (const std::string& name : options.engines) {
    auto it = std::find_if(allEngines.begin(), allEngines.end(),
                           [&](const EngineInfo& e) { return e.name == name; });
    if (it == allEngines.end()) {
      std::cerr << "impulse2d_bench: engine '" << name << "' is not compiled in\n";
      return 2;
    }
  }
  for (const EngineInfo& e : allEngines) {
    if (options.engines.empty() || std::find(options.engines.begin(), options.engines.end(),
                                             e.name) != options.engines.end()) {
      engines.push_back(&e);
    }
  }
  // Per scene: every engine's default row first (they run as one batch, below), then the sweeps;
  // each once per thread count. A row the engine refuses is skipped with its reason.
  std::vector<Job> jobs;
  size_t refused = 0;
  for (const SceneSpec& scene : scenes) {
    if (!selected(options.scenes, scene.name)) continue;
    std::vector<Job> batch, sweeps;
    for (const EngineInfo* engine : engines) {
      for (const std::string& solver : engine->solvers) {
        if (!options.solvers.empty() && std::find(options.solvers.begin(), options.solvers.end(),
                                                  solver) == options.solvers.end()) {
          continue;
        }
        for (const Job& job : jobsFor(*engine, solver, scene, options.full)) {
          (job.sweep == "default" ? batch : sweeps).push_back(job);
        }
      }
      if (engine->name == "impulse2d") {
        for (const EngineSettings& settings : options.also) {
          batch.push_back({engine, &scene, settings, "chosen"});
        }
      }
    }
    batch.insert(batch.end(), sweeps.begin(), sweeps.end());
    for (const Job& job : batch) {
      for (const int threads : options.threads) {
        Job copy = job;
        copy.settings.threads = threads;
        const std::string why =
            job.engine->refuses ? job.engine->refuses(scene, copy.settings) : "";
        if (why.empty()) {
          jobs.push_back(copy);
        } else {
          std::cerr << "impulse2d_bench: skipping " << job.engine->name << ' '
                    << job.settings.solver << " on " << scene.name << " with " << threads
                    << " thread(s): " << why << "\n";
          ++refused;
        }
      }
    }
  }
  if (jobs.empty()) {
    std::cerr << "impulse2d_bench: "
              << (refused ? "every row was refused (above)"
                          : "nothing matches --scenes, --engines and --solvers")
              << "\n";
    return 2;
  }

  std::ofstream csv(options.csv);
  if (!csv) {
    std::cerr << "impulse2d_bench: cannot write " << options.csv << "\n";
    return 1;
  }
  csv << kCsvHeader << '\n';
  const bool terminal = isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  auto progress = [&](size_t index, const Job& job, int repeat, int repeats, double ms,
                      bool stood) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char line[320];
    std::snprintf(line, sizeof line,
                  "[%zu/%zu %.0f s] %s %s %s dt=1/%.0f vel=%d pos=%d threads=%d run %d/%d: %.3f "
                  "ms/step%s",
                  index + 1, jobs.size(), elapsed, job.engine->name.c_str(),
                  job.settings.solver.c_str(), job.scene->name.c_str(), 1.0 / job.settings.timeStep,
                  job.settings.velocityIterations, job.settings.positionIterations,
                  job.settings.threads, repeat + 1, repeats, ms, stood ? "" : " (did not stand)");
    std::cerr << (terminal ? "\r\033[K" : "") << line << (terminal ? "" : "\n") << std::flush;
  };
  // Jobs run in batches: the default (and chosen) rows of one scene together, each swept row
  // alone. Within a
  // batch the repeats go round robin over the jobs, so a change in the machine's load (it may be
  // shared) falls on every engine alike and the ratios of one run stay fair.
  for (size_t first = 0; first < jobs.size();) {
    size_t last = first + 1;
    auto batched = [](const Job& job) { return job.sweep == "default" || job.sweep == "chosen"; };
    if (batched(jobs[first])) {
      while (last < jobs.size() && batched(jobs[last]) && jobs[last].scene == jobs[first].scene) {
        ++last;
      }
    }
    const int repeats = batched(jobs[first]) ? options.repeats : options.sweepRepeats;
    std::vector<RunResult> results(last - first);
    std::vector<std::vector<double>> times(last - first);
    for (int r = 0; r < repeats; ++r) {
      for (size_t k = first; k < last; ++k) {
        const RunResult once = runOnce(jobs[k], options.steps, r == 0);
        if (r == 0) results[k - first] = once;
        times[k - first].push_back(once.msPerStep);
        progress(k, jobs[k], r, repeats, once.msPerStep, results[k - first].errors.stood);
      }
    }
    for (size_t k = first; k < last; ++k) {
      std::vector<double>& t = times[k - first];
      std::sort(t.begin(), t.end());
      results[k - first].msPerStep = t[t.size() / 2];
      csv << csvRow(jobs[k], results[k - first]) << '\n';
    }
    csv.flush();
    first = last;
  }
  if (terminal) std::cerr << '\n';
  if (!csv) {
    std::cerr << "impulse2d_bench: writing " << options.csv << " failed\n";
    return 1;
  }

  const auto large = std::find_if(scenes.begin(), scenes.end(),
                                  [](const SceneSpec& s) { return s.name == "pyramid100"; });
  if (large != scenes.end() && selected(options.scenes, large->name)) {
    std::ofstream memory(options.memoryCsv);
    if (!memory) {
      std::cerr << "impulse2d_bench: cannot write " << options.memoryCsv << "\n";
      return 1;
    }
    memory << "engine,scene,bodies,contacts,bytes_built,bytes_peak,bytes_per_body,"
              "bytes_per_contact,peak_bytes_per_body\n";
    for (const EngineInfo* engine : engines) {
      memory << memoryRow(*engine, *large, options.quick ? 15 : 60) << '\n';
    }
    std::cerr << "memory figures written to " << options.memoryCsv << "\n";
  }
  std::cerr << jobs.size() << " rows written to " << options.csv << "\n";
  return 0;
}

}  // namespace
}  // namespace impulse2d_bench

int main(int argc, char** argv) {
  using namespace impulse2d_bench;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
  }
  const std::string simd = impulse2d::useSimdTargetFromEnvironment();
  if (!simd.empty()) std::cerr << "impulse2d_bench: " << simd << "\n";
  Options options;
  const std::string why = parseOptions(argc, argv, &options);
  if (!why.empty()) {
    std::cerr << "impulse2d_bench: " << why << " (--help for usage)\n";
    return 2;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {  // an engine refusing what a scene asks of it
    std::cerr << "impulse2d_bench: " << e.what() << "\n";
    return 1;
  }
}
