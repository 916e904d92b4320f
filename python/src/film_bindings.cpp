// Films: a render's per-pixel sums, saved, loaded and merged as the CLI's film files are.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <variant>

#include "casters.h"
#include "py_film.h"

namespace wavetrace::python {
namespace {

// A copy of a film held by Python (Film itself is move-only).
PyFilm copy_of(const PyFilm& f) {
    PyFilm c{f.name, Film(f.film.width(), f.film.height()), f.info};
    c.film.merge(f.film);
    return c;
}

}  // namespace

void bind_film(py::module_& m) {
    py::class_<PyFilm>(m, "Film",
                       "Per-pixel sums of a render's samples with what they are of: render into "
                       "one (render(..., film=f)) to keep or resume the render, save and load it "
                       "as the CLI's film files (docs/film-format.md), merge parts of a render.")
        .def(py::init([] { return PyFilm{"film", Film(), FilmInfo{}}; }),
             "An empty film: the first render into it sets its size and settings.")
        .def_property_readonly("width", [](const PyFilm& f) { return f.film.width(); })
        .def_property_readonly("height", [](const PyFilm& f) { return f.film.height(); })
        .def_property_readonly("spp", [](const PyFilm& f) { return f.info.samples(); },
                               "Samples per pixel it holds.")
        .def_property_readonly(
            "ranges",
            [](const PyFilm& f) {
                py::list l;
                for (const SampleRange& r : f.info.ranges) l.append(py::make_tuple(r.first, r.end()));
                return l;
            },
            "The sample ranges [first, end) of each pixel's sequence that it holds.")
        .def_property_readonly("settings", [](const PyFilm& f) { return f.info.settings; },
                               "What must match for films to be parts of one render.")
        .def_property_readonly("invalid_samples",
                               [](const PyFilm& f) { return f.film.invalid_samples(); })
        .def("mean", [](const PyFilm& f) { return to_array(f.film.mean()); },
             "The image: each pixel's mean, float32 (height, width, 3).")
        .def("variance", [](const PyFilm& f) { return to_array(f.film.variance_of_mean()); },
             "The variance of each pixel's mean, per channel, float32 (height, width, 3).")
        .def("save",
             [](const PyFilm& f, const std::filesystem::path& path) {
                 if (is_fresh(f)) throw FilmError("an empty film: render into it first");
                 py::gil_scoped_release release;
                 save_film(path, f.film, f.info);
             },
             py::arg("path"), "Writes the film file atomically.")
        .def_static(
            "load",
            [](const std::filesystem::path& path) {
                py::gil_scoped_release release;
                auto [film, info] = load_film(path);
                return PyFilm{path.string(), std::move(film), std::move(info)};
            },
            py::arg("path"), "Reads a film file (the CLI's --film), checking it whole.")
        .def_static(
            "merge",
            [](const std::vector<std::variant<std::filesystem::path, const PyFilm*>>& parts) {
                std::vector<PyFilm> films;
                for (const auto& p : parts) {
                    if (const auto* path = std::get_if<std::filesystem::path>(&p)) {
                        py::gil_scoped_release release;
                        auto [film, info] = load_film(*path);
                        films.push_back({path->string(), std::move(film), std::move(info)});
                    } else {
                        const PyFilm* f = std::get<const PyFilm*>(p);
                        if (is_fresh(*f)) throw FilmError("an empty film cannot be merged");
                        films.push_back(copy_of(*f));
                        films.back().name = "film " + std::to_string(films.size());
                    }
                }
                py::gil_scoped_release release;
                auto [film, info] = merge_films(std::move(films));
                return PyFilm{"merged film", std::move(film), std::move(info)};
            },
            py::arg("parts"),
            "Merges parts of one render (films or film files; same settings, disjoint sample "
            "ranges) in order of their first sample, as `wavetrace merge` does.")
        .def("__repr__", [](const PyFilm& f) {
            return "<wavetrace.Film " + std::to_string(f.film.width()) + "x" +
                   std::to_string(f.film.height()) + ", " + std::to_string(f.info.samples()) +
                   " spp>";
        });
}

}  // namespace wavetrace::python
