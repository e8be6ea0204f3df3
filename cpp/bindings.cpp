// The only file with Python headers: a list of bindings to the kernel.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "ancf_cable.hpp"
#include "bench.hpp"
#include "contact.hpp"
#include "dynamics.hpp"
#include "eigen_analysis.hpp"
#include "frequency.hpp"
#include "generalized_alpha.hpp"
#include "limits.hpp"
#include "linear_beam.hpp"
#include "linear_track.hpp"
#include "model.hpp"
#include "output.hpp"
#include "periodic.hpp"
#include "rail.hpp"
#include "rolling.hpp"
#include "statics.hpp"

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
  d["sleeper_z"] = r.z;
  d["ballast_force"] = r.ballast_force;
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

// Hands the vector's buffer to numpy without copying it (the array owns it through a capsule),
// so a run's output is held once, not twice, on its way to Python.
template <class T>
py::array_t<T> as_array(std::vector<T>&& v) {
  auto* owner = new std::vector<T>(std::move(v));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owner->size()), owner->data(), free_owner);
}

// Every field of the output table under its name: per-wheel fields (n_samples, n_wheels),
// the others (n_samples,); integer fields as int32. Plus the run's counters.
py::dict output_to_dict(SimOutput&& o) {
  py::dict d;
  const auto& table = output_fields();
  const py::ssize_t nw = o.rec.n_wheels();
  for (int f = 0; f < kFieldCount; ++f) {
    std::vector<double>& col = o.rec.column(f);
    const py::ssize_t n = static_cast<py::ssize_t>(col.size());
    py::array arr;
    if (table[f].integer) {
      std::vector<int32_t> ints(col.begin(), col.end());
      arr = as_array(std::move(ints));
    } else {
      arr = as_array(std::move(col));
    }
    if (table[f].per_wheel) arr = arr.attr("reshape")(n / nw, nw);
    d[table[f].name] = arr;
  }
  {  // the vehicle's bodies: z [m] and phi [rad], (n_samples, n_bodies) each
    const py::ssize_t nb = o.rec.n_bodies();
    const std::vector<double>& b = o.rec.bodies();
    const py::ssize_t ns = nb > 0 ? static_cast<py::ssize_t>(b.size()) / (2 * nb) : 0;
    py::array_t<double> z({ns, nb}), phi({ns, nb});
    auto zm = z.mutable_unchecked<2>();
    auto pm = phi.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < ns; ++i)
      for (py::ssize_t k = 0; k < nb; ++k) {
        zm(i, k) = b[2 * (i * nb + k)];
        pm(i, k) = b[2 * (i * nb + k) + 1];
      }
    d["body_z"] = z;
    d["body_phi"] = phi;
  }
  d["steps"] = o.steps;
  d["newton_iterations"] = o.newton_iterations;
  d["factorizations"] = o.factorizations;
  d["state_changes"] = o.state_changes;
  d["final_state"] = o.final_state;
  d["stability_limit"] = o.stability_limit;
  return d;
}

py::tuple output_table() {
  py::list rows;
  for (const FieldInfo& f : output_fields())
    rows.append(
        py::make_tuple(f.name, f.unit, f.doc, f.per_wheel, f.integer ? "int32" : "float64"));
  return py::tuple(rows);
}

Model make_model(const RailModel& rail, const std::vector<WheelParams>& wheels,
                 const ContactParams& contact, const VehicleParams& vehicle = VehicleParams()) {
  return Model{rail, wheels, contact, vehicle};
}

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

// Guards for hostile input at the binding level: the kernel indexes rail coordinate vectors
// without bounds checks, so every binding taking one checks its size first (std::invalid_argument
// becomes ValueError in Python).
void check_coordinates(const RailModel& rail, const Eigen::VectorXd& e, const char* name) {
  if (e.size() != rail.n_dof())
    throw std::invalid_argument(std::string(name) + " has " + std::to_string(e.size()) +
                                " entries; this rail has n_dof = " + std::to_string(rail.n_dof()));
}

