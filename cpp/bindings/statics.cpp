// Bindings of the statics: the static equilibrium of the rail with its wheels, of the rail alone,
// and the quasi-static line (the GIL released while the kernel solves).
#include "statics.hpp"

#include "common.hpp"

namespace trackwheel::bindings {

namespace {

py::dict static_solve(const RailModel& rail, const WheelParams& w, const ContactParams& c,
                      double x) {
  StaticResult r;
  {
    py::gil_scoped_release nogil;
    r = solve_static(rail, w, c, x);
  }
  return static_to_dict(r);
}

py::list static_solve_wheels(const RailModel& rail, const std::vector<WheelParams>& w,
                             const std::vector<ContactParams>& c, const std::vector<double>& x) {
  std::vector<StaticResult> rs;
  {
    py::gil_scoped_release nogil;
    rs = solve_static_wheels(rail, w, c, x);
  }
  py::list out;
  for (const StaticResult& r : rs) out.append(static_to_dict(r));
  return out;
}

py::dict quasi_static(const RailModel& rail, const WheelParams& w, const ContactParams& c,
                      const std::vector<double>& x) {
  std::vector<StaticResult> rs;
  {
    py::gil_scoped_release nogil;
    rs = solve_quasi_static(rail, w, c, x);
  }
  const size_t n = rs.size();
  Eigen::VectorXd yc(n), yw(n), sc(n), N(n), H(n);
  for (size_t i = 0; i < n; ++i) {
    yc(i) = rs[i].y_contact;
    yw(i) = rs[i].y_wheel;
    sc(i) = rs[i].contact_s;
    N(i) = rs[i].normal_force;
    H(i) = rs[i].horizontal_reaction;
  }
  py::dict d;
  d["y_contact"] = yc;
  d["y_wheel"] = yw;
  d["contact_s"] = sc;
  d["normal_force"] = N;
  d["horizontal_reaction"] = H;
  return d;
}

}  // namespace

void bind_statics(py::module_& m) {
  m.def("static_solve", &static_solve, py::arg("rail"), py::arg("wheel"), py::arg("contact"),
        py::arg("x_wheel"),
        "Static equilibrium of the wheel at X_A = x_wheel [m] on the rail under its load F + M g: "
        "{'e' (n_dof,), 'x_wheel', 'y_wheel', 'contact_s' [m], 'y_contact' [m] (the rail under "
        "the load), 'normal_force', 'horizontal_reaction' [N], 'iterations', 'sleeper_z' [m], "
        "'ballast_force' [N]}");
  m.def("static_solve_wheels", &static_solve_wheels, py::arg("rail"), py::arg("wheels"),
        py::arg("contacts"), py::arg("x_wheels"),
        "Static equilibrium of several wheels on the rail, wheel w at x_wheels[w] under its load "
        "F + M g: one static_solve dict per wheel (the same rail e in each)");
  m.def(
      "rail_static",
      [](const RailModel& rail) {
        py::gil_scoped_release nogil;
        return solve_rail_static(rail);
      },
      py::arg("rail"), "The rail's coordinates e (n_dof,) at rest under its own weight, no wheel");
  m.def("quasi_static", &quasi_static, py::arg("rail"), py::arg("wheel"), py::arg("contact"),
        py::arg("x"),
        "The quasi-static line: a static solve at each X_A in x [m], each from the rail of the "
        "one before; {'y_contact', 'y_wheel', 'contact_s' [m], 'normal_force', "
        "'horizontal_reaction' [N]} (n,) each");
}

}  // namespace trackwheel::bindings
