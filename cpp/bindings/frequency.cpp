// Bindings of the frequency domain: the linear track's receptance and the periodic level's
// moving-load receptance matrix (the GIL released while the kernel computes).
#include "frequency.hpp"

#include <complex>

#include "common.hpp"
#include "periodic.hpp"

namespace trackwheel::bindings {

namespace {

py::object periodic_receptance(const PeriodicTrackParams& track, double speed, double omega, int n,
                               const std::vector<double>& offsets, double rtol, bool with_stats) {
  std::vector<Eigen::MatrixXcd> a;
  PeriodicStats st;
  {
    py::gil_scoped_release nogil;
    a = periodic_receptance_matrix(track, speed, omega, n, offsets, rtol, &st);
  }
  const py::ssize_t M = 2 * n + 1, no = static_cast<py::ssize_t>(a.size());
  py::array_t<std::complex<double>> out({no, M, M});
  auto r = out.mutable_unchecked<3>();
  for (py::ssize_t j = 0; j < no; ++j)
    for (py::ssize_t p = 0; p < M; ++p)
      for (py::ssize_t q = 0; q < M; ++q) r(j, p, q) = a[j](p, q);
  if (!with_stats) return out;
  py::dict d;
  d["points"] = st.points;
  d["poles"] = st.poles;
  d["rounds"] = st.rounds;
  d["den_evaluations"] = st.den_evaluations;
  return py::make_tuple(out, d);
}

}  // namespace

void bind_frequency(py::module_& m) {
  m.def(
      "receptance",
      [](const RailModel& rail, const BeamParams& beam, const std::vector<double>& x,
         const std::vector<double>& xr, const std::vector<double>& freqs) {
        py::gil_scoped_release nogil;
        return receptance(rail, beam, x, xr, freqs);
      },
      py::arg("rail"), py::arg("beam"), py::arg("x"), py::arg("x_response"), py::arg("freqs"),
      "Receptances (n_freq, n_force * n_resp) [m/N] of the linear track, a unit force at each "
      "of x (column e * n_resp + r: response r to force e)");
  py::class_<PeriodicTrackParams>(m, "PeriodicTrackParams")
      .def(py::init<>())
      .def_readwrite("bay", &PeriodicTrackParams::bay, "d, support spacing [m]")
      .def_readwrite("EI", &PeriodicTrackParams::EI, "bending stiffness [N m^2]")
      .def_readwrite("mass", &PeriodicTrackParams::mass, "rho A [kg/m]")
      .def_readwrite("shear", &PeriodicTrackParams::shear, "kappa G A [N]; 0: Euler-Bernoulli")
      .def_readwrite("rotary", &PeriodicTrackParams::rotary, "rho I [kg m]")
      .def_readwrite("pad_stiffness", &PeriodicTrackParams::pad_stiffness, "k_s or k_p [N/m]")
      .def_readwrite("pad_damping", &PeriodicTrackParams::pad_damping, "c_s or c_p [N s/m]")
      .def_readwrite("sleeper_mass", &PeriodicTrackParams::sleeper_mass, "m_s [kg]; 0: single")
      .def_readwrite("ballast_stiffness", &PeriodicTrackParams::ballast_stiffness, "k_b [N/m]")
      .def_readwrite("ballast_damping", &PeriodicTrackParams::ballast_damping, "c_b [N s/m]");
  m.def("periodic_receptance_matrix", &periodic_receptance, py::arg("track"), py::arg("speed"),
        py::arg("omega"), py::arg("n"), py::arg("offsets"), py::arg("rtol"),
        py::arg("stats") = false,
        "Moving-load receptance matrices (n_offsets, 2n+1, 2n+1) [m/N] of the periodic track; "
        "with stats=True also the work counts {points, poles, rounds, den_evaluations}");
}

}  // namespace trackwheel::bindings
