// Bindings of the track: the rail and its supports, the running-surface profile, the wheel and
// the contact law, and the contact at a state.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "common.hpp"
#include "contact.hpp"
#include "linear_beam.hpp"
#include "profile.hpp"
#include "rail.hpp"

namespace trackwheel::bindings {

namespace {

using PpolyArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Appends scipy PPoly coefficients c (shape (4, m), highest power first) to the kernel's
// interval-major profile table, read in place (a km of profile is 32 MB: no temporary copy).
void append_ppoly(const PpolyArray& c, std::vector<double>& v) {
  if (c.ndim() != 2 || c.shape(0) != 4)
    throw std::invalid_argument("profile coefficients must have shape (4, m)");
  const auto a = c.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(1); ++i)
    for (py::ssize_t k = 0; k < 4; ++k) v.push_back(a(k, i));
}

// A Python object released with the GIL held wherever its last owner dies (the rail model
// and its profile are copied and destroyed in GIL-free code too).
std::shared_ptr<py::object> gil_held(py::object o) {
  return std::shared_ptr<py::object>(new py::object(std::move(o)), [](py::object* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
}

// The streamed profile's source: the next array of a Python iterator, drawn with the GIL
// (the time loop runs without it; one call per chunk).
Profile::ChunkSource python_chunk_source(const py::object& chunks) {
  auto it = gil_held(py::iter(chunks));
  return [it]() {
    py::gil_scoped_acquire gil;
    std::vector<double> v;
    py::object next = py::reinterpret_steal<py::object>(PyIter_Next(it->ptr()));
    if (!next) {
      if (PyErr_Occurred()) throw py::error_already_set();  // the iterator's own exception
      return v;                                             // exhausted
    }
    const PpolyArray c = py::cast<PpolyArray>(next);
    v.reserve(4 * static_cast<std::size_t>(c.ndim() == 2 ? c.shape(1) : 0));
    append_ppoly(c, v);
    return v;
  };
}

// `chunks` callable: each opening calls it for a fresh iterable; else the one iterable, once.
Profile::ChunkOpener python_chunk_opener(const py::object& chunks) {
  auto src = gil_held(chunks);
  return [src]() {
    py::gil_scoped_acquire gil;
    return python_chunk_source(PyCallable_Check(src->ptr()) ? (*src)() : *src);
  };
}

// The contact point and force of a wheel centre at (xa, ya) on the rail e.
py::dict contact_eval(const RailModel& rail, const Eigen::VectorXd& e, double xa, double ya,
                      double s_guess, const ContactParams& cp, const Vec10& qdot) {
  check_coordinates(rail, e, "e");
  const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(xa, ya), s_guess);
  const ContactForce cf = contact_force(cp, pt, qdot, true);
  py::dict d;
  d["s"] = pt.s;
  d["element"] = pt.mp.element;
  d["rho"] = pt.rho;
  d["phi"] = pt.phi;
  d["normal"] = Eigen::Vector2d(pt.n);
  d["tangent"] = Eigen::Vector2d(pt.t);
  d["y_contact"] = pt.r.y();
  d["surface"] = Eigen::Vector2d(pt.p);
  d["N"] = cf.N;
  d["active"] = cf.active;
  d["F"] = cf.F;
  d["K"] = cf.K;
  d["C"] = cf.C;
  d["grad_rho"] = cf.grad_rho;
  Vec10 sq;
  Mat10 sqq;
  contact_parameter_derivatives(pt, sq, &sqq);
  d["ds_dq"] = sq;
  d["d2s_dq2"] = sqq;
  d["compression"] = cf.compression;
  d["deflection"] = cf.deflection;
  d["rolling_radius"] = pt.rho + cf.deflection;
  d["compliance"] = pt.compliance.G;
  d["energy"] = cf.energy;
  return d;
}

void bind_rail_params(py::module_& m) {
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
      .def_readwrite("pin_far_end", &RailParams::pin_far_end)
      .def_readwrite("absorbing_length", &RailParams::absorbing_length, "L_z [m]")
      .def_readwrite("absorbing_damping", &RailParams::absorbing_damping,
                     "c_max at the rail ends [N s/m^2]")
      .def_readwrite("shear_stiffness", &RailParams::shear_stiffness,
                     "kappa G A [N]; 0: Euler-Bernoulli cable, > 0: shear-deformable element")
      .def_readwrite("rotary_inertia", &RailParams::rotary_inertia,
                     "rho I [kg m] (shear-deformable element only)")
      .def_readwrite("absorbing_axial_damping", &RailParams::absorbing_axial_damping,
                     "c_max,x on the axial motion at the rail ends [N s/m^2]");
  py::class_<SupportParams>(m, "SupportParams")
      .def(py::init<>())
      .def_readwrite("position", &SupportParams::position)
      .def_readwrite("stiffness", &SupportParams::stiffness)
      .def_readwrite("damping", &SupportParams::damping)
      .def_readwrite("sleeper_mass", &SupportParams::sleeper_mass)
      .def_readwrite("ballast_stiffness", &SupportParams::ballast_stiffness)
      .def_readwrite("ballast_damping", &SupportParams::ballast_damping)
      .def_readwrite("void_gap", &SupportParams::void_gap,
                     "g_j >= 0 [m] per support (empty: none): the void between sleeper j at rest "
                     "and its ballast bed; g_j > 0 makes that ballast unilateral")
      .def_readwrite("tensionless", &SupportParams::tensionless,
                     "every sleeper's ballast unilateral (pushes only)");
  py::class_<BeamParams>(m, "BeamParams")
      .def(py::init<>())
      .def_readwrite("shear_stiffness", &BeamParams::shear_stiffness,
                     "kappa G A [N]; 0: Euler-Bernoulli")
      .def_readwrite("rotary_inertia", &BeamParams::rotary_inertia, "rho I [kg m]");
}

void bind_profile(py::module_& m) {
  py::class_<Profile>(m, "Profile",
                      "Running-surface profile r(X): piecewise cubic on a uniform grid")
      .def(py::init<>())
      .def(py::init([](double x0, double dx, const PpolyArray& c) {
             // c: scipy PPoly coefficients, shape (4, m), highest power first
             std::vector<double> v;
             v.reserve(4 * static_cast<std::size_t>(c.ndim() == 2 ? c.shape(1) : 0));
             append_ppoly(c, v);
             return Profile(x0, dx, std::move(v));
           }),
           py::arg("x0"), py::arg("dx"), py::arg("coefficients"))
      .def(py::init([](double x0, double dx, py::ssize_t n_intervals, py::iterable chunks) {
             // the table chunk by chunk: no whole-table array on the Python side
             if (n_intervals < 1) throw std::invalid_argument("profile n_intervals must be >= 1");
             std::vector<double> v;
             v.reserve(4 * static_cast<std::size_t>(n_intervals));
             for (py::handle h : chunks) append_ppoly(py::cast<PpolyArray>(h), v);
             if (v.size() != 4 * static_cast<std::size_t>(n_intervals))
               throw std::invalid_argument(
                   "profile chunks hold " + std::to_string(v.size() / 4) +
                   " intervals, n_intervals = " + std::to_string(n_intervals));
             return Profile(x0, dx, std::move(v));
           }),
           py::arg("x0"), py::arg("dx"), py::arg("n_intervals"), py::arg("chunks"),
           "The table from an iterable of (4, m_k) coefficient arrays, m_k summing to "
           "n_intervals")
      .def(py::init([](double x0, double dx, int n_intervals, py::object chunks, double retention) {
             if (!PyCallable_Check(chunks.ptr()) && !py::isinstance<py::iterable>(chunks))
               throw py::type_error("profile chunks must be an iterable or a callable");
             return Profile(x0, dx, n_intervals, python_chunk_opener(chunks), retention,
                            PyCallable_Check(chunks.ptr()) != 0);
           }),
           py::arg("x0"), py::arg("dx"), py::arg("n_intervals"), py::arg("chunks"),
           py::arg("retention"),
           "Streamed: the (4, m_k) coefficient arrays of `chunks` (an iterable, or a callable "
           "returning a fresh one) are drawn as X advances and dropped once they end more than "
           "`retention` [m] behind the furthest X requested. A request behind the kept range "
           "draws a fresh iterable from the callable and reads forwards to it, or raises "
           "RuntimeError for a plain iterable. An exception of the iterator surfaces where the "
           "profile is read")
      .def_property_readonly("empty", &Profile::empty)
      .def_property_readonly("streamed", &Profile::streamed)
      .def_property_readonly("n_intervals", &Profile::n_intervals)
      .def_property_readonly("loaded_intervals", &Profile::loaded_intervals, "intervals held now")
      .def_property_readonly("peak_loaded_intervals", &Profile::peak_loaded_intervals,
                             "the most intervals ever held at once")
      .def_property_readonly("rewinds", &Profile::rewinds, "times the stream was re-opened")
      .def(
          "__call__",
          [](const Profile& p, double x) {
            const ProfileValue v = p(x);
            return py::make_tuple(v.r, v.rx, v.rxx);
          },
          "(r, dr/dX, d2r/dX2) at X");
}

void bind_wheel_contact(py::module_& m) {
  py::class_<WheelParams>(m, "WheelParams")
      .def(py::init<>())
      .def_readwrite("mass", &WheelParams::mass)
      .def_readwrite("inertia", &WheelParams::inertia)
      .def_readwrite("radius", &WheelParams::radius)
      .def_readwrite("load", &WheelParams::load)
      .def_readwrite("torque", &WheelParams::torque)
      .def_readwrite("brake_torque", &WheelParams::brake_torque,
                     "T_b of the friction brake on the rotation [N m] (0: none)")
      .def_readwrite("gravity", &WheelParams::gravity)
      .def_readwrite("x_offset", &WheelParams::x_offset,
                     "X_A - (X_0 + v t), the wheel's place along the vehicle [m]")
      .def_readwrite("out_of_round", &WheelParams::out_of_round,
                     "Delta rho(psi) [m] over one revolution psi in [0, 2 pi] (empty: round)");
  py::enum_<ContactLaw>(m, "ContactLaw")
      .value("linear", ContactLaw::Linear)
      .value("hertz", ContactLaw::Hertz);
  py::class_<ContactParams>(m, "ContactParams")
      .def(py::init<>())
      .def_readwrite("law", &ContactParams::law)
      .def_readwrite("stiffness", &ContactParams::stiffness)
      .def_readwrite("damping", &ContactParams::damping)
      .def_readwrite("radius", &ContactParams::radius)
      .def_readwrite("friction", &ContactParams::friction, "mu, slip judgement [-]")
      .def_readwrite("element_compliance", &ContactParams::element_compliance,
                     "the rail element's fixed-end compliance under the load in series with the "
                     "law (docs: Model § Contact)");
}

void bind_rail_model(py::module_& m) {
  py::class_<RailModel>(m, "RailModel")
      .def(py::init<const RailParams&, const SupportParams&>())
      .def(py::init<const RailParams&, const SupportParams&, Profile>())
      .def_property_readonly("profile", &RailModel::profile,
                             "the rail's profile (a streamed one shares its state)")
      .def_property_readonly("n_dof", &RailModel::n_dof)
      .def_property_readonly("n_free", &RailModel::n_free)
      .def_property_readonly("n_nodes", &RailModel::n_nodes)
      .def_property_readonly("element_length", &RailModel::element_length)
      .def_property_readonly("free_to_full", &RailModel::free_to_full)
      .def_property_readonly("total_mass", &RailModel::total_mass)
      .def("reference", &RailModel::reference)
      .def("mass_dense", &RailModel::mass_dense)
      .def("mass_band_dense", [](const RailModel& r) { return r.mass().dense(); })
      .def("tangent_dense",
           [](const RailModel& r, const Eigen::VectorXd& e) {
             check_coordinates(r, e, "e");
             return r.tangent_dense(e);
           })
      .def("gravity_force", &RailModel::gravity_force)
      .def("internal_force",
           [](const RailModel& r, const Eigen::VectorXd& e) {
             check_coordinates(r, e, "e");
             Eigen::VectorXd Q;
             double U;
             r.internal_force(e, nullptr, Q, &U);
             return py::make_tuple(Q, U);
           })
      .def(
          "positions",
          [](const RailModel& r, const Eigen::VectorXd& e, const std::vector<double>& s) {
            check_coordinates(r, e, "e");
            for (double si : s)
              if (!std::isfinite(si)) throw std::invalid_argument("s must be finite [m]");
            Eigen::MatrixXd out(s.size(), 2);
            for (size_t i = 0; i < s.size(); ++i) out.row(i) = r.position(e, r.locate(s[i]));
            return out;
          },
          "Rail points r(s) (n, 2) [m] for material coordinates s [m]");
  m.def("contact_eval", &contact_eval, "Contact point and force for q = [X_A, Y_A, e_el]");
}

}  // namespace

void bind_track(py::module_& m) {
  bind_rail_params(m);
  bind_profile(m);
  bind_wheel_contact(m);
  bind_rail_model(m);
}

}  // namespace trackwheel::bindings
