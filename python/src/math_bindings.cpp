// Transforms for the builders.
#include <pybind11/operators.h>

#include "casters.h"
#include "wavetrace/math/transform.h"

namespace wavetrace::python {

void bind_math(py::module_& m) {
    py::class_<Transform>(m, "Transform",
                          "An affine transform; a * b applies b first. The identity by default.")
        .def(py::init<>())
        .def_static("translate", &Transform::translate, py::arg("offset"))
        .def_static(
            "scale",
            [](const py::object& s) {
                Vec3 v = py::isinstance<py::sequence>(s) ? s.cast<Vec3>() : Vec3(s.cast<float>());
                if (v.x == 0 || v.y == 0 || v.z == 0)
                    throw py::value_error("scale: every component must be non-zero");
                return Transform::scale(v);
            },
            py::arg("factor"), "Scales by a number or per axis (x, y, z).")
        .def_static(
            "rotate",
            [](Vec3 axis, float degrees) {
                if (axis.x == 0 && axis.y == 0 && axis.z == 0)
                    throw py::value_error("rotate: the axis must not be zero");
                return Transform::rotate(axis, degrees);
            },
            py::arg("axis"), py::arg("degrees"),
            "Rotation by `degrees` about `axis`, right-handed (counter-clockwise seen from its tip).")
        .def_static(
            "matrix",
            [](const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
                if (a.ndim() != 2 || a.shape(1) != 4 || (a.shape(0) != 3 && a.shape(0) != 4))
                    throw py::value_error("matrix: expected a 3 x 4 or 4 x 4 array");
                double rows[3][4];
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 4; ++c) rows[r][c] = a.at(r, c);
                Transform t;
                if (!Transform::affine(rows, &t))
                    throw py::value_error("matrix: singular or not finite");
                return t;
            },
            py::arg("rows"), "The affine map of a row-major 3 x 4 (or 4 x 4) matrix [L | t].")
        .def(py::self * py::self)
        .def("point", &Transform::point, py::arg("p"))
        .def("vector", &Transform::vector, py::arg("v"))
        .def("inverse", &Transform::inverse);
}

}  // namespace wavetrace::python
