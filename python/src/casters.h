// What the bindings share: vectors as Python sequences, keyword construction of plain records,
// and images as NumPy arrays that own their pixels.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <utility>

#include "wavetrace/image/image.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/scene.h"

namespace py = pybind11;

namespace pybind11::detail {

// Vec3 (points, vectors, normals, colours) from any sequence of three numbers, to a tuple.
template <>
struct type_caster<wavetrace::Vec3> {
    PYBIND11_TYPE_CASTER(wavetrace::Vec3, const_name("tuple[float, float, float]"));
    bool load(handle src, bool convert) {
        if (!src || !py::isinstance<py::sequence>(src) || py::isinstance<py::str>(src))
            return false;
        auto seq = py::reinterpret_borrow<py::sequence>(src);
        if (seq.size() != 3) return false;
        for (int i = 0; i < 3; ++i) {
            make_caster<float> c;
            if (!c.load(seq[i], convert)) return false;
            value[i] = cast_op<float>(c);
        }
        return true;
    }
    static handle cast(wavetrace::Vec3 v, return_value_policy, handle) {
        return py::make_tuple(v.x, v.y, v.z).release();
    }
};

}  // namespace pybind11::detail

namespace wavetrace::python {

// A constructor taking any of the record's attributes as keywords: Sphere(center=..., radius=1).
template <class T, class... Options>
void keyword_init(py::class_<T, Options...>& cls) {
    cls.def(py::init([](const py::kwargs& kwargs) {
                py::object self = py::cast(T{});
                for (auto item : kwargs) {
                    const std::string key = py::str(item.first);
                    if (key.starts_with("_") || !py::hasattr(self, item.first))
                        throw py::type_error(std::string(py::str(py::type::of(self).attr("__name__"))) +
                                             ": no attribute '" + key + "'");
                    py::setattr(self, item.first, item.second);
                }
                return self.cast<T>();
            }),
            "Every attribute may be given as a keyword; the others keep their defaults.");
}

// An image's pixels as a float32 array of shape (height, width, 3) that owns them: moved, not
// copied.
inline py::array_t<float> to_array(Image image) {
    static_assert(sizeof(Color) == 3 * sizeof(float));
    auto* pixels = new std::vector<Color>(std::move(image.pixels));
    py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<Color>*>(p); });
    const py::ssize_t w = image.width, h = image.height, f = sizeof(float);
    return py::array_t<float>({h, w, py::ssize_t(3)}, {w * 3 * f, 3 * f, f},
                              reinterpret_cast<const float*>(pixels->data()), owner);
}

// An array of shape (height, width, 3) or (height, width) (grey) as an Image; `what` names it in
// errors.
inline Image to_image(const py::array_t<float, py::array::c_style | py::array::forcecast>& a,
                      const char* what) {
    if (!(a.ndim() == 3 && a.shape(2) == 3) && a.ndim() != 2)
        throw py::value_error(std::string(what) +
                              ": expected an array of shape (height, width, 3) or (height, width)");
    if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > kMaxImageSide ||
        a.shape(1) > kMaxImageSide)
        throw py::value_error(std::string(what) + ": each side must be 1.." +
                              std::to_string(kMaxImageSide) + " pixels");
    Image image(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    const float* src = a.data();
    const bool grey = a.ndim() == 2;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = grey ? Color(src[i]) : Color(src[3 * i], src[3 * i + 1], src[3 * i + 2]);
    return image;
}

void bind_math(py::module_& m);
void bind_scene(py::module_& m);
void bind_render(py::module_& m);
void bind_film(py::module_& m);
void bind_bvh(py::module_& m);
void bind_image(py::module_& m);

}  // namespace wavetrace::python
