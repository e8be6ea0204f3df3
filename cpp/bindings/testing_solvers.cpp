// Test-only probes of the solvers and benchmark hooks, in the submodule _core.testing (not
// public API): the full path's generalized-alpha step at any iterate (its residual, iteration
// matrix and Newton correction), the band and bordered solvers, the rolling constraint's
// kinematics, the track at rest, the linear track's modes, the periodic lattice sum and the
// timing of a band factorisation.
#include <optional>
#include <stdexcept>
#include <string>

#include "bench.hpp"
#include "common.hpp"
#include "frequency.hpp"
#include "generalized_alpha.hpp"
#include "periodic.hpp"
#include "rolling.hpp"

namespace trackwheel::bindings {

namespace {

// A dense square as a band matrix of half bandwidth b (entries outside the band ignored).
BandMatrix band_of(const Eigen::MatrixXd& A, int b) {
  if (A.rows() != A.cols()) throw std::invalid_argument("A must be square");
  if (b < 0) throw std::invalid_argument("half_bandwidth must be >= 0");
  const int n = static_cast<int>(A.rows());
  BandMatrix M(n, b);
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - b); i <= std::min(n - 1, j + b); ++i) M.at(i, j) = A(i, j);
  return M;
}

// The generalized-alpha step from the consistent start of `init` to t1 at the iterate x (see
// the docstring).
py::dict ga_probe(const RailModel& rail, const std::vector<WheelParams>& wheels,
                  const ContactParams& c, const SimSettings& s, const SimState& init, double t1,
                  std::optional<Eigen::VectorXd> x, const VehicleParams& vehicle) {
  const Model model = make_model(rail, wheels, c, vehicle);
  check_settings(s);
  check_model(model);
  check_coordinates(rail, init.e, "initial.e");
  if (static_cast<int>(init.wheels.size()) != model.n_wheels())
    throw std::invalid_argument("initial needs one WheelState per wheel");
  if (init.body.size() != 2 * model.n_bodies() || init.bodydot.size() != init.body.size())
    throw std::invalid_argument("initial needs (z, phi) per vehicle body");
  System sys(model, s);
  SimState st = init;
  if (!sys.sleepers().empty() && st.z.size() == 0) {  // at rest under the given rail
    st.z = sys.sleepers().static_z(st.e);
    st.zdot = Eigen::VectorXd::Zero(st.z.size());
  }
  Eval ev;
  Accel acc;
  sys.evaluate(0.0, st, true, ev);
  for (int w = 0; w < sys.n_wheels(); ++w) st.wheels[w].s = ev.w[w].pt.s;
  sys.accelerations(st, ev, acc);
  SimOutput out;
  const Divergence div(s, [] { return std::string("probe"); });
  GeneralizedAlpha ga(sys, st, ev, acc, out, div);
  const int nf = sys.n_free(), m = sys.n_border(), ns = sys.sleepers().size();
  Eigen::VectorXd start(nf + m + ns);
  start << rail.to_free(acc.edd), acc.x, acc.zdd;
  Accel it = acc;
  if (x) {
    if (x->size() != nf + m + ns)
      throw std::invalid_argument("x must have n_free + 3 n_wheels + 2 n_bodies + n_sleepers = " +
                                  std::to_string(nf + m + ns) + " entries");
    it.edd = Eigen::VectorXd::Zero(rail.n_dof());
    rail.add_from_free(x->head(nf), it.edd);
    it.x = x->segment(nf, m);
    it.zdd = x->tail(ns);
  }
  Eigen::VectorXd minus_r, dx;
  Eigen::MatrixXd J;
  ga.probe(t1, it, minus_r, J, dx);
  py::dict d;
  d["start"] = start;
  d["residual"] = minus_r;
  d["matrix"] = J;
  d["solution"] = dx;
  return d;
}

