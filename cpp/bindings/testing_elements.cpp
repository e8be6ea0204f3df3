// Test-only probes of the elements, in the submodule _core.testing (not public API): the ANCF
// cable and shear-deformable elements, the quadrature and shape functions, the linear beam's
// Timoshenko element, the element's compliance and the contact law in series with it.
#include "ancf_cable.hpp"
#include "ancf_shear.hpp"
#include "common.hpp"
#include "contact.hpp"
#include "linear_beam.hpp"

namespace trackwheel::bindings {

namespace {

// The RailModel validates its own section; a ShearSection built directly is checked here (the
// element divides by kGA and l).
void check_shear_section(const ShearSection& c) {
  if (!(c.length > 0 && c.kGA > 0 && std::isfinite(c.kGA)))
    throw std::invalid_argument("ShearSection: length must be > 0 m, kGA finite > 0 N");
  check_gauss(c.n_gauss);
}

void bind_cable(py::module_& t) {
  py::class_<CableSection>(t, "CableSection")
      .def(py::init<>())
      .def_readwrite("length", &CableSection::length, "element length l [m]")
      .def_readwrite("EA", &CableSection::EA, "axial stiffness [N]")
      .def_readwrite("EI", &CableSection::EI, "bending stiffness [N m^2]")
      .def_readwrite("rhoA", &CableSection::rhoA, "mass per length [kg/m]")
      .def_readwrite("exact_curvature", &CableSection::exact_curvature)
      .def_readwrite("n_gauss", &CableSection::n_gauss);
  t.def("cable_mass", &cable_mass, "Element mass matrix (8x8) [kg]");
  t.def(
      "cable_elastic",
      [](const CableSection& c, const Vec8& e) {
        Vec8 Q;
        Mat8 K;
        double U;
        cable_elastic(c, e, &Q, &K, &U);
        return py::make_tuple(Q, K, U);
      },
      "Elastic force Q [N], Jacobian K = dQ/de [N/m], strain energy U [J]");
  t.def("cable_axial", [](const CableSection& c, const Vec8& e) {
    Vec8 Q;
    Mat8 K;
    double U;
    cable_axial(c, e, &Q, &K, &U);
    return py::make_tuple(Q, K, U);
  });
  t.def("cable_bending", [](const CableSection& c, const Vec8& e) {
    Vec8 Q;
    Mat8 K;
    double U;
    cable_bending(c, e, &Q, &K, &U);
    return py::make_tuple(Q, K, U);
  });
  t.def("gauss_points", [](int n) {
    Eigen::VectorXd xi(n), w(n);
    gauss_points(n, xi.data(), w.data());
    return py::make_tuple(xi, w);
  });
  t.def("hermite", [](double xi, double l) {
    const HermiteValues h = hermite(xi, l);
    return py::make_tuple(Eigen::Vector4d(h.n), Eigen::Vector4d(h.ns), Eigen::Vector4d(h.nss));
  });
}

void bind_shear(py::module_& t) {
  py::class_<ShearSection>(t, "ShearSection")
      .def(py::init<>())
      .def_readwrite("length", &ShearSection::length, "element length l [m]")
      .def_readwrite("EA", &ShearSection::EA, "axial stiffness [N]")
      .def_readwrite("EI", &ShearSection::EI, "bending stiffness [N m^2]")
      .def_readwrite("kGA", &ShearSection::kGA, "shear stiffness kappa G A [N]")
      .def_readwrite("rhoA", &ShearSection::rhoA, "mass per length [kg/m]")
      .def_readwrite("rhoI", &ShearSection::rhoI, "rotary inertia per length [kg m]")
      .def_readwrite("exact_curvature", &ShearSection::exact_curvature)
      .def_readwrite("n_gauss", &ShearSection::n_gauss);
  t.def(
      "shear_mass",
      [](const ShearSection& c) {
        check_shear_section(c);
        return shear_mass(c);
      },
      "Shear-deformable element mass matrix (8x8) [kg]");
  t.def(
      "shear_elastic",
      [](const ShearSection& c, const Vec8& e) {
        check_shear_section(c);
        Vec8 Q;
        Mat8 K;
        double U;
        shear_elastic(c, e, &Q, &K, &U);
        return py::make_tuple(Q, K, U);
      },
      "Shear-deformable element: elastic force Q [N], Jacobian K = dQ/de [N/m], strain energy "
      "U [J]");
}

void bind_linear_elements(py::module_& t) {
  t.def("timoshenko_stiffness", &timoshenko_stiffness, py::arg("EI"), py::arg("kGA"), py::arg("l"),
        "Exact IIE Timoshenko element stiffness (4x4) over [w1, psi1, w2, psi2]");
  t.def("timoshenko_mass", &timoshenko_mass, py::arg("rhoA"), py::arg("rhoI"), py::arg("EI"),
        py::arg("kGA"), py::arg("l"), "Consistent IIE element mass (4x4) with rotary inertia");
  t.def("timoshenko_energy", &timoshenko_energy, py::arg("EI"), py::arg("kGA"), py::arg("l"),
        py::arg("q"), "IIE element strain energy [J]");
  t.def(
      "timoshenko_shapes",
      [](double xi, double l, double phi) {
        const BeamShapes s = timoshenko_shapes(xi, l, phi);
        Eigen::Matrix<double, 5, 4> out;
        for (int a = 0; a < 4; ++a) out.col(a) << s.w[a], s.ws[a], s.wss[a], s.psi[a], s.psis[a];
        return out;
      },
      py::arg("xi"), py::arg("l"), py::arg("phi"),
      "IIE shape functions: rows w, w', w'', psi, psi'; columns [w1, psi1, w2, psi2]");
  t.def(
      "fixed_end_compliance",
      [](double EI, double shear_compliance, double l, double a) {
        const ElementCompliance g = fixed_end_compliance(EI, shear_compliance, l, a);
        return py::make_tuple(g.G, g.Ga, g.Gaa);
      },
      py::arg("EI"), py::arg("shear_compliance"), py::arg("l"), py::arg("a"),
      "The element's clamped-clamped compliance under a point load at a in [0, l]: (G [m/N], "
      "dG/da, d2G/da2); shear_compliance = 1/kGA [1/N], 0 for Euler-Bernoulli");
  t.def(
      "series_contact",
      [](ContactLaw law, double stiffness, double G, double delta) {
        const SeriesForce f = series_normal_force(law, stiffness, G, delta);
        return py::make_tuple(f.N, f.slope, f.compression,
                              series_potential(law, stiffness, G, delta));
      },
      py::arg("law"), py::arg("stiffness"), py::arg("G"), py::arg("delta"),
      "The contact law in series with a compliance G [m/N] at the approach delta [m]: (N [N], "
      "dN/d(delta) [N/m], the law's compression [m], the stored energy [J])");
}

}  // namespace

void bind_testing_elements(py::module_& t) {
  bind_cable(t);
  bind_shear(t);
  bind_linear_elements(t);
}

}  // namespace trackwheel::bindings
