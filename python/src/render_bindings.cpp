// Rendering from Python: the library's render() (or an AOV) into a film, with the GIL released
// and Python's signals and progress callback served between passes.
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <optional>

#include "casters.h"
#include "py_film.h"
#include "py_scene.h"
#include "wavetrace/engines/aov.h"
#include "wavetrace/engines/render.h"

namespace wavetrace::python {
namespace {

// Between passes, on the thread that called render(): takes the GIL, runs Python's signal
// handlers (a SIGINT raises KeyboardInterrupt there) and the progress callback; either one
// raising stops the render at this pass boundary.
class PythonObserver : public RenderObserver {
  public:
    explicit PythonObserver(py::object progress) : progress_(std::move(progress)) {}

    bool on_pass(int done, int requested, const Film&) override {
        py::gil_scoped_acquire gil;
        try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!progress_.is_none()) {
                py::object go_on = progress_(done, requested);
                if (!go_on.is_none() && !py::bool_(go_on)) {
                    stopped_ = true;
                    return false;
                }
            }
        } catch (py::error_already_set& e) {
            error_ = std::move(e);
            return false;
        }
        return true;
    }

    // After render() returned, with the GIL held: whether a KeyboardInterrupt stopped it; any
    // other exception is raised.
    bool interrupted() {
        if (!error_) return false;
        if (error_->matches(PyExc_KeyboardInterrupt)) return true;
        throw std::move(*error_);
    }
    bool stopped() const { return stopped_; }

  private:
    py::object progress_;
    std::optional<py::error_already_set> error_;
    bool stopped_ = false;
};

int checked(const char* name, std::optional<long long> value, int fallback, long long lo, long long hi) {
    const long long v = value.value_or(fallback);
    if (v < lo || v > hi)
        throw py::value_error(std::string(name) + ": expected " + std::to_string(lo) + ".." +
                              std::to_string(hi) + ", got " + std::to_string(v));
    return static_cast<int>(v);
}

template <class T>
T parsed(const char* name, const std::string& value, std::optional<T> result) {
    if (!result) throw py::value_error(std::string(name) + ": unknown value '" + value + "'");
    return *result;
}

py::dict stats_dict(const RenderStats& st) {
    py::dict d;
    d["seconds"] = st.seconds;
    d["paths"] = st.paths;
    d["rays"] = st.rays;
    d["spp"] = st.spp_done;
    return d;
}

