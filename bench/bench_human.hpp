// Box2D v3.1.1's ragdoll (shared/human.c) as scene bodies and joints, for the rain scene.
#pragma once

#include "bench_scene.hpp"

namespace impulse2d_bench {

/// Adds the eleven bones of one human standing at `position` (its feet), scale 1, as human.c's
/// CreateHuman with rain's joint friction 0.05, spring 5 Hz and damping ratio 0.5. Its bodies
/// belong to event group `group`; `groupIndex` > 0 keeps its bones from touching each other (and
/// from touching other humans of the same index, as in v3).
void addHuman(SceneSpec& scene, int group, const Vec2& position, int groupIndex);

}  // namespace impulse2d_bench