// The full path's step, the band and bordered solvers, the rolling constraint.
void bind_solver_probes(py::module_& t) {
  t.def("ga_probe", &ga_probe, py::arg("rail"), py::arg("wheels"), py::arg("contact"),
        py::arg("settings"), py::arg("initial"), py::arg("t1"), py::arg("x") = py::none(),
        py::arg("vehicle") = VehicleParams(),
        "Test hook: the generalized-alpha step from the consistent start of `initial` to t1 [s] "
        "at the iterate x = [e''_free, (Y'', theta'', lambda) per wheel, (z'', phi'') per body, "
        "z'' per sleeper] (None: the start accelerations). Returns {'start': the start "
        "accelerations in that layout, 'residual': -r, 'matrix': the iteration matrix dr/dx "
        "(assembled, dense, the sleepers uncondensed), 'solution': the kernel's Newton correction "
        "(the sleepers condensed)}");
  t.def(
      "band_solve",
      [](const Eigen::MatrixXd& A, int half_bandwidth, const Eigen::VectorXd& r) {
        BandMatrix M = band_of(A, half_bandwidth);
        if (r.size() != M.size()) throw std::invalid_argument("r must match A");
        if (!M.factorize()) throw std::runtime_error("band matrix is singular");
        Eigen::VectorXd x = r;
        M.solve_in_place(x);
        return x;
      },
      py::arg("A"), py::arg("half_bandwidth"), py::arg("r"),
      "Test hook: solve A x = r by the band LU (no pivoting) of A's band");
  t.def(
      "bordered_solve",
      [](const Eigen::MatrixXd& A, int half_bandwidth, const Eigen::MatrixXd& B,
         const Eigen::MatrixXd& C, const Eigen::MatrixXd& D, const Eigen::VectorXd& r1,
         const Eigen::VectorXd& r2) {
        BandMatrix M = band_of(A, half_bandwidth);
        const int n = M.size(), k = static_cast<int>(D.rows());
        if (B.rows() != n || B.cols() != k || C.rows() != k || C.cols() != n || D.cols() != k ||
            r1.size() != n || r2.size() != k)
          throw std::invalid_argument("bordered_solve: inconsistent shapes");
        BorderedSolver solver;
        if (!solver.factorize(M, B, C, D)) throw std::runtime_error("bordered matrix is singular");
        Eigen::VectorXd x1, x2;
        solver.solve(r1, r2, x1, x2);
        return py::make_tuple(x1, x2);
      },
      py::arg("A"), py::arg("half_bandwidth"), py::arg("B"), py::arg("C"), py::arg("D"),
      py::arg("r1"), py::arg("r2"),
      "Test hook: solve [A B; C D] [x1; x2] = [r1; r2] with the bordered band solver");
  t.def(
      "split_bordered_solve",
      [](const Eigen::MatrixXd& A, int half_bandwidth, const py::list& cases) {
        BandMatrix M = band_of(A, half_bandwidth);
        const int n = M.size();
        if (!M.factorize()) throw std::runtime_error("band matrix is singular");
        SplitBorderedSolver solver;
        py::list out;
        bool first = true;
        for (const py::handle& h : cases) {
          const auto c = h.cast<py::tuple>();
          if (c.size() != 7) throw std::invalid_argument("a case is (idx, E, F, G, D, r1, r2)");
          const auto idx =
              c[0].cast<Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>();
          const auto E = c[1].cast<Eigen::MatrixXd>(), F = c[2].cast<Eigen::MatrixXd>(),
                     G = c[3].cast<Eigen::MatrixXd>(), D = c[4].cast<Eigen::MatrixXd>();
          const auto r1 = c[5].cast<Eigen::VectorXd>(), r2 = c[6].cast<Eigen::VectorXd>();
          const int ng = static_cast<int>(idx.rows()), gs = static_cast<int>(idx.cols());
          const int r = ng * gs, m = static_cast<int>(D.rows());
          if (E.rows() != r || E.cols() != r || F.rows() != r || F.cols() != m || G.rows() != m ||
              G.cols() != r || D.cols() != m || r1.size() != n || r2.size() != m ||
              (idx.array() >= n).any() || (idx.array() < -1).any())
            throw std::invalid_argument("split_bordered_solve: inconsistent shapes");
          if (first) {
            solver.resize(n, ng, gs, m);
            solver.set_band(M);
            first = false;
          }
          for (int g = 0; g < ng; ++g) solver.set_group(g, idx.row(g).data());
          if (!solver.factorize(E, F, G, D))
            throw std::runtime_error("bordered matrix is singular");
          Eigen::VectorXd x1, x2;
          solver.solve(r1, r2, x1, x2);
          out.append(py::make_tuple(x1, x2, solver.band_solves()));
        }
        return out;
      },
      py::arg("A"), py::arg("half_bandwidth"), py::arg("cases"),
      "Test hook: solve [A + P E P^T, P F; G P^T, D] [x1; x2] = [r1; r2] with the split "
      "bordered solver, A's band factorised once, for each case (idx, E, F, G, D, r1, r2) in "
      "turn with one solver (idx: n_groups x group_size band indices, -1 none; the first case "
      "fixes the shapes). Returns [(x1, x2, band solves so far)]");
  t.def(
      "rolling_eval",
      [](const RailModel& rail, const Eigen::VectorXd& e, double xa, double ya, double s_guess,
         const Vec10& qdot, double thetadot) {
        check_coordinates(rail, e, "e");
        const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(xa, ya), s_guess);
        Vec10 grad;
        distance_derivatives(pt, grad, nullptr);
        const RollingKinematics k = rolling_kinematics(pt, grad, qdot, thetadot, true);
        py::dict d;
        d["g"] = k.g;
        d["b"] = Vec11(k.b);
        d["dg_dq"] = Vec10(k.dg_dq);
        d["db_dq"] = Mat11x10(k.db_dq);
        d["ds_dq"] = Vec10(k.ds_dq);
        d["s"] = pt.s;
        d["s_dot"] = k.s_dot;
        return d;
      },
      "Rolling-constraint kinematics for q = [X_A, Y_A, e_el], qdot = [V_A, edot_el]");
}

