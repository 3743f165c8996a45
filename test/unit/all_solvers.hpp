// Every SolverType (impulse2d::kAllSolvers, the one list) as gtest parameters: the property and
// determinism tests run once per entry; a new solver also needs its pinned hash in
// test_determinism.cpp.
#pragma once

#include <impulse2d/defs.hpp>

#include <string>
#include <vector>

namespace impulse2d {
namespace test {

struct SolverCase {
  SolverType type;
  const char* name;  ///< the scene's `solver:` value and the CLI's --solver
};

inline const std::vector<SolverCase>& allSolvers() {
  static const std::vector<SolverCase> solvers = [] {
    std::vector<SolverCase> all;
    for (SolverType s : kAllSolvers) all.push_back({s, solverName(s)});
    return all;
  }();
  return solvers;
}

/// gtest parameter names: the solvers' names.
struct SolverCaseName {
  template <class ParamInfo>
  std::string operator()(const ParamInfo& info) const {
    return info.param.name;
  }
};

}  // namespace test
}  // namespace impulse2d
