// The one way to render light transport: a request (size, samples, estimator, engine) into a
// film, watched by an observer that sees progress and may stop the render between passes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "wavetrace/film/film.h"
#include "wavetrace/sampling/sampler.h"
#include "wavetrace/shading/estimator.h"

namespace wavetrace {

struct Scene;
class Bvh;

// The data-oriented wavefront engine (the product) or the recursive megakernel it is checked
// and benchmarked against: the same paths from the same seed, the same image up to rounding.
enum class Engine { Wavefront, Megakernel };

const char* to_string(Engine e);
std::optional<Engine> parse_engine(const std::string& name);

// How the wavefront's threads share its kernels (the image is the same either way, bit for bit):
// - Resident: each thread carries a wave of its own through every kernel, bounce after bounce,
//   so that the wave's queues stay in its core's cache.
// - Stage: one wave for all threads, each kernel a parallel loop over it, the threads meeting
//   between kernels (pbrt-v4's CPU wavefront).
enum class Schedule { Resident, Stage };

const char* to_string(Schedule s);
std::optional<Schedule> parse_schedule(const std::string& name);

struct WavefrontOptions {
    // Most paths a thread carries through the kernels at once (a wave holds consecutive pixels,
    // at most 1/64 of the image, and as many samples of each as fill it; the waves shrink
    // towards the end of a pass). 4096 paths keep a wave's queues within a core's L2 cache.
    // The stage schedule's one wave holds as many paths as all the threads' waves together.
    size_t wave_size = 4096;
    Schedule schedule = Schedule::Resident;
    // Whether each bounce's entries are reordered by material kind before shading. Off: shade
    // gathers the vertices its SIMD kernels run over by itself, which costs less. The image is
    // the same either way.
    bool sort_by_material = false;
};

// The wavefront's queue memory per path in flight (bytes), from the queue declarations: a
// thread holds a wave of at most WavefrontOptions::wave_size paths.
size_t wavefront_bytes_per_path();

struct RenderRequest {
    int width = 0;
    int height = 0;
    // The samples rendered are [first_sample, first_sample + spp) of each pixel's sequence:
    // rendering [0, k) and then [k, n) into one film gives the film of [0, n), bit for bit.
    int spp = 1;
    int first_sample = 0;
    uint64_t seed = 0;
    SamplerKind sampler = SamplerKind::Sobol;
    // ZSobol lays each pixel's samples out in a block of the one sequence, sized for a sample
    // count (rounded up to a power of two): this one, or 0 for first_sample + spp. Parts of
    // one render (a resume to more samples, sample ranges) state the whole render's count.
    int sampler_spp = 0;
    Estimator estimator;
    Engine engine = Engine::Wavefront;
    WavefrontOptions wavefront;  // read by the wavefront engine only
    // With an observer, a render runs in passes of one or more samples of every pixel: the
    // first one sample, the later ones about this long. Long enough that the threads seldom
    // wait on each other, short enough to stop or checkpoint promptly. Without an observer the
    // render is one pass.
    double pass_seconds = 0.5;
    // Seconds after which no pass starts (0: none): the render stops at the first pass
    // boundary after them, every pixel holding the same samples; the first pass (one sample)
    // is always rendered. A time limit cuts the render into passes as an observer does.
    double time_limit = 0;
};

struct RenderStats {
    double seconds = 0;
    uint64_t paths = 0;  // camera samples
    uint64_t rays = 0;   // every ray traced, shadow rays and medium-boundary steps included
    int spp_done = 0;    // samples per pixel added: request.spp unless stopped
};

// Watches a render; both methods have defaults that do nothing.
class RenderObserver {
  public:
    virtual ~RenderObserver() = default;
    // Before each pass and once after the last, on the thread that called render(), while no
    // sample is being added: the film may be read (a preview, a checkpoint). `samples_done` of
    // `samples_requested` per pixel are in it. Returning false stops the render here, so that
    // every pixel holds the same number of samples (the return value after the last pass is
    // ignored).
    virtual bool on_pass(int samples_done, int samples_requested, const Film& film);
    // Now and then during a pass, from worker threads (concurrently: keep it cheap and
    // thread-safe): the fraction of the requested samples done.
    virtual void on_progress(double fraction);
};

// What must match for two films to be parts of one render (FilmInfo::settings): the scene's
// fingerprint (e.g. fnv1a_64 of its file; 0 for a scene built in code), the image size and
// every request setting that changes the samples, as "key=value" lines.
std::string film_settings(uint64_t scene_fingerprint, const RenderRequest& request);

// The sampler a request's samples come from.
Sampler request_sampler(const RenderRequest& request);

// Renders the request's samples into `film` (of the request's size), after those it holds.
// The image does not depend on the thread count, the wave size or how the passes fell.
RenderStats render(const Scene& scene,
                   const Bvh& bvh,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer = nullptr);

}  // namespace wavetrace
