// The stored generic instance of the five-point problem that every new instance starts from,
// and how it was made. Internal to the synthesis library and its tests.
#pragma once

#include <cstdint>
#include <vector>

#include "nbar/synthesis/five_point.hpp"

namespace nbar::synthesis {

struct FivePointStart {
  CVector parameters;              // delta_0..4, deltab_0..4, alpha, alphab, beta, betab (generic complex)
  std::vector<CVector> solutions;  // affine isotropic: t1..t4, tb1..tb4, x, xb, y, yb
};

// The instance kept in five_point_start.cpp (written by the nbar-five-point-start program).
const FivePointStart& five_point_start();

// Random complex parameters fitted to a random solution, then monodromy until 36 solutions.
FivePointStart generate_five_point_start(std::uint64_t seed, const SolverOptions& options = {});

// The isotropic formulation (tracker coordinates with homogenized moving pivots).
const ParameterizedSystem& five_point_parameterized_system();

// A solution in affine isotropic coordinates (normalized frame) as the task's numbers.
FivePointSolution five_point_solution(const FivePointTask& task, const CVector& affine);

}  // namespace nbar::synthesis
