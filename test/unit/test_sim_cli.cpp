// impulse2d_sim as users run it: exit codes, one-line errors, the CSV layouts of the contract,
// reproducible hashes, and a full-length pyramid run.
#include <impulse2d/scene.hpp>
#include <impulse2d/simd.hpp>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace impulse2d {
namespace {

struct SimRun {
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string shellQuoted(const std::string& arg) {
  std::string out = "'";
  for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "impulse2d_sim_test_" + std::to_string(getpid()) + "_" + name;
}

SimRun runSim(const std::vector<std::string>& args) {
  static int runs = 0;
  const std::string outPath = tempPath("stdout" + std::to_string(runs));
  const std::string errPath = tempPath("stderr" + std::to_string(runs++));
  std::string command = shellQuoted(IMPULSE2D_SIM_EXECUTABLE);
  for (const std::string& arg : args) command += " " + shellQuoted(arg);
  command += " >" + shellQuoted(outPath) + " 2>" + shellQuoted(errPath) + " </dev/null";
  const int status = std::system(command.c_str());
  SimRun run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = readFile(outPath);
  run.err = readFile(errPath);
  std::remove(outPath.c_str());
  std::remove(errPath.c_str());
  return run;
}

std::string config(const std::string& name) {
  return std::string(IMPULSE2D_SOURCE_DIR) + "/config/" + name;
}

size_t movingBodies(const std::string& scenePath) {
  Scene scene;
  std::string error;
  EXPECT_TRUE(loadSceneFile(scenePath, &scene, &error)) << error;
  size_t count = 0;
  for (const BodyDef& body : scene.bodies) count += body.type != BodyType::Static;
  return count;
}

TEST(SimCli, HelpExitsZeroWithUsage) {
  for (const char* flag : {"--help", "-h"}) {
    const SimRun run = runSim({flag});
    EXPECT_EQ(run.exitCode, 0);
    EXPECT_EQ(run.out.rfind("usage: impulse2d_sim SCENE.yaml", 0), 0u) << run.out;
    EXPECT_NE(run.out.find("--contacts FILE"), std::string::npos);
    EXPECT_NE(run.out.find("override world.solver: " + solverNameList()), std::string::npos)
        << "the usage does not name every solver: " << solverNameList();
    EXPECT_TRUE(run.err.empty()) << run.err;
  }
}

void expectOneLineError(const SimRun& run, int exitCode, const std::string& mentions) {
  EXPECT_EQ(run.exitCode, exitCode) << run.err;
  const std::vector<std::string> errLines = lines(run.err);
  ASSERT_EQ(errLines.size(), 1u) << run.err;
  EXPECT_EQ(errLines[0].rfind("impulse2d_sim: ", 0), 0u) << run.err;
  EXPECT_NE(errLines[0].find(mentions), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
}

// Each body the world removes is named on stderr with its cause and step, not only counted.
TEST(SimCli, EachRemovedBodyIsReportedWithItsCauseAndStep) {
  const std::string scene = tempPath("removed.yaml");
  {
    std::ofstream out(scene);
    out << "world: {remove_lost_bodies: true, max_linear_speed: 1000000}\n"
           "bodies:\n"
           "  - {name: ground, type: static, position: [0, -0.5], shapes: [{size: [20, 1]}]}\n"
           "  - {name: sinker, position: [0, -30], shapes: [{size: [1, 1]}]}\n"
           "  - {name: flyer, position: [0, 5], linear_velocity: [0, 1000000],\n"
           "     shapes: [{size: [1, 1]}]}\n";
  }
  // Up at 1e6 m/s, less 9.81 m/s^2: past y = 1e7 m in step 1001.
  const SimRun run = runSim({scene, "--steps", "1001"});
  std::remove(scene.c_str());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::vector<std::string> err = lines(run.err);
  ASSERT_EQ(err.size(), 2u) << run.err;
  EXPECT_EQ(
      err[0].rfind("impulse2d_sim: step 1 (t = 0.01 s): removed body 'sinker' (LOST_FOR_GOOD)", 0),
      0u)
      << err[0];
  EXPECT_NE(err[0].find("lost for good"), std::string::npos) << err[0];
  EXPECT_EQ(
      err[1].rfind("impulse2d_sim: step 1001 (t = 10.01 s): removed body 'flyer' (LEFT_WORLD)", 0),
      0u)
      << err[1];
  EXPECT_NE(err[1].find("it left the world extent of 1e7 m"), std::string::npos) << err[1];
  EXPECT_NE(run.out.find("bodies: 1, contacts: 0, removed: 2 (listed on stderr)"),
            std::string::npos)
      << run.out;
}

TEST(SimCli, BadArgumentsExitTwoWithOneLine) {
  const std::string pendulum = config("pendulum.yaml");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{pendulum, "--bogus"}, "--bogus"},
      {{}, "no scene file"},
      {{pendulum, pendulum}, "one scene file"},
      {{pendulum, "--steps"}, "--steps needs a value"},
      {{pendulum, "--steps", "-1"}, "--steps"},
      {{pendulum, "--steps", "ten"}, "--steps"},
      {{pendulum, "--steps", "5", "--duration", "1"}, "not both"},
      {{pendulum, "--duration", "nan"}, "--duration"},
      {{pendulum, "--duration", "inf"}, "--duration"},
      {{pendulum, "--time-step", "0"}, "--time-step"},
      {{pendulum, "--time-step", "1e-3x"}, "--time-step"},
      {{pendulum, "--velocity-iterations", "0"}, "--velocity-iterations"},
      {{pendulum, "--position-iterations=1001"}, "--position-iterations"},
      {{pendulum, "--every", "0"}, "--every"},
      {{pendulum, "--solver", "pgs"}, "--solver 'pgs': must be baumgarte, ngs, soft or substep"},
      {{pendulum, "--csv", "same.csv", "--contacts", "same.csv"}, "different files"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.second);
    expectOneLineError(runSim(c.first), 2, c.second);
  }
}

TEST(SimCli, MissingSceneFileExitsTwoWithOneLine) {
  expectOneLineError(runSim({"/nonexistent/scene.yaml"}), 2, "/nonexistent/scene.yaml");
}

TEST(SimCli, BadSceneExitsTwoNamingTheKey) {
  const std::string bad = std::string(IMPULSE2D_SOURCE_DIR) + "/test/scenes/bad/";
  expectOneLineError(runSim({bad + "misspelled_key.yaml"}), 2,
                     "bodies[1] 'box': shapes[0].frction");
  expectOneLineError(runSim({bad + "unknown_body.yaml"}), 2, "joints[0] 'hinge': body_a");
}

// Devices are checked as in the node; a drive with no command holds its body still against a
// push (here, the body starts moving at 1 m/s), lasers and bumpers are not run.
TEST(SimCli, ScenesWithDevicesRunAndBadDevicesExitTwo) {
  const std::string scene = tempPath("robot.yaml");
  const std::string csv = tempPath("robot.csv");
  auto write = [&](const std::string& plane) {
    std::ofstream out(scene);
    out << "world: {plane: " << plane << ", gravity: [0.0, 0.0]}\n"
        << "bodies: [{name: robot, linear_velocity: [1.0, 0.0], shapes: [{type: circle, "
           "radius: 0.25}]}]\n"
        << "devices: [{type: diff_drive, name: drive, body: robot}, {type: laser, name: laser, "
           "body: robot}, {type: bumper, name: bumper, body: robot}]\n";
  };
  write("xy");
  const SimRun run = runSim({scene, "--steps", "100", "--every", "100", "--csv", csv});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  const std::vector<std::string> rows = lines(readFile(csv));
  ASSERT_EQ(rows.size(), 3u);  // the header, step 0 and step 100
  // The drive brakes at most max_force / mass = 9.81 m/s^2: stopped after 0.1 s and about 5 cm
  // (without it the robot would have coasted 1 m).
  double x = 0.0, vx = 1.0;
  ASSERT_EQ(std::sscanf(rows[2].c_str(), "100,%*[^,],robot,%lf,%*[^,],%*[^,],%lf", &x, &vx), 2)
      << rows[2];
  EXPECT_NEAR(x, 0.05, 0.01);
  EXPECT_NEAR(vx, 0.0, 1e-9);
  std::remove(csv.c_str());
  write("xz");
  expectOneLineError(runSim({scene}), 2,
                     "devices[0] 'drive': type: a diff_drive drives on the floor");
  std::remove(scene.c_str());
}

TEST(SimCli, UnwritableOutputIsAnError) {
  const SimRun run =
      runSim({config("pendulum.yaml"), "--steps", "1", "--csv", "/nonexistent/x.csv"});
  EXPECT_NE(run.exitCode, 0);
  expectOneLineError(run, 1, "/nonexistent/x.csv");
  if (access("/dev/full", W_OK) == 0) {  // the disk filling up is found when the file is closed
    expectOneLineError(runSim({config("pendulum.yaml"), "--steps", "1", "--csv", "/dev/full"}), 1,
                       "/dev/full");
  }
}

TEST(SimCli, CsvHasTheHeaderAndOneRowPerMovingBodyPerWrittenStep) {
  const std::string csv = tempPath("pendulum.csv");
  const SimRun run =
      runSim({config("pendulum.yaml"), "--steps", "10", "--every", "5", "--csv", csv});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::vector<std::string> rows = lines(readFile(csv));
  std::remove(csv.c_str());
  const size_t bodies = movingBodies(config("pendulum.yaml"));
  ASSERT_GE(bodies, 1u);
  ASSERT_EQ(rows.size(), 1 + 3 * bodies);  // steps 0, 5 and 10
  EXPECT_EQ(rows[0], "step,time,body,x,y,angle,vx,vy,omega");
  EXPECT_EQ(rows[1].rfind("0,0,", 0), 0u) << rows[1];
  EXPECT_EQ(rows[1 + bodies].rfind("5,", 0), 0u) << rows[1 + bodies];
  EXPECT_EQ(rows.back().rfind("10,", 0), 0u) << rows.back();
  for (size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(std::count(rows[i].begin(), rows[i].end(), ','), 8) << rows[i];
  }
  // Full precision: the time of step 5 is printed as the double it is.
  std::istringstream row(rows[1 + bodies]);
  std::string step, time;
  std::getline(row, step, ',');
  std::getline(row, time, ',');
  EXPECT_NEAR(std::stod(time), 0.05, 1e-12);
  EXPECT_GE(time.size(), 17u) << time;
}

TEST(SimCli, CsvAlwaysWritesTheLastStep) {
  const std::string csv = tempPath("every4.csv");
  const SimRun run =
      runSim({config("pendulum.yaml"), "--steps", "10", "--every", "4", "--csv", csv});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::set<std::string> steps;
  const std::vector<std::string> rows = lines(readFile(csv));
  std::remove(csv.c_str());
  for (size_t i = 1; i < rows.size(); ++i) steps.insert(rows[i].substr(0, rows[i].find(',')));
  EXPECT_EQ(steps, (std::set<std::string>{"0", "4", "8", "10"}));
}

TEST(SimCli, ContactsCsvHasTheHeaderAndWrittenSteps) {
  const std::string csv = tempPath("contacts.csv");
  const SimRun run =
      runSim({config("ramp.yaml"), "--steps", "20", "--every", "10", "--contacts", csv});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::vector<std::string> rows = lines(readFile(csv));
  std::remove(csv.c_str());
  ASSERT_GE(rows.size(), 2u);  // the boxes rest on the ramp
  EXPECT_EQ(rows[0], "step,body_a,body_b,x,y,nx,ny,separation,normal_impulse,tangent_impulse");
  for (size_t i = 1; i < rows.size(); ++i) {
    const std::string step = rows[i].substr(0, rows[i].find(','));
    EXPECT_TRUE(step == "10" || step == "20") << rows[i];
    EXPECT_EQ(std::count(rows[i].begin(), rows[i].end(), ','), 9) << rows[i];
  }
}

TEST(SimCli, PrintsOneSummaryLineAndAppliesOverrides) {
  const SimRun run = runSim({config("pendulum.yaml"), "--duration", "1", "--time-step", "0.02"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::vector<std::string> out = lines(run.out);
  ASSERT_EQ(out.size(), 1u) << run.out;
  // "steps: 50, simulated: 1 s, wall: <seconds> s, bodies: 2, contacts: <count>"
  double wall = -1.0;
  int contacts = -1;
  char tail = 0;
  EXPECT_EQ(std::sscanf(out[0].c_str(),
                        "steps: 50, simulated: 1 s, wall: %lf s, bodies: 2, contacts: %d%c", &wall,
                        &contacts, &tail),
            2)
      << out[0];
  EXPECT_GE(wall, 0.0) << out[0];
  EXPECT_GE(contacts, 0) << out[0];
}

TEST(SimCli, HashIsReproducible) {
  const std::vector<std::string> args = {config("demo.yaml"), "--steps", "300", "--hash"};
  const SimRun first = runSim(args);
  const SimRun second = runSim(args);
  ASSERT_EQ(first.exitCode, 0) << first.err;
  ASSERT_EQ(second.exitCode, 0) << second.err;
  const std::vector<std::string> a = lines(first.out), b = lines(second.out);
  ASSERT_EQ(a.size(), 2u) << first.out;
  ASSERT_EQ(b.size(), 2u) << second.out;
  ASSERT_EQ(a[1].size(), 6u + 16u) << a[1];
  EXPECT_EQ(a[1].substr(0, 6), "hash: ");
  EXPECT_EQ(a[1].find_first_not_of("0123456789abcdef", 6), std::string::npos) << a[1];
  EXPECT_EQ(a[1], b[1]);
}

// --profile lists the stages the solver has, each with a mean time and share, then the step; and
// timing the stages changes nothing of the result.
TEST(SimCli, ProfilePrintsEachStageAndChangesNothing) {
  const SimRun plain = runSim({config("pyramid.yaml"), "--steps", "120", "--hash"});
  const SimRun timed = runSim({config("pyramid.yaml"), "--steps", "120", "--hash", "--profile"});
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  ASSERT_EQ(timed.exitCode, 0) << timed.err;
  const std::vector<std::string> a = lines(plain.out), b = lines(timed.out);
  ASSERT_EQ(a.size(), 2u) << plain.out;
  ASSERT_GE(b.size(), 4u) << timed.out;
  EXPECT_EQ(a[1], b[1]);  // the same hash
  EXPECT_EQ(b[2], "profile (ms per step, mean of 120 steps):");
  double sum = 0.0, step = -1.0;
  std::set<std::string> names;
  for (size_t i = 3; i < b.size(); ++i) {
    std::istringstream line(b[i]);
    std::string word, name;
    double ms = -1.0;
    // A name may be two words ("broad phase"): read words until a number.
    while (line >> word) {
      char* end = nullptr;
      const double value = std::strtod(word.c_str(), &end);
      if (end != word.c_str() && *end == '\0') {
        ms = value;
        break;
      }
      name += (name.empty() ? "" : " ") + word;
    }
    ASSERT_GE(ms, 0.0) << b[i];
    if (name == "step") {
      step = ms;
    } else {
      names.insert(name);
      sum += ms;
    }
  }
  EXPECT_GT(step, 0.0) << timed.out;
  EXPECT_LE(sum, step * 1.0001 + 1e-4) << timed.out;  // the stages are parts of the step
  for (const char* stage : {"broad phase", "narrow phase", "prepare", "solve", "integrate"}) {
    EXPECT_TRUE(names.count(stage)) << stage << " missing from\n" << timed.out;
  }
}

// IMPULSE2D_SIMD picks the kernels' instruction set at start-up; a name it does not know is
// said on stderr and the run goes on, on the best one. Any choice gives the same hash.
TEST(SimCli, SimdFromTheEnvironment) {
  const std::vector<std::string> args = {config("pyramid.yaml"), "--steps", "120", "--hash"};
  const SimRun best = runSim(args);
  ASSERT_EQ(best.exitCode, 0) << best.err;
  setenv("IMPULSE2D_SIMD", "NEON_BF16", 1);
  const SimRun bogus = runSim(args);
  setenv("IMPULSE2D_SIMD", simdTargets().back().c_str(), 1);  // the portable one
  const SimRun portable = runSim(args);
  unsetenv("IMPULSE2D_SIMD");
  ASSERT_EQ(bogus.exitCode, 0) << bogus.err;
  EXPECT_EQ(bogus.err.rfind("impulse2d_sim: IMPULSE2D_SIMD=NEON_BF16 is not one of:", 0), 0u)
      << bogus.err;
  EXPECT_EQ(lines(bogus.out).back(), lines(best.out).back());
  ASSERT_EQ(portable.exitCode, 0) << portable.err;
  EXPECT_TRUE(portable.err.empty()) << portable.err;
  EXPECT_EQ(lines(portable.out).back(), lines(best.out).back());
}

TEST(SimCli, PyramidRunsForTenSimulatedSeconds) {
  const SimRun run = runSim({config("pyramid.yaml"), "--duration", "10", "--hash"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out.rfind("steps: 1000, simulated: 10 s,", 0), 0u) << run.out;
  EXPECT_NE(run.out.find("bodies: 211,"), std::string::npos) << run.out;
  EXPECT_TRUE(run.err.empty()) << run.err;  // no progress output when stderr is not a terminal
}

}  // namespace
}  // namespace impulse2d
