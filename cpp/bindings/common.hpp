// What the binding files share (bindings/*.cpp, the only files with Python headers): the
// conversions of the kernel's results to Python objects, the guards on coordinate vectors, the
// progress callback, and the declarations of each file's bind function, called in order by
// module.cpp.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "model.hpp"
#include "statics.hpp"
#include "time_loop.hpp"

namespace trackwheel::bindings {

namespace py = pybind11;

// A run's output as {field: array} for every output table row (per-wheel fields (n_samples,
// n_wheels), integer fields int32), the bodies' body_z, body_phi (n_samples, n_bodies) and the
// counters; the buffers are handed to numpy without a copy.
py::dict output_to_dict(SimOutput&& o);
// A static solution as a dict (the fields of StaticResult).
py::dict static_to_dict(const StaticResult& r);
Model make_model(const RailModel& rail, const std::vector<WheelParams>& wheels,
                 const ContactParams& contact, const VehicleParams& vehicle = VehicleParams());
// Throws std::invalid_argument (ValueError) unless e has the rail's n_dof entries: the kernel
// indexes rail coordinate vectors without bounds checks.
void check_coordinates(const RailModel& rail, const Eigen::VectorXd& e, const char* name);
// progress(step, n_steps) called from the time loop with the GIL held; it is also where Ctrl-C
// reaches the kernel (PyErr_CheckSignals), whether or not a progress bar is shown.
ProgressFn python_progress(py::object progress);

// The binding files, each a list of .def calls of one concept (module.cpp calls them in this
// order, so that a type is registered before a signature names it).
void bind_track(py::module_& m);      // track.cpp: rail, supports, profile, wheel, contact
void bind_vehicle(py::module_& m);    // vehicle.cpp: vehicle bodies, suspensions, the window
void bind_statics(py::module_& m);    // statics.cpp
void bind_eigen(py::module_& m);      // eigen.cpp
void bind_dynamics(py::module_& m);   // dynamics.cpp: settings, state, simulate
void bind_linear(py::module_& m);     // linear.cpp: the linear path
void bind_frequency(py::module_& m);  // frequency.cpp: receptance, the periodic level
// The test-only probes and benchmark hooks, in the submodule _core.testing (not public API).
void bind_testing_elements(py::module_& t);  // testing_elements.cpp
void bind_testing_solvers(py::module_& t);   // testing_solvers.cpp

}  // namespace trackwheel::bindings
