// Parsing impulse2d_sim's arguments. Every number is checked whole (no trailing junk, no NaN) and
// world settings are checked with World::validate, so the limits match the scene file's.
#include "options.hpp"

#include <impulse2d/world.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>

namespace impulse2d {
namespace sim {

const char* const kUsage =
    "usage: impulse2d_sim SCENE.yaml [--steps N | --duration SECONDS] [--time-step DT]\n"
    "                     [--velocity-iterations K] [--position-iterations K]\n"
    "                     [--solver baumgarte|ngs|soft|substep] [--threads N] [--csv FILE]\n"
    "                     [--contacts FILE] [--every K] [--hash] [--profile]\n"
    "\n"
    "Runs a scene file (the YAML schema of the impulse2d README) headless, without ROS.\n"
    "\n"
    "  --steps N                fixed steps to run (N >= 0)\n"
    "  --duration SECONDS       simulated time to run, rounded up to whole steps (default 10)\n"
    "  --time-step DT           override world.time_step (s, > 0)\n"
    "  --velocity-iterations K  override world.velocity_iterations (1 to 1000)\n"
    "  --position-iterations K  override world.position_iterations (0 to 1000)\n"
    "  --solver NAME            override world.solver: baumgarte, ngs, soft or substep\n"
    "  --threads N              override world.threads (1 to 256; the same result for any N)\n"
    "  --csv FILE               write step,time,body,x,y,angle,vx,vy,omega: one row per\n"
    "                           dynamic or kinematic body per written step; step 0 is the\n"
    "                           initial state\n"
    "  --contacts FILE          write step,body_a,body_b,x,y,nx,ny,separation,normal_impulse,\n"
    "                           tangent_impulse: the contact points of each written step >= 1\n"
    "  --every K                write step 0, every K-th step and the last (default 1)\n"
    "  --hash                   print \"hash: <16 hex digits>\" of the final state's exact bits\n"
    "  --profile                print each stage's mean wall time per step (ms), as Box2D's\n"
    "                           b2Profile: broad phase, narrow phase, colouring, prepare, warm\n"
    "                           start, solve, relax, restitution, positions, integrate,\n"
    "                           continuous, sleep\n"
    "  -h, --help               print this help\n"
    "\n"
    "Prints one summary line (steps, simulated and wall seconds, bodies, contacts) on stdout.\n"
    "Exit status: 0 on success, 1 when the run fails (an output file cannot be written), 2 for\n"
    "a bad argument or scene.\n";

namespace {

bool toUnsigned(const std::string& text, uint64_t* out) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return false;
  *out = v;
  return true;
}

bool toFinite(const std::string& text, double* out) {
  if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

// World::validate's reason without its YAML key, e.g. "must be finite and > 0".
std::string worldReason(const WorldDef& probe) {
  const std::string why = World::validate(probe);
  const size_t colon = why.find(": ");
  return colon == std::string::npos ? why : why.substr(colon + 2);
}

using Setter = std::function<std::string(const std::string&, Options*)>;

std::string setIterations(const std::string& value, int* out, bool* given, int WorldDef::*field) {
  uint64_t v = 0;
  WorldDef probe;
  if (!toUnsigned(value, &v) || v > 1000000) return "must be a whole number";
  probe.*field = static_cast<int>(v);
  const std::string why = worldReason(probe);
  if (!why.empty()) return why;
  *out = static_cast<int>(v);
  *given = true;
  return "";
}

const std::map<std::string, Setter>& setters() {
  static const std::map<std::string, Setter> table = {
      {"--steps",
       [](const std::string& v, Options* o) -> std::string {
         if (!toUnsigned(v, &o->steps)) return "must be a whole number >= 0";
         o->stepsGiven = true;
         return "";
       }},
      {"--duration",
       [](const std::string& v, Options* o) -> std::string {
         if (!toFinite(v, &o->duration) || o->duration < 0.0) {
           return "must be a finite number of seconds >= 0";
         }
         return "";
       }},
      {"--time-step",
       [](const std::string& v, Options* o) -> std::string {
         WorldDef probe;
         if (!toFinite(v, &probe.timeStep)) return "must be a finite number of seconds";
         const std::string why = worldReason(probe);
         if (!why.empty()) return why;
         o->timeStep = probe.timeStep;
         o->timeStepGiven = true;
         return "";
       }},
      {"--velocity-iterations",
       [](const std::string& v, Options* o) {
         return setIterations(v, &o->velocityIterations, &o->velocityIterationsGiven,
                              &WorldDef::velocityIterations);
       }},
      {"--position-iterations",
       [](const std::string& v, Options* o) {
         return setIterations(v, &o->positionIterations, &o->positionIterationsGiven,
                              &WorldDef::positionIterations);
       }},
      {"--solver",
       [](const std::string& v, Options* o) -> std::string {
         if (!solverFromName(v, &o->solver)) return "must be " + solverNameList();
         o->solverGiven = true;
         return "";
       }},
      {"--threads",
       [](const std::string& v, Options* o) {
         return setIterations(v, &o->threads, &o->threadsGiven, &WorldDef::threads);
       }},
      {"--csv",
       [](const std::string& v, Options* o) -> std::string {
         if (v.empty()) return "needs a file name";
         o->csvPath = v;
         return "";
       }},
      {"--contacts",
       [](const std::string& v, Options* o) -> std::string {
         if (v.empty()) return "needs a file name";
         o->contactsPath = v;
         return "";
       }},
      {"--every",
       [](const std::string& v, Options* o) -> std::string {
         if (!toUnsigned(v, &o->every) || o->every < 1) return "must be a whole number >= 1";
         return "";
       }},
  };
  return table;
}

}  // namespace

bool parseOptions(int argc, const char* const* argv, Options* out, std::string* error) {
  Options o;
  bool durationGiven = false;
  bool onlyFiles = false;  // after "--", so a scene may be named "-x.yaml"
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (onlyFiles || arg.empty() || arg[0] != '-' || arg == "-") {
      if (!o.scenePath.empty()) {
        *error = "one scene file only, got '" + o.scenePath + "' and '" + arg + "'";
        return false;
      }
      o.scenePath = arg;
      continue;
    }
    if (arg == "--") {
      onlyFiles = true;
    } else if (arg == "-h" || arg == "--help") {
      o.help = true;
    } else if (arg == "--hash") {
      o.hash = true;
    } else if (arg == "--profile") {
      o.profile = true;
    } else {
      const size_t eq = arg.find('=');
      const std::string flag = arg.substr(0, eq);
      const auto setter = setters().find(flag);
      if (setter == setters().end()) {
        *error = "unknown option '" + flag + "' (see --help)";
        return false;
      }
      std::string value;
      if (eq != std::string::npos) {
        value = arg.substr(eq + 1);
      } else if (i + 1 < argc) {
        value = argv[++i];
      } else {
        *error = flag + " needs a value (see --help)";
        return false;
      }
      const std::string why = setter->second(value, &o);
      if (!why.empty()) {
        *error = flag + " '" + value + "': " + why;
        return false;
      }
      durationGiven = durationGiven || flag == "--duration";
    }
  }
  if (o.help) {
    *out = o;
    return true;
  }
  if (o.stepsGiven && durationGiven) {
    *error = "give --steps or --duration, not both";
    return false;
  }
  if (o.scenePath.empty()) {
    *error = "no scene file given (see --help)";
    return false;
  }
  if (!o.csvPath.empty() && o.csvPath == o.contactsPath) {
    *error = "--csv and --contacts must name different files";
    return false;
  }
  *out = o;
  return true;
}

WorldDef applyOverrides(const Options& options, WorldDef settings) {
  if (options.timeStepGiven) settings.timeStep = options.timeStep;
  if (options.velocityIterationsGiven) settings.velocityIterations = options.velocityIterations;
  if (options.positionIterationsGiven) settings.positionIterations = options.positionIterations;
  if (options.solverGiven) settings.solver = options.solver;
  if (options.threadsGiven) settings.threads = options.threads;
  return settings;
}

bool stepsToRun(const Options& options, double timeStep, uint64_t* steps, std::string* error) {
  if (options.stepsGiven) {
    *steps = options.steps;
    return true;
  }
  const double exact = options.duration / timeStep;
  // 10 s at 0.01 s is 1000.0000000000001 steps in doubles, not 1001.
  const double nearest = std::round(exact);
  const double count =
      std::abs(exact - nearest) <= 1e-9 * std::max(1.0, nearest) ? nearest : std::ceil(exact);
  if (!(count < 1e15)) {
    *error = "--duration: too many steps of " + std::to_string(timeStep) + " s";
    return false;
  }
  *steps = static_cast<uint64_t>(count);
  return true;
}

}  // namespace sim
}  // namespace impulse2d
