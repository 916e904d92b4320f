// The data a wave's kernels work on: read-only inputs and one thread's queues. A wave is a
// range of pixels, with one or several samples of each, that a thread carries through every stage,
// while it stays in that core's cache; each kernel is a free function over a range of queue
// entries, taking the queues it reads const and the queues it writes mutable.
#pragma once

#include <cstdint>
#include <vector>

#include "queues/emission_queue.h"
#include "queues/light_sample_queue.h"
#include "queues/path_state.h"
#include "queues/ray_queue.h"
#include "queues/shadow_queue.h"
#include "shading/lights.h"
#include "wavetrace/film/film.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/estimator.h"

namespace wavetrace {

// The intersector is not among them: the kernels that trace rays take it as a template
// parameter (kernels/intersect.h, kernels/intersect_shadow.h).
struct WaveInputs {
    const Scene& scene;
    const LightSet& lights;
    const Estimator& estimator;
    Sampler sampler;
    int width, height;  // of the image
    const CameraRays& camera;
    MediumStack camera_media;
    bool shadows_walk = true;  // shadows_walk(scene): shadow rays need more than an occlusion test
};

// The samples a wave carries of each of its pixels: [first, first + per_pixel), side by side
// (a small image's wave holds several samples of a pixel, so that it is as large, and its
// paths as coherent, as a large image's).
struct WaveSamples {
    uint32_t first = 0;
    uint32_t per_pixel = 1;
};

// The radiance of a wave's paths, per slot (pixel times per_pixel plus sample), held until the
// wave's last path ends: a pixel's samples end in any order, and the film must receive them in
// sample order.
struct WaveFilm {
    std::vector<Color> radiance;
};

// Entries [begin, end) of a queue.
struct EntryRange {
    size_t begin = 0, end = 0;
};

// Entry i of paths, rays and hits belongs to one path; the entries of the appended queues
// (light samples, shadows, emission) name theirs. Each holds one entry per path at most.
struct WaveQueues {
    PathQueue paths;
    RayQueue rays;
    HitQueue hits;
    LightSampleQueue light_samples;
    ShadowQueue shadows;
    EmissionQueue emissions;
    std::vector<Color> transmittance;  // per shadow entry, from intersect_shadow
    std::vector<uint8_t> keep;         // per entry: 1 if the path goes on after shading
    std::vector<uint8_t> key;          // per entry: sort_by_material's scratch
    WaveFilm film;                     // per entry at generation

    void resize(size_t wave_size);
    // Bytes of queue memory per path in flight, from the queues' field declarations.
    static constexpr size_t bytes_per_path() {
        return PathQueue::kBytesPerEntry + RayQueue::kBytesPerEntry + HitQueue::kBytesPerEntry +
               LightSampleQueue::kBytesPerEntry + ShadowQueue::kBytesPerEntry +
               EmissionQueue::kBytesPerEntry + 2 * sizeof(Color) + 2 * sizeof(uint8_t);
    }
};

}  // namespace wavetrace
