// Bindings of the vehicle above the wheels (bodies, suspensions, its constant matrices and
// static state) and of the travelling window.
#include "vehicle.hpp"

#include "common.hpp"
#include "state.hpp"

namespace trackwheel::bindings {

namespace {

py::dict vehicle_matrices_dict(const VehicleParams& vehicle, int n_wheels) {
  check_vehicle(vehicle, n_wheels);
  const VehicleMatrices vm = vehicle_matrices(vehicle, n_wheels);
  py::dict d;
  d["K"] = vm.K;
  d["C"] = vm.C;
  d["mass"] = vm.mass;
  d["G"] = vm.G;
  return d;
}

Eigen::VectorXd static_bodies_of(const VehicleParams& vehicle, const Eigen::VectorXd& y_wheels) {
  const int nw = static_cast<int>(y_wheels.size());
  check_vehicle(vehicle, nw);
  if (vehicle.empty()) return Eigen::VectorXd(Eigen::VectorXd::Zero(0));
  return static_bodies(vehicle_matrices(vehicle, nw), y_wheels);
}

}  // namespace

void bind_vehicle(py::module_& m) {
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
  py::class_<WindowParams>(m, "WindowParams")
      .def(py::init<>())
      .def_readwrite("bay", &WindowParams::bay, "sleeper bay d_s [m]; 0: no window")
      .def_readwrite("elements_per_bay", &WindowParams::elements_per_bay, "[-]")
      .def_readwrite("origin", &WindowParams::origin, "track coordinate of s = 0 at t = 0 [m]")
      .def_readwrite("hold", &WindowParams::hold, "s of the rearmost wheel at a shift [m]")
      .def_readwrite("supports", &WindowParams::supports,
                     "the track's supports streamed into the window, one per sleeper from the "
                     "start window's rear support on (a copy: assign it); empty: the rail's");
  m.def("vehicle_matrices", &vehicle_matrices_dict, py::arg("vehicle"), py::arg("n_wheels"),
        "The vehicle's constant matrices over u = [Y_A per wheel, (z, phi) per body] "
        "(vehicle.hpp): {'K' [N/m], 'C' [N s/m]: sum k g g^T, sum c g g^T over the suspensions; "
        "'mass': the bodies' masses [kg] and pitch inertias [kg m^2], the wheels' entries 0; 'G': "
        "the bodies' weights and loads [N]}");
  m.def("static_bodies", &static_bodies_of, py::arg("vehicle"), py::arg("y_wheels"),
        "[z_0, phi_0, z_1, phi_1, ...] [m, rad] of the bodies in static equilibrium above wheel "
        "centres held at heights y_wheels [m]: the bodies' rows of K_v u = -G (vehicle.hpp)");
}

}  // namespace trackwheel::bindings
