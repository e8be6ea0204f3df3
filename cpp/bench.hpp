// Timing helpers for the benchmarks (benchmarks/work_precision.py): the cost of the kernel's
// elementary linear-algebra operations, measured in C++ so that no Python overhead enters.
#pragma once

#include "rail.hpp"

namespace trackwheel {

// Wall time [s] of one factorisation + one solve of the generalized-alpha iteration matrix of
// the rail, M + cv C_s + cq K_t(e_ref) over the free coordinates (band LU, half bandwidth 7),
// averaged over `repeats` factorise + solve cycles (each on a fresh copy of the assembled
// matrix; the copy is included, the assembly is not). With `bordered`, the three border
// rows/columns of the wheel (Y_A, theta, lambda) are added as in the time loop and the bordered
// Schur solver is timed instead. cq = beta' h^2 [s^2], cv = gamma' h [s].
double time_band_factor_solve(const RailModel& rail, double cq, double cv, int repeats,
                              bool bordered = false);

}  // namespace trackwheel
