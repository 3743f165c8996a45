// What the world node publishes: tf and tf_static on the x-z plane, ~contacts, ~markers,
// /clock and /diagnostics.
#include "world_test_util.hpp"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <impulse2d/ContactArray.h>
#include <impulse2d/Step.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <map>

namespace impulse2d_test {
namespace {

bool hasContact(const impulse2d::ContactArray& msg, const std::string& a, const std::string& b) {
  for (const impulse2d::Contact& c : msg.contacts) {
    if ((c.body_a == a && c.body_b == b) || (c.body_a == b && c.body_b == a)) return true;
  }
  return false;
}

const visualization_msgs::Marker* findMarker(const visualization_msgs::MarkerArray& msg,
                                             const std::string& ns, const std::string& text = "") {
  for (const visualization_msgs::Marker& m : msg.markers) {
    if (m.ns == ns && (text.empty() || m.text == text)) return &m;
  }
  return nullptr;
}

TEST(Topics, SpawnedBodyAppearsOnTfAndFalls) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(spawn(boxBody("tf_faller", 6.0, 12.0)));
  geometry_msgs::TransformStamped first;
  try {
    first = buffer.lookupTransform("world", "tf_faller", ros::Time(0), ros::Duration(5.0));
  } catch (const tf2::TransformException& e) {
    FAIL() << e.what();
  }
  // The x-z plane: 2D (x, y) is 3D (x, 0, y).
  EXPECT_NEAR(first.transform.translation.x, 6.0, 1e-3);
  EXPECT_EQ(first.transform.translation.y, 0.0);
  EXPECT_LE(first.transform.translation.z, 12.0);
  EXPECT_TRUE(waitFor(
      [&] {
        try {
          const auto now = buffer.lookupTransform("world", "tf_faller", ros::Time(0));
          return now.transform.translation.z < first.transform.translation.z - 0.5;
        } catch (const tf2::TransformException&) {
          return false;
        }
      },
      5.0));
  EXPECT_TRUE(remove("tf_faller"));
}

TEST(Topics, StaticBodyIsOnTfStaticWithThePlaneRotation) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  impulse2d::Body shelf = boxBody("tf_shelf", 3.0, 7.0, 2.0, 0.2, impulse2d::Body::STATIC);
  shelf.pose.theta = 0.5;
  ASSERT_TRUE(spawn(shelf));
  geometry_msgs::TransformStamped t;
  try {
    t = buffer.lookupTransform("world", "tf_shelf", ros::Time(0), ros::Duration(5.0));
  } catch (const tf2::TransformException& e) {
    FAIL() << e.what();
  }
  EXPECT_NEAR(t.transform.translation.x, 3.0, 1e-12);
  EXPECT_NEAR(t.transform.translation.y, 0.0, 1e-12);
  EXPECT_NEAR(t.transform.translation.z, 7.0, 1e-12);
  // theta about -y: counter-clockwise in the plane seen from -y.
  EXPECT_NEAR(t.transform.rotation.w, std::cos(0.25), 1e-12);
  EXPECT_NEAR(t.transform.rotation.y, -std::sin(0.25), 1e-12);
  EXPECT_NEAR(t.transform.rotation.x, 0.0, 1e-12);
  EXPECT_NEAR(t.transform.rotation.z, 0.0, 1e-12);
  EXPECT_TRUE(remove("tf_shelf"));
}

