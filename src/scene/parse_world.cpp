// The `world:` settings of a scene, checked with World::validate(WorldDef).
#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

namespace impulse2d {
namespace scene_detail {

void parseWorld(const YAML::Node& node, Scene* scene) {
  const Fields f(node, "the world settings",
                 {"gravity",
                  "time_step",
                  "velocity_iterations",
                  "position_iterations",
                  "plane",
                  "frame_id",
                  "solver",
                  "threads",
                  "baumgarte",
                  "linear_slop",
                  "speculative_distance",
                  "restitution_threshold",
                  "max_push_velocity",
                  "warm_starting",
                  "enable_sleep",
                  "time_to_sleep",
                  "sleep_linear_tolerance",
                  "sleep_angular_tolerance",
                  "contact_hertz",
                  "contact_damping_ratio",
                  "joint_hertz",
                  "joint_damping_ratio",
                  "remove_lost_bodies",
                  "max_linear_speed",
                  "max_rotation"});
  WorldDef& w = scene->world;
  w.gravity = f.vec2("gravity", w.gravity);
  w.timeStep = f.number("time_step", w.timeStep);
  w.velocityIterations = f.integer("velocity_iterations", w.velocityIterations);
  w.positionIterations = f.integer("position_iterations", w.positionIterations);
  if (f.has("solver")) {
    const std::string solver = f.string("solver", "");
    if (!solverFromName(solver, &w.solver)) {
      throw SceneError("solver", "must be " + solverNameList() + ", not " + quoted(solver));
    }
  }
  w.threads = f.integer("threads", w.threads);
  w.baumgarte = f.number("baumgarte", w.baumgarte);
  w.linearSlop = f.number("linear_slop", w.linearSlop);
  w.speculativeDistance = f.number("speculative_distance", w.speculativeDistance);
  w.restitutionThreshold = f.number("restitution_threshold", w.restitutionThreshold);
  w.maxPushVelocity = f.number("max_push_velocity", w.maxPushVelocity);
  w.maxLinearSpeed = f.number("max_linear_speed", w.maxLinearSpeed);
  w.maxRotation = f.number("max_rotation", w.maxRotation);
  w.warmStarting = f.boolean("warm_starting", w.warmStarting);
  w.enableSleep = f.boolean("enable_sleep", w.enableSleep);
  w.timeToSleep = f.number("time_to_sleep", w.timeToSleep);
  w.sleepLinearTolerance = f.number("sleep_linear_tolerance", w.sleepLinearTolerance);
  w.sleepAngularTolerance = f.number("sleep_angular_tolerance", w.sleepAngularTolerance);
  w.contactHertz = f.number("contact_hertz", w.contactHertz);
  w.contactDampingRatio = f.number("contact_damping_ratio", w.contactDampingRatio);
  w.jointHertz = f.number("joint_hertz", w.jointHertz);
  w.jointDampingRatio = f.number("joint_damping_ratio", w.jointDampingRatio);
  w.removeLostBodies = f.boolean("remove_lost_bodies", w.removeLostBodies);
  scene->plane = f.string("plane", scene->plane);
  if (scene->plane != "xz" && scene->plane != "xy") {
    throw SceneError("plane",
                     "must be xz (vertical) or xy (top-down), not " + quoted(scene->plane));
  }
  if (f.has("frame_id")) scene->frameId = f.name("frame_id");
  const std::string why = World::validate(w);
  if (!why.empty()) throw SceneError("", why);
}

}  // namespace scene_detail
}  // namespace impulse2d
