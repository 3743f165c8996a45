// impulse2d_core_soak: runs the core soak (soak_run.hpp) for a time or a number of seeds.
//
//   impulse2d_core_soak [--seed N] [--seconds S | --runs N] [--steps N] [--solver NAME|all]
//                       [--threads N] [--top-down] [--wrenches-at-points] [--watch BODY]
//                       [--keep-going] [--junit FILE]
//
// Seeds run one after the other from --seed, each with every solver asked for, until --seconds
// of wall time have passed (default 60) or --runs seeds are done. Prints one line per run and a
// total; on a violation, the seed, the solver and the last edits, and exits 1 (after the seed's
// other solvers; --keep-going runs every seed asked for and counts the failures). --watch prints
// one body's pose, velocity and contacts after every step (to see how a violation came about).
// --wrenches-at-points pushes off the centre, as the ROS soak's clients do (soak::Options).
#include <impulse2d/defs.hpp>
#include <impulse2d/simd.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "soak_run.hpp"

namespace {

int usage(const char* why) {
  std::fprintf(stderr,
               "impulse2d_core_soak: %s\nusage: impulse2d_core_soak [--seed N] [--seconds S | "
               "--runs N] [--steps N] [--solver baumgarte|ngs|soft|substep|all] [--threads N] "
               "[--top-down] [--wrenches-at-points] [--watch BODY] [--keep-going] "
               "[--junit FILE]\n",
               why);
  return 2;
}

bool number(const char* text, double lo, double hi, double* out) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= lo && v <= hi)) return false;
  *out = v;
  return true;
}

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace impulse2d;
  const std::string simd = useSimdTargetFromEnvironment();
  if (!simd.empty()) std::fprintf(stderr, "impulse2d_core_soak: %s\n", simd.c_str());
  double seed = 1, seconds = 60, runs = 0, steps = 600, threads = 1;
  bool topDown = false, keepGoing = false, wrenchesAtPoints = false;
  std::string junit, watch;
  std::vector<SolverType> solvers(std::begin(kAllSolvers), std::end(kAllSolvers));
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    auto take = [&](double lo, double hi, double* out) {
      if (!value || !number(value, lo, hi, out)) return false;
      ++i;
      return true;
    };
    if (arg == "--seed") {
      if (!take(0, 1e15, &seed)) return usage("--seed needs a whole number >= 0");
    } else if (arg == "--seconds") {
      if (!take(0, 1e7, &seconds)) return usage("--seconds needs a number >= 0");
    } else if (arg == "--runs") {
      if (!take(1, 1e9, &runs)) return usage("--runs needs a number >= 1");
    } else if (arg == "--steps") {
      if (!take(1, 1e7, &steps)) return usage("--steps needs a number >= 1");
    } else if (arg == "--threads") {
      if (!take(1, 256, &threads)) return usage("--threads needs 1 to 256");
    } else if (arg == "--keep-going") {
      keepGoing = true;
    } else if (arg == "--top-down") {
      topDown = true;
    } else if (arg == "--wrenches-at-points") {
      wrenchesAtPoints = true;
    } else if (arg == "--watch") {
      if (!value) return usage("--watch needs a body name");
      watch = value;
      ++i;
    } else if (arg == "--junit") {
      if (!value) return usage("--junit needs a file");
      junit = value;
      ++i;
    } else if (arg == "--solver") {
      if (!value) return usage("--solver needs a name");
      SolverType s;
      if (std::string(value) == "all") {
        solvers.assign(std::begin(kAllSolvers), std::end(kAllSolvers));
      } else if (solverFromName(value, &s)) {
        solvers.assign(1, s);
      } else {
        return usage(
            ("unknown solver '" + std::string(value) + "'; use " + solverNameList() + " or all")
                .c_str());
      }
      ++i;
    } else {
      return usage(("unknown argument '" + arg + "'").c_str());
    }
  }

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<std::string> cases;
  uint64_t totalSteps = 0, totalEdits = 0, totalChecks = 0, done = 0, failed = 0;
  for (uint64_t s = static_cast<uint64_t>(seed);; ++s) {
    const uint64_t runsDone = s - static_cast<uint64_t>(seed);
    if (runs > 0 ? runsDone >= runs : (runsDone > 0 && elapsed() >= seconds)) break;
    for (const SolverType solver : solvers) {
      soak::Options options;
      options.seed = s;
      options.steps = static_cast<int>(steps);
      options.solver = solver;
      options.threads = static_cast<int>(threads);
      options.gravity = !topDown && soak::gravityOf(s);
      options.watch = watch;
      options.wrenchesAtPoints = wrenchesAtPoints;
      const soak::Report report = soak::run(options);
      ++done;
      totalSteps += report.steps;
      totalEdits += report.edits;
      totalChecks += report.checks;
      const std::string line = report.summary(options);
      std::printf("%s\n", line.c_str());
      std::string xml = "  <testcase classname=\"core_soak\" name=\"seed_" + std::to_string(s) +
                        "_" + solverName(solver) + (wrenchesAtPoints ? "_at_points" : "") + "\"";
      if (report.violations.empty()) {
        xml += "/>";
      } else {
        ++failed;
        std::string detail;
        for (const std::string& v : report.violations) detail += v + "\n";
        detail += "last edits, oldest first:\n";
        for (const std::string& e : report.lastEdits) detail += "  " + e + "\n";
        detail += "reproduce: impulse2d_core_soak --seed " + std::to_string(s) +
                  " --runs 1 --steps " + std::to_string(options.steps) + " --solver " +
                  solverName(solver) + (topDown ? " --top-down" : "") +
                  (wrenchesAtPoints ? " --wrenches-at-points" : "") + "\n";
        std::fprintf(stderr, "%s", detail.c_str());
        xml += "><failure message=\"" + xmlEscape(report.violations.front()) + "\"><![CDATA[" +
               detail + "]]></failure></testcase>";
      }
      cases.push_back(xml);
    }
    std::fflush(stdout);
    if (failed > 0 && !keepGoing) break;
  }
  std::printf("core soak: %llu runs, %llu steps, %llu edits, %llu checks, %llu failed, %.0f s\n",
              static_cast<unsigned long long>(done), static_cast<unsigned long long>(totalSteps),
              static_cast<unsigned long long>(totalEdits),
              static_cast<unsigned long long>(totalChecks), static_cast<unsigned long long>(failed),
              elapsed());
  if (!junit.empty()) {
    std::ofstream out(junit);
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"core_soak\" tests=\""
        << cases.size() << "\" failures=\"" << failed << "\">\n";
    for (const std::string& c : cases) out << c << "\n";
    out << "</testsuite>\n";
  }
  return failed > 0 ? 1 : 0;
}
