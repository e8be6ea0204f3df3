#include "common.hpp"

#include <cstdint>
#include <utility>

#include "output.hpp"

namespace trackwheel::bindings {

namespace {

// Hands the vector's buffer to numpy without copying it (the array owns it through a capsule),
// so a run's output is held once, not twice, on its way to Python.
template <class T>
py::array_t<T> as_array(std::vector<T>&& v) {
  auto* owner = new std::vector<T>(std::move(v));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owner->size()), owner->data(), free_owner);
}

}  // namespace

py::dict output_to_dict(SimOutput&& o) {
  py::dict d;
  const auto& table = output_fields();
  const py::ssize_t nw = o.rec.n_wheels();
  const py::ssize_t n_samples = static_cast<py::ssize_t>(o.rec.n_samples());
  for (int f = 0; f < kFieldCount; ++f) {
    std::vector<double>& col = o.rec.column(f);
    const py::ssize_t n = static_cast<py::ssize_t>(col.size());
    if (table[f].per_support) {  // (n_samples, n_supports), or None when not recorded
      const py::ssize_t ns = o.rec.n_supports();
      d[table[f].name] =
          ns > 0 ? as_array(std::move(col)).attr("reshape")(n_samples, ns) : py::object(py::none());
      continue;
    }
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
  {  // each support's envelope along the track, one array per envelope field
    py::dict env;
    const auto& info = envelope_fields();
    for (int f = 0; f < kEnvelopeFieldCount; ++f)
      env[info[f].name] = as_array(std::move(o.envelope.column(f)));
    d["support_envelope"] = env;
  }
  d["steps"] = o.steps;
  d["newton_iterations"] = o.newton_iterations;
  d["factorizations"] = o.factorizations;
  d["band_factorizations"] = o.band_factorizations;
  d["band_solves"] = o.band_solves;
  d["state_changes"] = o.state_changes;
  d["ballast_events"] = o.ballast_events;
  d["ballast_frozen"] = o.ballast_frozen;
  d["ballast_contact_time"] = o.ballast_contact_time;
  d["final_state"] = o.final_state;
  d["stability_limit"] = o.stability_limit;
  return d;
}

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
  d["sleeper_closed"] = r.closed;
  return d;
}

Model make_model(const RailModel& rail, const std::vector<WheelParams>& wheels,
                 const ContactParams& contact, const VehicleParams& vehicle) {
  return Model{rail, wheels, contact, vehicle};
}

void check_coordinates(const RailModel& rail, const Eigen::VectorXd& e, const char* name) {
  if (e.size() != rail.n_dof())
    throw std::invalid_argument(std::string(name) + " has " + std::to_string(e.size()) +
                                " entries; this rail has n_dof = " + std::to_string(rail.n_dof()));
}

ProgressFn python_progress(py::object progress) {
  if (progress.is_none()) return nullptr;
  return [progress](long step, long n) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    progress(step, n);
  };
}

}  // namespace trackwheel::bindings
