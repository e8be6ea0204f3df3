// The only file with Python headers: a list of bindings to the kernel.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "ancf_cable.hpp"
#include "contact.hpp"
#include "eigen_analysis.hpp"
#include "rail.hpp"
#include "statics.hpp"
#include "wheel.hpp"

namespace py = pybind11;
using namespace trackwheel;

namespace {

py::dict static_to_dict(const StaticResult& r) {
  py::dict d;
  d["e"] = r.e;
  d["x_wheel"] = r.x_wheel;
  d["y_wheel"] = r.y_wheel;
  d["contact_s"] = r.contact_s;
  d["y_contact"] = r.y_contact;
  d["normal_force"] = r.normal_force;
  d["horizontal_reaction"] = r.horizontal_reaction;
  d["iterations"] = r.iterations;
  return d;
}

py::tuple modal_to_tuple(const ModalResult& r) {
  const py::ssize_t np = static_cast<py::ssize_t>(r.shapes.size());
  const py::ssize_t nd = np ? r.shapes[0].rows() : 0, nm = np ? r.shapes[0].cols() : 0;
  py::array_t<double> shapes({np, nd, nm});
  auto s = shapes.mutable_unchecked<3>();
  for (py::ssize_t p = 0; p < np; ++p)
    for (py::ssize_t i = 0; i < nd; ++i)
      for (py::ssize_t k = 0; k < nm; ++k) s(p, i, k) = r.shapes[p](i, k);
  return py::make_tuple(r.frequencies, shapes);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "trackwheel C++ kernel (ANCF rail, supports, contact, statics, eigen analysis)";

  py::class_<CableSection>(m, "CableSection")
      .def(py::init<>())
      .def_readwrite("length", &CableSection::length, "element length l [m]")
      .def_readwrite("EA", &CableSection::EA, "axial stiffness [N]")
      .def_readwrite("EI", &CableSection::EI, "bending stiffness [N m^2]")
      .def_readwrite("rhoA", &CableSection::rhoA, "mass per length [kg/m]")
      .def_readwrite("exact_curvature", &CableSection::exact_curvature)
      .def_readwrite("n_gauss", &CableSection::n_gauss);
  m.def("cable_mass", &cable_mass, "Element mass matrix (8x8) [kg]");
  m.def("cable_elastic", [](const CableSection& c, const Vec8& e) {
    Vec8 Q; Mat8 K; double U;
    cable_elastic(c, e, &Q, &K, &U);
    return py::make_tuple(Q, K, U);
  }, "Elastic force Q [N], Jacobian K = dQ/de [N/m], strain energy U [J]");
  m.def("cable_axial", [](const CableSection& c, const Vec8& e) {
    Vec8 Q; Mat8 K; double U;
    cable_axial(c, e, &Q, &K, &U);
    return py::make_tuple(Q, K, U);
  });
  m.def("cable_bending", [](const CableSection& c, const Vec8& e) {
    Vec8 Q; Mat8 K; double U;
    cable_bending(c, e, &Q, &K, &U);
    return py::make_tuple(Q, K, U);
  });
  m.def("gauss_points", [](int n) {
    Eigen::VectorXd xi(n), w(n);
    gauss_points(n, xi.data(), w.data());
    return py::make_tuple(xi, w);
  });
  m.def("hermite", [](double xi, double l) {
    const HermiteValues h = hermite(xi, l);
    return py::make_tuple(Eigen::Vector4d(h.n), Eigen::Vector4d(h.ns), Eigen::Vector4d(h.nss));
  });

  py::class_<RailParams>(m, "RailParams")
      .def(py::init<>())
      .def_readwrite("length", &RailParams::length)
      .def_readwrite("EA", &RailParams::EA)
      .def_readwrite("EI", &RailParams::EI)
      .def_readwrite("rhoA", &RailParams::rhoA)
      .def_readwrite("n_elements", &RailParams::n_elements)
      .def_readwrite("exact_curvature", &RailParams::exact_curvature)
      .def_readwrite("n_gauss", &RailParams::n_gauss)
      .def_readwrite("gravity", &RailParams::gravity)
      .def_readwrite("pin_far_end", &RailParams::pin_far_end);
  py::class_<SupportParams>(m, "SupportParams")
      .def(py::init<>())
      .def_readwrite("position", &SupportParams::position)
      .def_readwrite("stiffness", &SupportParams::stiffness)
      .def_readwrite("damping", &SupportParams::damping);
  py::class_<WheelParams>(m, "WheelParams")
      .def(py::init<>())
      .def_readwrite("mass", &WheelParams::mass)
      .def_readwrite("inertia", &WheelParams::inertia)
      .def_readwrite("radius", &WheelParams::radius)
      .def_readwrite("load", &WheelParams::load)
      .def_readwrite("torque", &WheelParams::torque)
      .def_readwrite("gravity", &WheelParams::gravity);
  py::enum_<ContactLaw>(m, "ContactLaw")
      .value("linear", ContactLaw::Linear)
      .value("hertz", ContactLaw::Hertz);
  py::class_<ContactParams>(m, "ContactParams")
      .def(py::init<>())
      .def_readwrite("law", &ContactParams::law)
      .def_readwrite("stiffness", &ContactParams::stiffness)
      .def_readwrite("damping", &ContactParams::damping)
      .def_readwrite("radius", &ContactParams::radius);

  py::class_<RailModel>(m, "RailModel")
      .def(py::init<const RailParams&, const SupportParams&>())
      .def_property_readonly("n_dof", &RailModel::n_dof)
      .def_property_readonly("n_free", &RailModel::n_free)
      .def_property_readonly("n_nodes", &RailModel::n_nodes)
      .def_property_readonly("element_length", &RailModel::element_length)
      .def_property_readonly("free_to_full", &RailModel::free_to_full)
      .def_property_readonly("total_mass", &RailModel::total_mass)
      .def("reference", &RailModel::reference)
      .def("mass_dense", &RailModel::mass_dense)
      .def("mass_band_dense", [](const RailModel& r) { return r.mass().dense(); })
      .def("tangent_dense", &RailModel::tangent_dense)
      .def("gravity_force", &RailModel::gravity_force)
      .def("internal_force", [](const RailModel& r, const Eigen::VectorXd& e) {
        Eigen::VectorXd Q; double U;
        r.internal_force(e, nullptr, Q, &U);
        return py::make_tuple(Q, U);
      })
      .def("positions", [](const RailModel& r, const Eigen::VectorXd& e,
                           const std::vector<double>& s) {
        Eigen::MatrixXd out(s.size(), 2);
        for (size_t i = 0; i < s.size(); ++i) out.row(i) = r.position(e, r.locate(s[i]));
        return out;
      }, "Rail points r(s) (n, 2) [m] for material coordinates s [m]");

  m.def("contact_eval", [](const RailModel& rail, const Eigen::VectorXd& e, double xa, double ya,
                           double s_guess, const ContactParams& cp, const Vec10& qdot) {
    const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(xa, ya), s_guess);
    const ContactForce cf = contact_force(cp, pt, qdot, true);
    py::dict d;
    d["s"] = pt.s; d["element"] = pt.mp.element; d["rho"] = pt.rho; d["phi"] = pt.phi;
    d["normal"] = Eigen::Vector2d(pt.n); d["tangent"] = Eigen::Vector2d(pt.t);
    d["y_contact"] = pt.r.y();
    d["N"] = cf.N; d["active"] = cf.active; d["F"] = cf.F; d["K"] = cf.K; d["C"] = cf.C;
    d["grad_rho"] = cf.grad_rho;
    return d;
  }, "Contact point and force for q = [X_A, Y_A, e_el]");

