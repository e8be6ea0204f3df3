// The poles of the periodic track's moving-load integrand (periodic.hpp): the zeros of 1 + s S
// near the real k axis, the track's lightly damped Bloch waves, found from the local minima of
// |1 + s S| on a scan and from the free rail's poles by secant iterations, with the residue
// factors that the quadrature subtracts near them and adds back exactly.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "periodic_track.hpp"

namespace trackwheel::periodic {

struct Pole {
  cd k, rho;
  Eigen::VectorXcd h;
};

// The poles with real part in (edges.front(), edges.back()) and |imaginary part| below
// kPoleStrip half zones, sorted, without duplicates; evals counts the evaluations of 1 + s S.
std::vector<Pole> find_poles(const Line& line, const std::vector<double>& edges, long& evals);

}  // namespace trackwheel::periodic
