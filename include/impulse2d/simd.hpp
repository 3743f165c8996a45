// Which instruction set the sub-stepping solvers' SIMD kernels run on. Every one gives
// bit-identical results; by default the kernels run on the widest this processor has (8 doubles
// a register with AVX-512, 4 with AVX2, 2 with SSE4). A program picks another at start-up, before
// it steps a world; impulse2d_sim, impulse2d_bench and the node and nodelet call
// useSimdTargetFromEnvironment(), so IMPULSE2D_SIMD=AVX2 (say) chooses for them.
#pragma once

#include <string>
#include <vector>

namespace impulse2d {

/// The instruction sets this processor can run the kernels on, best first ("AVX3", "AVX2",
/// "SSE4", ...; last Highway's portable one, "SCALAR" or "EMU128" by its version).
std::vector<std::string> simdTargets();
/// The one they run on now.
std::string simdTarget();
/// Runs the kernels on `name` (one of simdTargets()), or on the best again for "". A name not
/// listed changes nothing and returns false.
bool useSimdTarget(const std::string& name);
/// useSimdTarget(IMPULSE2D_SIMD) when that variable is set and not empty. Returns "" when it was
/// unset, empty or used; otherwise a message naming the variable, its value and the choices (the
/// kernels stay where they were).
std::string useSimdTargetFromEnvironment();

}  // namespace impulse2d
