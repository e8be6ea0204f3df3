// The compiled module trackwheel._core: its limits and the binding files by concept, in the order
// that registers every type before a signature names it; the test-only probes and benchmark
// hooks in its submodule _core.testing, apart from the public surface.
#include "common.hpp"
#include "limits.hpp"

namespace py = pybind11;
using namespace trackwheel::bindings;
namespace limits = trackwheel::limits;

PYBIND11_MODULE(_core, m) {
  m.doc() = "trackwheel C++ kernel (ANCF rail, supports, contact, statics, eigen analysis)";
  m.attr("MAX_ELEMENTS") = limits::kMaxElements;
  m.attr("MAX_DENSE_EIGEN_DOF") = limits::kMaxDenseEigenDof;
  m.attr("GAUSS_RANGE") = py::make_tuple(limits::kMinGauss, limits::kMaxGauss);
  m.attr("MAX_SPEED") = limits::kMaxSpeed;
  m.attr("MAX_SUPPORTS") = limits::kMaxSupports;
  bind_track(m);
  bind_vehicle(m);
  bind_statics(m);
  bind_eigen(m);
  bind_dynamics(m);
  bind_linear(m);
  bind_frequency(m);
  py::module_ t = m.def_submodule(
      "testing",
      "Test-only probes and benchmark hooks of the kernel (not public API: names and signatures "
      "may change with the kernel)");
  bind_testing_elements(t);
  bind_testing_solvers(t);
}