TEST(Topics, RestingBodyShowsInContactsAndMarkers) {
  Latest<impulse2d::ContactArray> contacts(worldNs() + "/contacts");
  Latest<visualization_msgs::MarkerArray> markers(worldNs() + "/markers");
  ASSERT_TRUE(spawn(boxBody("rest_box", -1.0, 0.5)));  // on the ground, whose top is y = 0
  EXPECT_TRUE(waitFor(
      [&] {
        auto msg = contacts.get();
        return msg && hasContact(*msg, "ground", "rest_box");
      },
      10.0));
  auto contact = contacts.get();
  ASSERT_TRUE(contact);
  EXPECT_EQ(contact->header.frame_id, "world");
  for (const impulse2d::Contact& c : contact->contacts) {
    if (c.body_b != "rest_box") continue;
    EXPECT_NEAR(c.normal.y, 1.0, 1e-3);  // from the ground up to the box
    EXPECT_GT(c.normal_impulse, 0.0);
    EXPECT_EQ(c.point.z, 0.0);
  }

  EXPECT_TRUE(waitFor(
      [&] {
        auto msg = markers.get();
        if (!msg) return false;
        const auto* points = findMarker(*msg, "contact_points");
        return findMarker(*msg, "names", "rest_box") && points && !points->points.empty();
      },
      10.0));
  auto marker = markers.get();
  ASSERT_TRUE(marker);
  ASSERT_FALSE(marker->markers.empty());
  EXPECT_EQ(marker->markers[0].action, visualization_msgs::Marker::DELETEALL);
  EXPECT_TRUE(findMarker(*marker, "bodies"));
  EXPECT_TRUE(findMarker(*marker, "contact_normals"));

  // Deleted, it vanishes from both.
  ASSERT_TRUE(remove("rest_box"));
  EXPECT_TRUE(waitFor(
      [&] {
        auto c = contacts.get();
        auto m = markers.get();
        return c && m && !hasContact(*c, "ground", "rest_box") &&
               !findMarker(*m, "names", "rest_box");
      },
      10.0));
}

TEST(Topics, ClockFollowsSimulatedTime) {
  Latest<rosgraph_msgs::Clock> clock("/clock");
  if (!expectClock()) {
    // Give a publisher time to show up; there must be none.
    ros::WallDuration(1.0).sleep();
    EXPECT_EQ(clock.count(), 0);
    return;
  }
  ASSERT_TRUE(waitFor([&] { return clock.count() >= 2; }, 5.0));
  PausedWorld paused;
  // Let a clock message from a step before the pause arrive, then read the paused time.
  ros::WallDuration(0.2).sleep();
  const ros::Time before = clock.get()->clock;
  impulse2d::Step step;
  step.request.steps = 7;
  ASSERT_TRUE(call("step", step));
  ASSERT_TRUE(step.response.success);
  const ros::Time expected = before + ros::Duration(7 * kTimeStep);
  EXPECT_TRUE(waitFor([&] { return clock.get()->clock == expected; }, 5.0))
      << "clock " << clock.get()->clock << ", expected " << expected;
}

TEST(Topics, DiagnosticsReportTheRealTimeFactor) {
  Latest<diagnostic_msgs::DiagnosticArray> diagnostics("/diagnostics");
  auto reported = [&] {
    auto msg = diagnostics.get();
    if (!msg) return false;
    for (const auto& status : msg->status) {
      for (const auto& kv : status.values) {
        if (kv.key == "real-time factor") return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(waitFor(reported, 5.0));
}

// The stage times of impulse2d_sim --profile, means over the window: every stage listed, none
// negative, together no more than the step, and the step timed.
TEST(Topics, DiagnosticsReportTheStageTimes) {
  Latest<diagnostic_msgs::DiagnosticArray> diagnostics("/diagnostics");
  std::map<std::string, double> stages;
  auto reported = [&] {
    auto msg = diagnostics.get();
    if (!msg) return false;
    stages.clear();
    for (const auto& status : msg->status) {
      for (const auto& kv : status.values) {
        if (kv.key.rfind("stage ms: ", 0) == 0) stages[kv.key.substr(10)] = std::stod(kv.value);
      }
    }
    return stages.count("step") && stages["step"] > 0.0;
  };
  ASSERT_TRUE(waitFor(reported, 5.0));
  double sum = 0.0;
  for (const char* name :
       {"broad phase", "narrow phase", "colouring", "prepare", "warm start", "solve", "relax",
        "restitution", "positions", "integrate", "continuous", "sleep"}) {
    ASSERT_TRUE(stages.count(name)) << name;
    EXPECT_GE(stages[name], 0.0) << name;
    sum += stages[name];
  }
  EXPECT_LE(sum, stages["step"] * 1.001 + 1e-6);
  EXPECT_GT(stages["solve"], 0.0);
}

}  // namespace
}  // namespace impulse2d_test