// The track at rest, the linear track's modes, the periodic lattice sum, a benchmark's timing.
void bind_track_probes(py::module_& t) {
  t.def(
      "track_static",
      [](const RailModel& rail) {
        StaticResult r;
        {
          py::gil_scoped_release nogil;
          r = solve_track_static(rail);
        }
        return static_to_dict(r);
      },
      "Static track under its own weight, no wheel: {'e', 'sleeper_z', 'ballast_force', ...}");
  t.def(
      "track_modes",
      [](const RailModel& rail, const BeamParams& beam, double M, double k,
         const std::vector<double>& x, int n_modes) {
        std::vector<Eigen::MatrixXd> shapes;
        Eigen::MatrixXd f;
        {
          py::gil_scoped_release nogil;
          f = track_modes(rail, beam, M, k, x, n_modes, &shapes);
        }
        return py::make_tuple(f, shapes);
      },
      py::arg("rail"), py::arg("beam"), py::arg("wheel_mass"), py::arg("contact_stiffness"),
      py::arg("positions"), py::arg("n_modes"),
      "Linear-track modes: (frequencies (n_pos, n_modes) [Hz], shapes per position (ny + 1, "
      "n_modes) over the y coordinates then the wheel)");
  t.def("periodic_lattice_sum", &periodic_lattice_sum, py::arg("track"), py::arg("k"), py::arg("w"),
        "The lattice sum S(k, w) [m/N] of the periodic track");
  t.def("time_band_factor_solve", &time_band_factor_solve, py::arg("rail"), py::arg("cq"),
        py::arg("cv"), py::arg("repeats"), py::arg("bordered") = false,
        "Mean wall time [s] of one factorisation + solve of M + cv C_s + cq K_t (benchmarks)");
}

}  // namespace

void bind_testing_solvers(py::module_& t) {
  bind_solver_probes(t);
  bind_track_probes(t);
}

}  // namespace trackwheel::bindings
