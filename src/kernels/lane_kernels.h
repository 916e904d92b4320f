// The wavefront's kernels that run in SIMD lanes, over a chunk of a wave: camera rays
// (scene/camera_ray-inl.h), the uniform numbers of each vertex (render/sampler-inl.h), the light
// samples towards quad lights (shading/quad_light_nee-inl.h) and the continuation of the
// Lambertian vertices (shading/lambertian_step-inl.h). The formulas are the ones the megakernel
// runs in one lane; these run them a vector at a time, on the best target the CPU has
// (Highway's dynamic dispatch), with the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "shading/path_vertex.h"
#include "wavetrace/render/sampler.h"
#include "wavetrace/scene/camera.h"

namespace wavetrace {

// Entries the kernels gather before they run a vector kernel over them: a multiple of every
// target's lane count, and small enough that the blocks below stay in L1.
inline constexpr size_t kShadeChunk = 64;

// Camera rays of kShadeChunk pixels.
struct CameraRayBlock {
    alignas(64) float o[3][kShadeChunk];
    alignas(64) float d[3][kShadeChunk];
};

// Rows k < n of `out`: generate_camera_ray(camera, seed, pixel[k], sample, x[k], y[k]), bit for
// bit.
void draw_camera_rays(const CameraRays& camera,
                      uint64_t seed,
                      uint32_t sample,
                      const uint32_t* pixel,
                      const float* x,
                      const float* y,
                      size_t n,
                      CameraRayBlock& out);

// The bounce's uniform numbers of kShadeChunk paths, one row per BounceDim (the medium
// distance row is not drawn: segment_flight draws it when the scene has media).
struct SampleBlock {
    alignas(64) float u[kBounceDims][kShadeChunk];

    VertexSamples at(size_t k) const {
        return {u[kDimLightSelect][k],
                u[kDimLightU][k],
                u[kDimLightV][k],
                {u[kDimTechnique][k], u[kDimDirectionSelect][k], u[kDimDirectionU][k],
                 u[kDimDirectionV][k], u[kDimBsdfLobe][k], u[kDimBsdfU][k], u[kDimBsdfV][k]},
                u[kDimRoulette][k]};
    }
};

// Rows k < n of `out`: vertex_samples(seed, pixel[k], sample, bounce[k]), bit for bit.
void draw_vertex_samples(uint64_t seed,
                         uint32_t sample,
                         const uint32_t* pixel,
                         const uint16_t* bounce,
                         size_t n,
                         SampleBlock& out);

// Lambertian vertices gathered by shade (SoA, `n` of them), and their continuations.
struct LambertianBlock {
    // in
    alignas(64) float p[3][kShadeChunk];
    alignas(64) float ng[3][kShadeChunk];
    alignas(64) float ns[3][kShadeChunk];
    alignas(64) float wo[3][kShadeChunk];
    alignas(64) float albedo[3][kShadeChunk];
    alignas(64) float beta[3][kShadeChunk];
    alignas(64) float u1[kShadeChunk], u2[kShadeChunk], u_rr[kShadeChunk];
    alignas(64) float roulette[kShadeChunk];  // 1: Russian roulette applies
    uint32_t entry[kShadeChunk];              // the wave entry of each row
    size_t n = 0;
    // out
    alignas(64) float origin[3][kShadeChunk];
    alignas(64) float wi[3][kShadeChunk];
    alignas(64) float weight[3][kShadeChunk];
    alignas(64) float pdf[kShadeChunk];
    alignas(64) float alive[kShadeChunk];  // 1: the path goes on

    // Appends the vertex of wave entry `entry`, which takes_lambertian_step().
    void push(size_t entry,
              const Vertex& v,
              Vec3 wo,
              Color beta,
              const ContinuationSamples& u,
              float u_roulette,
              bool roulette);
};

// Rows k < b.n: what continue_path computes for them, bit for bit.
void lambertian_steps(LambertianBlock& b);

// Lambertian vertices whose light sample picked a quad light (quad_light_sample_at), gathered
// by shade with their light (SoA, `n` of them), and their shadow rays.
struct QuadLightBlock {
    // in
    alignas(64) float p[3][kShadeChunk];
    alignas(64) float ng[3][kShadeChunk];
    alignas(64) float ns[3][kShadeChunk];
    alignas(64) float wo[3][kShadeChunk];
    alignas(64) float albedo[3][kShadeChunk];
    alignas(64) float beta[3][kShadeChunk];
    alignas(64) float u1[kShadeChunk], u2[kShadeChunk];
    alignas(64) float q[3][kShadeChunk];  // the light of each row (QuadEmitter)
    alignas(64) float u[3][kShadeChunk];
    alignas(64) float v[3][kShadeChunk];
    alignas(64) float n[3][kShadeChunk];
    alignas(64) float radiance[3][kShadeChunk];
    alignas(64) float area[kShadeChunk], select_prob[kShadeChunk], two_sided[kShadeChunk];
    uint32_t entry[kShadeChunk];  // the wave entry of each row
    size_t rows = 0;
    // out
    alignas(64) float origin[3][kShadeChunk];
    alignas(64) float wi[3][kShadeChunk];
    alignas(64) float contribution[3][kShadeChunk];  // beta f |cos| Le / p_light times the weight
    alignas(64) float tmax[kShadeChunk];
    alignas(64) float valid[kShadeChunk];  // 1: append the shadow ray (weight > 0)

    void push(size_t entry,
              const Vertex& vertex,
              Vec3 wo,
              Color beta,
              float u1,
              float u2,
              const QuadEmitter& light,
              float select_prob);
};

// Rows k < b.rows: what next_event computes for them, bit for bit, times their beta.
void quad_light_samples(QuadLightBlock& b, bool mis, MisHeuristic heuristic);

}  // namespace wavetrace