// progress(step, n_steps) called from the time loop with the GIL held; it is also where Ctrl-C
// reaches the kernel (PyErr_CheckSignals), whether or not a progress bar is shown.
ProgressFn python_progress(py::object progress) {
  if (progress.is_none()) return nullptr;
  return [progress](long step, long n) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    progress(step, n);
  };
}

// The RailModel validates its own section; a ShearSection built directly is checked here (the
// element divides by kGA and l).
void check_shear_section(const ShearSection& c) {
  if (!(c.length > 0 && c.kGA > 0 && std::isfinite(c.kGA)))
    throw std::invalid_argument("ShearSection: length must be > 0 m, kGA finite > 0 N");
  check_gauss(c.n_gauss);
}

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
  m.def(
      "cable_elastic",
      [](const CableSection& c, const Vec8& e) {
        Vec8 Q;
        Mat8 K;
        double U;
        cable_elastic(c, e, &Q, &K, &U);
        return py::make_tuple(Q, K, U);
      },
      "Elastic force Q [N], Jacobian K = dQ/de [N/m], strain energy U [J]");
  m.def("cable_axial", [](const CableSection& c, const Vec8& e) {
    Vec8 Q;
    Mat8 K;
    double U;
    cable_axial(c, e, &Q, &K, &U);
    return py::make_tuple(Q, K, U);
  });
  m.def("cable_bending", [](const CableSection& c, const Vec8& e) {
    Vec8 Q;
    Mat8 K;
    double U;
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

  py::class_<ShearSection>(m, "ShearSection")
      .def(py::init<>())
      .def_readwrite("length", &ShearSection::length, "element length l [m]")
      .def_readwrite("EA", &ShearSection::EA, "axial stiffness [N]")
      .def_readwrite("EI", &ShearSection::EI, "bending stiffness [N m^2]")
      .def_readwrite("kGA", &ShearSection::kGA, "shear stiffness kappa G A [N]")
      .def_readwrite("rhoA", &ShearSection::rhoA, "mass per length [kg/m]")
      .def_readwrite("rhoI", &ShearSection::rhoI, "rotary inertia per length [kg m]")
      .def_readwrite("exact_curvature", &ShearSection::exact_curvature)
      .def_readwrite("n_gauss", &ShearSection::n_gauss);
  m.def(
      "shear_mass",
      [](const ShearSection& c) {
        check_shear_section(c);
        return shear_mass(c);
      },
      "Shear-deformable element mass matrix (8x8) [kg]");
  m.def(
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
      .def_readwrite("ballast_damping", &SupportParams::ballast_damping);
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
  py::class_<BodyParams>(m, "BodyParams")
      .def(py::init<>())
      .def_readwrite("mass", &BodyParams::mass, "[kg]")
      .def_readwrite("inertia", &BodyParams::inertia, "pitch inertia [kg m^2]")
      .def_readwrite("gravity", &BodyParams::gravity, "[m/s^2]")
      .def_readwrite("load", &BodyParams::load, "constant downward force on the centre [N]");
  py::class_<SuspensionParams>(m, "SuspensionParams")
      .def(py::init<>())
      .def_readwrite("stiffness", &SuspensionParams::stiffness, "k [N/m]")
      .def_readwrite("damping", &SuspensionParams::damping, "c [N s/m]")
      .def_readwrite("lower_wheel", &SuspensionParams::lower_wheel, "wheel index or -1")
      .def_readwrite("lower_body", &SuspensionParams::lower_body, "body index or -1")
      .def_readwrite("lower_arm", &SuspensionParams::lower_arm, "[m]")
      .def_readwrite("upper_body", &SuspensionParams::upper_body, "body index")
      .def_readwrite("upper_arm", &SuspensionParams::upper_arm, "[m]");
  py::class_<VehicleParams>(m, "VehicleParams")
      .def(py::init<>())
      .def_readwrite("bodies", &VehicleParams::bodies, "a copy: assign the whole list")
      .def_readwrite("suspensions", &VehicleParams::suspensions, "a copy: assign the whole list");
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

  m.def(
      "contact_eval",
      [](const RailModel& rail, const Eigen::VectorXd& e, double xa, double ya, double s_guess,
         const ContactParams& cp, const Vec10& qdot) {
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
      },
      "Contact point and force for q = [X_A, Y_A, e_el]");

  m.def("static_solve",
        [](const RailModel& rail, const WheelParams& w, const ContactParams& c, double x) {
          StaticResult r;
          {
            py::gil_scoped_release nogil;
            r = solve_static(rail, w, c, x);
          }
          return static_to_dict(r);
        });
  m.def(
      "static_solve_wheels",
      [](const RailModel& rail, const std::vector<WheelParams>& w,
         const std::vector<ContactParams>& c, const std::vector<double>& x) {
        std::vector<StaticResult> rs;
        {
          py::gil_scoped_release nogil;
          rs = solve_static_wheels(rail, w, c, x);
        }
        py::list out;
        for (const StaticResult& r : rs) out.append(static_to_dict(r));
        return out;
      },
      py::arg("rail"), py::arg("wheels"), py::arg("contacts"), py::arg("x_wheels"),
      "Static equilibrium of several wheels on the rail, wheel w at x_wheels[w] under its load "
      "F + M g: one static_solve dict per wheel (the same rail e in each)");
  m.def("rail_static", [](const RailModel& rail) {
    py::gil_scoped_release nogil;
    return solve_rail_static(rail);
  });
  m.def(
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
  m.def("quasi_static", [](const RailModel& rail, const WheelParams& w, const ContactParams& c,
                           const std::vector<double>& x) {
    std::vector<StaticResult> rs;
    {
      py::gil_scoped_release nogil;
      rs = solve_quasi_static(rail, w, c, x);
    }
    const size_t n = rs.size();
    Eigen::VectorXd yc(n), yw(n), sc(n), N(n);
    for (size_t i = 0; i < n; ++i) {
      yc(i) = rs[i].y_contact;
      yw(i) = rs[i].y_wheel;
      sc(i) = rs[i].contact_s;
      N(i) = rs[i].normal_force;
    }
    py::dict d;
    d["y_contact"] = yc;
    d["y_wheel"] = yw;
    d["contact_s"] = sc;
    d["normal_force"] = N;
    return d;
  });
  m.def("linear_static_line", &linear_static_line, py::arg("rail"), py::arg("beam"),
        py::arg("load"), py::arg("x"), py::arg("n_modes") = 0,
        py::arg("element_compliance") = false, py::call_guard<py::gil_scoped_release>(),
        "Quasi-static line of the linear track: y(X_i) [m] under the load P [N] resting at "
        "each X_i [m] (K q = Q_g - P s(X)); n_modes > 0: of its modal reduction; "
        "element_compliance: the element's own deflection under the load G(X_i) P included.");
  m.def(
      "vertical_modes",
      [](const RailModel& rail, double M, double k, const std::vector<double>& x, int n_modes) {
        ModalResult r;
        {
          py::gil_scoped_release nogil;
          r = vertical_modes(rail, M, k, x, n_modes);
        }
        return modal_to_tuple(r);
      },
      "Vertical modes: (frequencies (n_pos, n_modes) [Hz], shapes (n_pos, n_dof + 1 + n_sleepers, "
      "n_modes))");
  m.def("axial_modes", [](const RailModel& rail, int n_modes) {
    return modal_to_tuple(axial_modes(rail, n_modes));
  });
  m.def(
      "direction_pencil",
      [](const RailModel& rail, int component, double M, double k, double x) {
        const SparsePencil p = direction_pencil(rail, component, M, k, x);
        py::dict d;
        d["n"] = p.n;
        d["dofs"] = p.dofs;
        d["row"] = p.row;
        d["col"] = p.col;
        d["K"] = p.K;
        d["M"] = p.M;
        d["C"] = p.C;
        return d;
      },
      py::arg("rail"), py::arg("component"), py::arg("wheel_mass") = 0.0,
      py::arg("contact_stiffness") = 0.0, py::arg("position") = 0.0,
      "K [N/m], M [kg], C [N s/m] of one direction (0: x, 1: y with the wheel if wheel_mass > 0) "
      "at the straight reference as triplets {n, dofs, row, col, K, M, C} over local coordinates "
      "(the direction's free coordinates, full indices in dofs, then the wheel's Y_w and the "
      "sleepers' z_j on layered supports)");

  // ---------------------------------------------------------------- the vehicle's own matrices
  m.def(
      "vehicle_matrices",
      [](const VehicleParams& vehicle, int n_wheels) {
        check_vehicle(vehicle, n_wheels);
        const VehicleMatrices vm = vehicle_matrices(vehicle, n_wheels);
        py::dict d;
        d["K"] = vm.K;
        d["C"] = vm.C;
        d["mass"] = vm.mass;
        d["G"] = vm.G;
        return d;
      },
      py::arg("vehicle"), py::arg("n_wheels"),
      "The vehicle's constant matrices over u = [Y_A per wheel, (z, phi) per body] "
      "(vehicle.hpp): {'K' [N/m], 'C' [N s/m]: sum k g g^T, sum c g g^T over the suspensions; "
      "'mass': the bodies' masses [kg] and pitch inertias [kg m^2], the wheels' entries 0; 'G': "
      "the bodies' weights and loads [N]}");
  m.def(
      "static_bodies",
      [](const VehicleParams& vehicle, const Eigen::VectorXd& y_wheels) {
        const int nw = static_cast<int>(y_wheels.size());
        check_vehicle(vehicle, nw);
        if (vehicle.empty()) return Eigen::VectorXd(Eigen::VectorXd::Zero(0));
        return static_bodies(vehicle_matrices(vehicle, nw), y_wheels);
      },
      py::arg("vehicle"), py::arg("y_wheels"),
      "[z_0, phi_0, z_1, phi_1, ...] [m, rad] of the bodies in static equilibrium above wheel "
      "centres held at heights y_wheels [m]: the bodies' rows of K_v u = -G (vehicle.hpp)");

  // ---------------------------------------------------------------- linear beam, frequency domain
  py::class_<BeamParams>(m, "BeamParams")
      .def(py::init<>())
      .def_readwrite("shear_stiffness", &BeamParams::shear_stiffness,
                     "kappa G A [N]; 0: Euler-Bernoulli")
      .def_readwrite("rotary_inertia", &BeamParams::rotary_inertia, "rho I [kg m]");
  m.def("timoshenko_stiffness", &timoshenko_stiffness, py::arg("EI"), py::arg("kGA"), py::arg("l"),
        "Exact IIE Timoshenko element stiffness (4x4) over [w1, psi1, w2, psi2]");
  m.def("timoshenko_mass", &timoshenko_mass, py::arg("rhoA"), py::arg("rhoI"), py::arg("EI"),
        py::arg("kGA"), py::arg("l"), "Consistent IIE element mass (4x4) with rotary inertia");
  m.def("timoshenko_energy", &timoshenko_energy, py::arg("EI"), py::arg("kGA"), py::arg("l"),
        py::arg("q"), "IIE element strain energy [J]");
  m.def(
      "timoshenko_shapes",
      [](double xi, double l, double phi) {
        const BeamShapes s = timoshenko_shapes(xi, l, phi);
        Eigen::Matrix<double, 5, 4> out;
        for (int a = 0; a < 4; ++a) out.col(a) << s.w[a], s.ws[a], s.wss[a], s.psi[a], s.psis[a];
        return out;
      },
      py::arg("xi"), py::arg("l"), py::arg("phi"),
      "IIE shape functions: rows w, w', w'', psi, psi'; columns [w1, psi1, w2, psi2]");
  m.def(
      "fixed_end_compliance",
      [](double EI, double shear_compliance, double l, double a) {
        const ElementCompliance g = fixed_end_compliance(EI, shear_compliance, l, a);
        return py::make_tuple(g.G, g.Ga, g.Gaa);
      },
      py::arg("EI"), py::arg("shear_compliance"), py::arg("l"), py::arg("a"),
      "The element's clamped-clamped compliance under a point load at a in [0, l]: (G [m/N], "
      "dG/da, d2G/da2); shear_compliance = 1/kGA [1/N], 0 for Euler-Bernoulli");
  m.def(
      "series_contact",
      [](ContactLaw law, double stiffness, double G, double delta) {
        const SeriesForce f = series_normal_force(law, stiffness, G, delta);
        return py::make_tuple(f.N, f.slope, f.compression,
                              series_potential(law, stiffness, G, delta));
      },
      py::arg("law"), py::arg("stiffness"), py::arg("G"), py::arg("delta"),
      "The contact law in series with a compliance G [m/N] at the approach delta [m]: (N [N], "
      "dN/d(delta) [N/m], the law's compression [m], the stored energy [J])");
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
  m.def(
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

  // ---------------------------------------------------------------- periodic track
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
  m.def(
      "periodic_receptance_matrix",
      [](const PeriodicTrackParams& track, double speed, double omega, int n,
         const std::vector<double>& offsets, double rtol, bool with_stats) -> py::object {
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
      },
      py::arg("track"), py::arg("speed"), py::arg("omega"), py::arg("n"), py::arg("offsets"),
      py::arg("rtol"), py::arg("stats") = false,
      "Moving-load receptance matrices (n_offsets, 2n+1, 2n+1) [m/N] of the periodic track; "
      "with stats=True also the work counts {points, poles, rounds, den_evaluations}");
  m.def("periodic_lattice_sum", &periodic_lattice_sum, py::arg("track"), py::arg("k"), py::arg("w"),
        "The lattice sum S(k, w) [m/N] of the periodic track");

  // ---------------------------------------------------------------- dynamics
  py::enum_<Integrator>(m, "Integrator")
      .value("generalized_alpha", Integrator::GeneralizedAlpha)
      .value("explicit", Integrator::ExplicitRK4);
  py::enum_<SlipState>(m, "SlipState")
      .value("free", SlipState::Free)
      .value("stick", SlipState::Stick)
      .value("slip", SlipState::Slip);
  py::class_<SimSettings>(m, "SimSettings")
      .def(py::init<>())
      .def_readwrite("integrator", &SimSettings::integrator)
      .def_readwrite("speed", &SimSettings::speed)
      .def_readwrite("x_start", &SimSettings::x_start)
      .def_readwrite("t_end", &SimSettings::t_end)
      .def_readwrite("dt", &SimSettings::dt)
      .def_readwrite("rho_inf", &SimSettings::rho_inf)
      .def_readwrite("baumgarte", &SimSettings::baumgarte)
      .def_readwrite("rolling", &SimSettings::rolling)
      .def_readwrite("output_every", &SimSettings::output_every)
      .def_readwrite("max_newton", &SimSettings::max_newton)
      .def_readwrite("newton_tol", &SimSettings::newton_tol)
      .def_readwrite("reuse_jacobian", &SimSettings::reuse_jacobian)
      .def_readwrite("record_energy", &SimSettings::record_energy)
      .def_readwrite("progress_every", &SimSettings::progress_every)
      .def_readwrite("window", &SimSettings::window, "the travelling window (a copy: assign it)");
  py::class_<WindowParams>(m, "WindowParams")
      .def(py::init<>())
      .def_readwrite("bay", &WindowParams::bay, "sleeper bay d_s [m]; 0: no window")
      .def_readwrite("elements_per_bay", &WindowParams::elements_per_bay, "[-]")
      .def_readwrite("origin", &WindowParams::origin, "track coordinate of s = 0 at t = 0 [m]")
      .def_readwrite("hold", &WindowParams::hold, "s of the rearmost wheel at a shift [m]");
  py::class_<WheelState>(m, "WheelState")
      .def(py::init<>())
      .def_readwrite("y", &WheelState::y, "Y_A [m]")
      .def_readwrite("ydot", &WheelState::ydot, "dY_A/dt [m/s]")
      .def_readwrite("theta", &WheelState::theta, "rolling angle [rad]")
      .def_readwrite("thetadot", &WheelState::thetadot, "rolling rate [rad/s]")
      .def_readwrite("s", &WheelState::s, "contact parameter warm start [m]")
      .def_readwrite("state", &WheelState::state)
      .def_readwrite("sigma", &WheelState::sigma, "sign of the sliding friction force")
      .def_readwrite("locked", &WheelState::locked, "held by the brake at theta' = 0")
      .def_readwrite("brake_sign", &WheelState::brake_sign,
                     "sign of the brake torque on the turning wheel (-sign theta')");
  py::class_<SimState>(m, "SimState")
      .def(py::init<>())
      .def_readwrite("e", &SimState::e, "rail coordinates (n_dof,)")
      .def_readwrite("edot", &SimState::edot, "rail velocities (n_dof,)")
      .def_readwrite("wheels", &SimState::wheels,
                     "one WheelState per wheel (a copy: assign the whole list)")
      .def_readwrite("body", &SimState::body, "(2 n_bodies,) [z, phi] per vehicle body")
      .def_readwrite("bodydot", &SimState::bodydot, "(2 n_bodies,) rates")
      .def_readwrite("z", &SimState::z,
                     "sleeper heights (n_sleepers,) [m]; empty: at rest under the initial rail")
      .def_readwrite("zdot", &SimState::zdot, "sleeper velocities (n_sleepers,) [m/s]");

  // trackwheel.DivergenceError(message, time=, step=, cause=) for the kernel's DivergenceError
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const DivergenceError& e) {
      py::object cls = py::module_::import("trackwheel").attr("DivergenceError");
      py::object exc = cls(e.what(), e.time, e.step, e.cause);
      PyErr_SetObject(cls.ptr(), exc.ptr());
    }
  });

  m.attr("OUTPUT_FIELDS") = output_table();
  m.attr("MAX_ELEMENTS") = limits::kMaxElements;
  m.attr("MAX_DENSE_EIGEN_DOF") = limits::kMaxDenseEigenDof;
  m.attr("GAUSS_RANGE") = py::make_tuple(limits::kMinGauss, limits::kMaxGauss);
  m.attr("MAX_SPEED") = limits::kMaxSpeed;
  m.attr("MAX_SUPPORTS") = limits::kMaxSupports;

  m.def(
      "simulate",
      [](const RailModel& rail, const std::vector<WheelParams>& wheels, const ContactParams& c,
         const SimSettings& s, const SimState& init, py::object progress,
         const VehicleParams& vehicle) {
        const ProgressFn fn = python_progress(progress);
        const Model model = make_model(rail, wheels, c, vehicle);
        SimOutput o;
        {
          py::gil_scoped_release nogil;
          o = simulate(model, s, init, fn);
        }
        return output_to_dict(std::move(o));
      },
      py::arg("rail"), py::arg("wheels"), py::arg("contact"), py::arg("settings"),
      py::arg("initial"), py::arg("progress") = py::none(), py::arg("vehicle") = VehicleParams(),
      "Run the whole time loop in C++ (GIL released; progress(step, n_steps) called every "
      "settings.progress_every steps with the GIL held, which also checks for Ctrl-C). Returns "
      "{field: array} for every OUTPUT_FIELDS row (per-wheel fields (n_samples, n_wheels)) and "
      "the vehicle's body_z, body_phi (n_samples, n_bodies), the counters steps, "
      "newton_iterations, factorizations, state_changes, stability_limit, final_state");
  m.def(
      "highest_frequency",
      [](const RailModel& rail, const WheelParams& w, const ContactParams& c,
         const Eigen::VectorXd& e, double x, double y) {
        check_coordinates(rail, e, "e");
        return highest_frequency(make_model(rail, {w}, c), e, {x}, {y});
      },
      "omega_max [rad/s] of the linearised rail + wheel-on-contact-spring system");
  m.def("explicit_stability_limit", &explicit_stability_limit);
  m.def("time_band_factor_solve", &time_band_factor_solve, py::arg("rail"), py::arg("cq"),
        py::arg("cv"), py::arg("repeats"), py::arg("bordered") = false,
        "Mean wall time [s] of one factorisation + solve of M + cv C_s + cq K_t (benchmarks)");
  m.def(
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

  py::enum_<WheelModel>(m, "WheelModel")
      .value("moving_force", WheelModel::MovingForce)
      .value("moving_mass", WheelModel::MovingMass)
      .value("sprung", WheelModel::Sprung)
      .value("hertz", WheelModel::Hertz);
  py::class_<LinearOptions>(m, "LinearOptions")
      .def(py::init<>())
      .def_readwrite("wheel_model", &LinearOptions::wheel_model)
      .def_readwrite("n_modes", &LinearOptions::n_modes)
      .def_readwrite("sudden", &LinearOptions::sudden)
      .def_readwrite("drop_height", &LinearOptions::drop_height)
      .def_readwrite("beam", &LinearOptions::beam);
  m.def(
      "simulate_linear",
      [](const RailModel& rail, const std::vector<WheelParams>& wheels, const ContactParams& c,
         const SimSettings& s, const LinearOptions& opt, py::object progress,
         const VehicleParams& vehicle) {
        const ProgressFn fn = python_progress(progress);
        const Model model = make_model(rail, wheels, c, vehicle);
        SimOutput o;
        {
          py::gil_scoped_release nogil;
          o = simulate_linear(model, s, opt, fn);
        }
        py::dict d = output_to_dict(std::move(o));
        d["final_state"] = py::none();
        return d;
      },
      py::arg("rail"), py::arg("wheels"), py::arg("contact"), py::arg("settings"),
      py::arg("options"), py::arg("progress") = py::none(), py::arg("vehicle") = VehicleParams(),
      "Linear vertical track fast path (Euler-Bernoulli or Timoshenko rail, constant matrices)");

  // ---------------------------------------------------------------- test hooks
  m.def(
      "ga_probe",
      [](const RailModel& rail, const std::vector<WheelParams>& wheels, const ContactParams& c,
         const SimSettings& s, const SimState& init, double t1, std::optional<Eigen::VectorXd> x,
         const VehicleParams& vehicle) {
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
            throw std::invalid_argument(
                "x must have n_free + 3 n_wheels + 2 n_bodies + n_sleepers = " +
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
      },
      py::arg("rail"), py::arg("wheels"), py::arg("contact"), py::arg("settings"),
      py::arg("initial"), py::arg("t1"), py::arg("x") = py::none(),
      py::arg("vehicle") = VehicleParams(),
      "Test hook: the generalized-alpha step from the consistent start of `initial` to t1 [s] "
      "at the iterate x = [e''_free, (Y'', theta'', lambda) per wheel, (z'', phi'') per body, "
      "z'' per sleeper] (None: the start accelerations). Returns {'start': the start "
      "accelerations in that layout, 'residual': -r, 'matrix': the iteration matrix dr/dx "
      "(assembled, dense, the sleepers uncondensed), 'solution': the kernel's Newton correction "
      "(the sleepers condensed)}");
  m.def(
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
  m.def(
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
}