  m.def("static_solve", [](const RailModel& rail, const WheelParams& w, const ContactParams& c,
                           double x) {
    StaticResult r;
    { py::gil_scoped_release nogil; r = solve_static(rail, w, c, x); }
    return static_to_dict(r);
  });
  m.def("rail_static", [](const RailModel& rail) {
    py::gil_scoped_release nogil;
    return solve_rail_static(rail);
  });
  m.def("quasi_static", [](const RailModel& rail, const WheelParams& w, const ContactParams& c,
                           const std::vector<double>& x) {
    std::vector<StaticResult> rs;
    { py::gil_scoped_release nogil; rs = solve_quasi_static(rail, w, c, x); }
    const size_t n = rs.size();
    Eigen::VectorXd yc(n), yw(n), sc(n), N(n);
    for (size_t i = 0; i < n; ++i) {
      yc(i) = rs[i].y_contact; yw(i) = rs[i].y_wheel; sc(i) = rs[i].contact_s;
      N(i) = rs[i].normal_force;
    }
    py::dict d;
    d["y_contact"] = yc; d["y_wheel"] = yw; d["contact_s"] = sc; d["normal_force"] = N;
    return d;
  });
  m.def("vertical_modes", [](const RailModel& rail, double M, double k,
                             const std::vector<double>& x, int n_modes) {
    ModalResult r;
    { py::gil_scoped_release nogil; r = vertical_modes(rail, M, k, x, n_modes); }
    return modal_to_tuple(r);
  }, "Vertical modes: (frequencies (n_pos, n_modes) [Hz], shapes (n_pos, n_dof + 1, n_modes))");
  m.def("axial_modes", [](const RailModel& rail, int n_modes) {
    return modal_to_tuple(axial_modes(rail, n_modes));
  });
}