// The C++ half of wavetrace.render(): returns (image, variance or None, stats, interrupted).
py::tuple render_scene(const std::shared_ptr<PyScene>& s,
                       std::optional<long long> spp,
                       std::optional<long long> width,
                       std::optional<long long> height,
                       const std::string& engine,
                       const std::string& strategy,
                       const std::string& mis_heuristic,
                       uint64_t seed,
                       int threads,
                       std::optional<long long> max_depth,
                       std::optional<long long> sample_offset,
                       double time_limit,
                       std::optional<long long> wave_size,
                       const std::string& schedule,
                       bool sort_by_material,
                       const std::string& aov,
                       const py::object& progress,
                       bool variance,
                       PyFilm* film,
                       const std::optional<std::string>& sampler,
                       std::optional<long long> sampler_spp) {
    const Scene& scene = s->scene;
    const int w = checked("width", width, scene.render.width, 1, kMaxImageSide);
    const int h = checked("height", height, scene.render.height, 1, kMaxImageSide);
    if (static_cast<long long>(w) * h > kMaxPixels)
        throw py::value_error("width x height: more than " + std::to_string(kMaxPixels) + " pixels");
    const int samples = checked("spp", spp, aov == "color" ? scene.render.spp : 1, 1, kMaxSpp);
    if (threads < 0) throw py::value_error("threads: expected a positive count (0: all)");
    if (!(time_limit >= 0 && time_limit < 1e9))
        throw py::value_error("time_limit: expected a positive number of seconds");
    std::optional<tbb::global_control> parallelism;
    if (threads > 0) parallelism.emplace(tbb::global_control::max_allowed_parallelism, threads);

    if (aov != "color") {
        std::optional<Aov> which;
        if (aov == "albedo") which = Aov::Albedo;
        if (aov == "normal") which = Aov::Normal;
        if (aov == "depth") which = Aov::Depth;
        const Aov kind = parsed("aov", aov, which);
        if (film || variance) throw py::value_error("film and variance: only for aov='color'");
        Image image;
        {
            InUse use(*s);
            py::gil_scoped_release release;
            image = render_aov(scene, *s->bvh(), kind, AovSettings{w, h, samples, seed});
        }
        return py::make_tuple(to_array(std::move(image)), py::none(), py::dict(), false);
    }

    RenderRequest request;
    request.width = w;
    request.height = h;
    request.spp = samples;
    request.seed = seed;
    request.sampler =
        sampler ? parsed("sampler", *sampler, parse_sampler(*sampler)) : scene.render.sampler;
    request.engine = parsed("engine", engine, parse_engine(engine));
    request.estimator.strategy = parsed("strategy", strategy, parse_strategy(strategy));
    if (mis_heuristic != "power" && mis_heuristic != "balance")
        throw py::value_error("mis_heuristic: unknown value '" + mis_heuristic + "'");
    request.estimator.heuristic =
        mis_heuristic == "balance" ? MisHeuristic::Balance : MisHeuristic::Power;
    request.estimator.max_depth = checked("max_depth", max_depth, scene.render.max_depth, 1, kMaxDepth);
    if (wave_size) request.wavefront.wave_size = checked("wave_size", wave_size, 0, 1, 1 << 26);
    request.wavefront.schedule = parsed("schedule", schedule, parse_schedule(schedule));
    request.wavefront.sort_by_material = sort_by_material;
    request.time_limit = time_limit;
    request.sampler_spp =
        checked("sampler_spp", sampler_spp,
                std::min<long long>(kMaxSpp, sample_offset.value_or(0) + samples), 1, kMaxSpp);

    // Samples [first, first + spp): from sample_offset, or after those the film holds.
    const std::string settings = film_settings(s->fingerprint, request);
    int first = checked("sample_offset", sample_offset, 0, 0, (1LL << 31) - kMaxSpp);
    PyFilm local{"film", Film(), FilmInfo{}};
    PyFilm& target = film ? *film : local;
    if (is_fresh(target)) {
        target.film = Film(w, h);
        target.info = FilmInfo{settings, {}};
    } else {
        const std::string diff = settings_difference(target.info.settings, settings);
        if (!diff.empty()) throw FilmError("film: the film of another render (" + diff + ")");
        const auto& ranges = target.info.ranges;
        if (ranges.size() > 1)
            throw FilmError("film: holds several sample ranges; merge parts with Film.merge");
        if (!ranges.empty()) {
            if (sample_offset && *sample_offset != ranges[0].end())
                throw FilmError("film: holds samples up to " + std::to_string(ranges[0].end()) +
                                "; a render into it continues there, not at sample_offset " +
                                std::to_string(*sample_offset));
            first = static_cast<int>(ranges[0].end());
        }
    }
    request.first_sample = first;

    PythonObserver observer(progress);
    RenderStats stats;
    {
        InUse use(*s);
        py::gil_scoped_release release;
        stats = render(scene, *s->bvh(), request, target.film, &observer);
    }
    const bool interrupted = observer.interrupted();
    if (stats.spp_done > 0) {
        auto& ranges = target.info.ranges;
        if (ranges.empty())
            ranges.push_back({uint32_t(first), uint32_t(stats.spp_done)});
        else
            ranges[0].count += uint32_t(stats.spp_done);
    }
    py::object var = variance ? py::object(to_array(target.film.variance_of_mean())) : py::none();
    return py::make_tuple(to_array(target.film.mean()), var, stats_dict(stats), interrupted);
}

}  // namespace

void bind_render(py::module_& m) {
    m.def("_render", &render_scene, py::arg("scene"), py::arg("spp"), py::arg("width"),
          py::arg("height"), py::arg("engine"), py::arg("strategy"), py::arg("mis_heuristic"),
          py::arg("seed"), py::arg("threads"), py::arg("max_depth"), py::arg("sample_offset"),
          py::arg("time_limit"), py::arg("wave_size"), py::arg("schedule"),
          py::arg("sort_by_material"), py::arg("aov"), py::arg("progress"), py::arg("variance"),
          py::arg("film").none(true), py::arg("sampler").none(true),
          py::arg("sampler_spp").none(true));
}

}  // namespace wavetrace::python
