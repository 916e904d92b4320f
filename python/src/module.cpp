// The `wavetrace._wavetrace` extension module: the C++ library's API, bound with pybind11.
// The pure-Python package around it (python/wavetrace/) adds the progress bar and result types.
#include "casters.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/build_info.h"
#include "wavetrace/film/film_file.h"

PYBIND11_MODULE(_wavetrace, m) {
    using namespace wavetrace;
    m.doc() = "wavetrace: a data-oriented wavefront path tracer (C++ core)";
    py::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);
    py::register_exception<FilmError>(m, "FilmError", PyExc_ValueError);
    py::register_exception<ImageError>(m, "ImageError", PyExc_OSError);
    const BuildInfo info = build_info();
    m.attr("__version__") = info.version;
    m.def("simd_target", &simd_target, "The SIMD target the kernels run on this CPU.");
    python::bind_math(m);
    python::bind_scene(m);
    python::bind_film(m);
    python::bind_render(m);
    python::bind_bvh(m);
    python::bind_image(m);
}
