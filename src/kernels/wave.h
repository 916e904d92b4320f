// The data a wave's kernels work on: read-only inputs and the queues. Each kernel is a free
// function over a range of queue entries (or path slots) that reads and writes only the
// entries in its range, so a thin parallel_for over ranges runs it on any number of threads
// with the same result.
#pragma once

#include <cstdint>
#include <vector>

#include "queues/path_state.h"
#include "queues/ray_queue.h"
#include "queues/shadow_queue.h"
#include "wavetrace/render/film.h"
#include "wavetrace/render/render.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/lights.h"

namespace wavetrace {

// The intersector is not among them: the kernels that trace rays take it as a template
// parameter (kernels/intersect.h, kernels/intersect_shadow.h).
struct WaveInputs {
    const Scene& scene;
    const LightSet& lights;
    const RenderConfig& config;
    const CameraRays& camera;
    MediumStack camera_media;
};

struct WaveQueues {
    PathState paths;                   // per path slot
    RayQueue rays;                     // the current bounce's rays, compacted
    RayQueue next_rays;                // compaction target (swapped with `rays` after each bounce)
    HitQueue hits;                     // rays' closest hits, entry for entry
    ScatterQueue scatter;              // vertices to light-sample, entry for entry
    ShadowQueue shadow_candidates;     // entry for entry; `shadow_keep` marks the real ones
    ShadowQueue shadow;                // compacted shadow rays
    std::vector<uint8_t> keep;         // 1: the ray entry's path goes on
    std::vector<uint8_t> shadow_keep;  // 1: the entry made a shadow ray
    std::vector<uint32_t> order;       // ray entries bucketed by material kind
    std::vector<uint32_t> compacted;   // compaction output indices
    std::vector<uint32_t> bucket_scratch;

    void resize(size_t wave_size);
    // Bytes of queue memory per path in flight, from the queues' field declarations.
    static size_t bytes_per_path();
};

}  // namespace wavetrace
