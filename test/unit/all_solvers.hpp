// Every SolverType, in one place: the property and determinism tests run once per entry, so a
// new solver is covered by adding one line here (and its pinned hash in test_determinism.cpp).
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
  static const std::vector<SolverCase> solvers = {
      {SolverType::Baumgarte, "baumgarte"},
      {SolverType::NonlinearGaussSeidel, "ngs"},
  };
  return solvers;
}

/// gtest parameter names: "baumgarte", "ngs".
struct SolverCaseName {
  template <class ParamInfo>
  std::string operator()(const ParamInfo& info) const {
    return info.param.name;
  }
};

}  // namespace test
}  // namespace impulse2d
