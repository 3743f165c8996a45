// The engine's limits, in one place: what one world, one body or one scene may hold. They bound
// the memory and time any single request can cost (the ROS node takes requests from anyone on
// its network), and they keep coordinates where doubles still resolve the solver's tolerances.
// README "Limits" documents them; World, the scene loader and the node refuse what exceeds them.
#pragma once

#include <cstddef>

namespace impulse2d {

/// Bodies alive in one world at a time.
constexpr std::size_t kMaxBodies = 65536;
/// Shapes over all bodies of one world (each costs a broad-phase proxy and about 600 bytes).
constexpr std::size_t kMaxShapes = 262144;
/// Shapes of one body.
constexpr std::size_t kMaxShapesPerBody = 64;
/// Vertices of one convex polygon (a Polygon stores them inline).
constexpr int kMaxPolygonVertices = 16;
/// Joints alive in one world at a time.
constexpr std::size_t kMaxJoints = 65536;
/// Threads one world steps on (WorldDef::threads).
constexpr int kMaxThreads = 256;
/// Characters of a body or joint name (they become tf frame names).
constexpr std::size_t kMaxNameLength = 256;
/// Bytes of scene text (YAML, or URDF), read from a file or received by a service.
constexpr std::size_t kMaxSceneBytes = 16u << 20;
/// Timed wrenches (the node's ~apply_wrench) pending at one time.
constexpr std::size_t kMaxPendingWrenches = 4096;
/// Devices (drives, lasers, bumpers) of one world; each costs the node a few ROS connections.
constexpr std::size_t kMaxDevices = 1024;
/// Cells of one occupancy map (a byte each while it loads; 8000 x 8000).
constexpr std::size_t kMaxMapCells = 64u << 20;
/// Beams of one laser (a ray cast each per scan).
constexpr int kMaxLaserBeams = 100000;
/// m. Bodies are created, and may be placed, only within this distance of the origin on each
/// axis: out to here doubles resolve better than a nanometre.
constexpr double kMaxCoordinate = 1e6;
/// m/s and rad/s: the fastest a body may be created or set moving. Far beyond anything physical;
/// it keeps products of speeds, masses and lever arms far from overflow.
constexpr double kMaxSpeed = 1e6;
/// N and N m: the largest force or torque one call may apply.
constexpr double kMaxForce = 1e12;
/// kg and kg m^2: the least mass and rotational inertia of a dynamic body; lighter shapes are
/// given these. With kMaxForce they keep every velocity change finite; the motion limits
/// (WorldDef::maxLinearSpeed, maxRotation) bound it.
constexpr double kMinMass = 1e-9;
constexpr double kMinInertia = 1e-20;
/// m. A body whose centre of mass leaves this box (on either axis), or whose state stops being
/// finite, is removed at the end of the step and reported by World::takeRemovedBodies(), instead
/// of being computed on as inf or NaN. With the motion limits, no valid edit reaches either.
constexpr double kWorldExtent = 1e7;

}  // namespace impulse2d
