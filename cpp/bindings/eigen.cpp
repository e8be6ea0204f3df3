// Bindings of the eigen analysis: the coupled wheel/rail/support modes (dense) and the pencils
// of one direction that the partial (sparse) solver of trackwheel.eigen takes.
#include "common.hpp"
#include "eigen_analysis.hpp"

namespace trackwheel::bindings {

namespace {

// (frequencies (n_pos, n_modes) [Hz], shapes (n_pos, n_coordinates, n_modes))
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

py::tuple vertical_modes_of(const RailModel& rail, double M, double k, const std::vector<double>& x,
                            int n_modes) {
  ModalResult r;
  {
    py::gil_scoped_release nogil;
    r = vertical_modes(rail, M, k, x, n_modes);
  }
  return modal_to_tuple(r);
}

py::dict direction_pencil_of(const RailModel& rail, int component, double M, double k, double x) {
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
}

}  // namespace

void bind_eigen(py::module_& m) {
  m.def("vertical_modes", &vertical_modes_of, py::arg("rail"), py::arg("wheel_mass"),
        py::arg("contact_stiffness"), py::arg("positions"), py::arg("n_modes"),
        "Vertical modes of the rail with the wheel (mass M [kg] on the contact spring k [N/m]) at "
        "each position [m]: (frequencies (n_pos, n_modes) [Hz], shapes (n_pos, n_dof + 1 + "
        "n_sleepers, n_modes))");
  m.def(
      "axial_modes",
      [](const RailModel& rail, int n_modes) { return modal_to_tuple(axial_modes(rail, n_modes)); },
      py::arg("rail"), py::arg("n_modes"),
      "Axial modes of the rail: (frequencies (1, n_modes) [Hz], shapes (1, n_dof, n_modes))");
  m.def("direction_pencil", &direction_pencil_of, py::arg("rail"), py::arg("component"),
        py::arg("wheel_mass") = 0.0, py::arg("contact_stiffness") = 0.0, py::arg("position") = 0.0,
        "K [N/m], M [kg], C [N s/m] of one direction (0: x, 1: y with the wheel if wheel_mass > "
        "0) at the straight reference as triplets {n, dofs, row, col, K, M, C} over local "
        "coordinates (the direction's free coordinates, full indices in dofs, then the wheel's "
        "Y_w and the sleepers' z_j on layered supports)");
}

}  // namespace trackwheel::bindings
