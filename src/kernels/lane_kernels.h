// The wavefront's kernels that run in SIMD lanes, over a chunk of a wave: camera rays
// (scene/camera_ray-inl.h), the uniform numbers of each vertex (sampling/sampler-inl.h), the
// points and normals of surface hits (shading/surface_point-inl.h), the light samples towards quad
// lights (shading/quad_light_nee-inl.h) and the continuation (shading/surface_step-inl.h) of
// Lambertian and rough metal vertices. The formulas are the ones the megakernel
// runs in one lane; these run them a vector at a time, on the best target the CPU has
// (Highway's dynamic dispatch), with the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sampling/sampler.h"
#include "shading/path_vertex.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/shapes.h"

namespace wavetrace {

// Entries the kernels gather before they run a vector kernel over them: a multiple of every
// target's lane count, and small enough that the blocks below stay in L1.
inline constexpr size_t kShadeChunk = 64;

// Row k of three SoA rows (x, y, z) of a block, as a Vec3.
inline Vec3 block_row(const float (*rows)[kShadeChunk], size_t k) {
    return {rows[0][k], rows[1][k], rows[2][k]};
}

// Camera rays of kShadeChunk pixels.
struct CameraRayBlock {
    alignas(64) float o[3][kShadeChunk];
    alignas(64) float d[3][kShadeChunk];
    alignas(64) float flight[kShadeChunk];  // segment_flight(.., 0), where drawn
};

// Rows k < n of `out`: generate_camera_ray(camera, seed, pixel[k], sample, x[k], y[k]), bit for
// bit, and with `flights` (a scene with media) the camera segment's optical depth
// segment_flight(scene, seed, pixel[k], sample, 0).
void draw_camera_rays(const CameraRays& camera,
                      uint64_t seed,
                      uint32_t sample,
                      const uint32_t* pixel,
                      const float* x,
                      const float* y,
                      size_t n,
                      bool flights,
                      CameraRayBlock& out);

// The bounce's uniform numbers of kShadeChunk paths, one row per BounceDim (the medium
// distance row of this bounce is not drawn: its segment has been traced), and the optical depth
// of the segment each vertex starts.
struct SampleBlock {
    alignas(64) float u[kBounceDims][kShadeChunk];
    alignas(64) float next_flight[kShadeChunk];  // segment_flight(.., bounce + 1), where drawn

    VertexSamples at(size_t k) const {
        return vertex_samples_of([&](BounceDim d) { return u[d][k]; });
    }
};

// Rows k < n of `out`: vertex_samples(seed, pixel[k], sample, bounce[k]), bit for bit, and with
// `flights` (a scene with media) segment_flight(scene, seed, pixel[k], sample, bounce[k] + 1).
void draw_vertex_samples(uint64_t seed,
                         uint32_t sample,
                         const uint32_t* pixel,
                         const uint16_t* bounce,
                         size_t n,
                         bool flights,
                         SampleBlock& out);

// The segments of a chunk's paths through their media (SoA, rows k < n): where each path
// scatters on the way to its hit, as scatters_in_medium finds it.
struct MediumSegmentBlock {
    // in: the ray's direction, the hit distance t in units of its length (infinity: a miss),
    // whether the path is in a medium (medium = 1) and its density there
    alignas(64) float dir[3][kShadeChunk];
    alignas(64) float t[kShadeChunk], medium[kShadeChunk], density[kShadeChunk];
    // in: the optical depth left to travel; out: what is left past the segment's end, for the
    // rows that do not scatter
    alignas(64) float flight[kShadeChunk];
    // out: |dir|, whether the path scatters (scatters = 1) and where: the world distance from
    // the ray's origin
    alignas(64) float dir_length[kShadeChunk], scatters[kShadeChunk], dist[kShadeChunk];
};

// Rows k < n of b: scatters_in_medium's result, bit for bit.
void medium_segments(MediumSegmentBlock& b, size_t n);

// Lambertian and rough metal surface vertices, and medium vertices of isotropic phase function,
// gathered by shade (SoA, `n` rows): each row's
// light sample towards a quad light (next_event's, where light[k] >= 0) and its continuation
// (continue_path's, where step[k] = 1), computed in one pass over the rows. A row's vertex is
// either given (p, ng, ns, wo: push) or resolved from its hit on a quad, a triangle or a sphere
// (push_*_hit, then resolve_surface_hits: surface_at's point and normals, resolve_segment's wo).
struct SurfaceBlock {
    // in: the vertices
    alignas(64) float p[3][kShadeChunk];
    alignas(64) float ng[3][kShadeChunk];
    alignas(64) float ns[3][kShadeChunk];
    alignas(64) float wo[3][kShadeChunk];
    alignas(64) float albedo[3][kShadeChunk];
    alignas(64) float alpha[kShadeChunk], metal[kShadeChunk];  // metal = 1: a rough metal
    alignas(64) float phase[kShadeChunk];  // phase = 1: in a medium (ng = 0, ns = +z), isotropic
    alignas(64) float beta[3][kShadeChunk];
    // in: the light sample: the light's index among the LightSet's quad emitters (-1: none),
    // its selection probability and the point on it
    alignas(64) int32_t light[kShadeChunk];
    alignas(64) int32_t sphere_light[kShadeChunk];  // or its index among the sphere emitters
    alignas(64) float select_prob[kShadeChunk], light_u1[kShadeChunk], light_u2[kShadeChunk];
    // in: the continuation (step = 1: take it here), its direction and roulette samples
    alignas(64) float step[kShadeChunk], dir_u1[kShadeChunk], dir_u2[kShadeChunk];
    alignas(64) float u_rr[kShadeChunk], roulette[kShadeChunk];  // roulette = 1: it applies
    uint32_t entry[kShadeChunk];                                 // the wave entry of each row
    // in: the hits of rows whose vertex is resolved here (hit_kind 1: a quad, 2: a triangle,
    // 3: a sphere; 0: the vertex is given): the ray's direction, the hit's (u, v) (sphere: the
    // radius), the corners (quad: q, u, v; triangle: p0, p1, p2; sphere: the hit point o + t d
    // and the centre) and, for triangles of a mesh with normals (smooth = 1), the vertex
    // normals
    alignas(64) int32_t hit_kind[kShadeChunk];
    alignas(64) float dir[3][kShadeChunk];
    alignas(64) float hit_u[kShadeChunk], hit_v[kShadeChunk];
    alignas(64) float corner[3][3][kShadeChunk];
    alignas(64) float vertex_normal[3][3][kShadeChunk];
    alignas(64) float smooth[kShadeChunk];
    size_t n = 0;
    // out: the shadow ray and its contribution beta f |cos| Le / p_light times the weight, for
    // rows with shadow = 1 (a light sample of weight > 0)
    alignas(64) float shadow_origin[3][kShadeChunk];
    alignas(64) float shadow_dir[3][kShadeChunk];
    alignas(64) float contribution[3][kShadeChunk];
    alignas(64) float tmax[kShadeChunk], shadow[kShadeChunk];
    // out: the next ray, the throughput factor and the BSDF density, for rows with alive = 1
    alignas(64) float origin[3][kShadeChunk];
    alignas(64) float wi[3][kShadeChunk];
    alignas(64) float weight[3][kShadeChunk];
    alignas(64) float pdf[kShadeChunk], alive[kShadeChunk];

    // Appends the vertex of wave entry `entry` (is_lane_vertex) with neither a light sample nor
    // a step; returns its row.
    size_t push(size_t entry, const Vertex& v, Vec3 wo, Color beta);
    // The same for a vertex to resolve from the ray direction `d` and its hit at (u, v) on a
    // quad (q, eu, ev), a triangle (p, and vertex normals n or nullptr) or a sphere (at its point
    // p = o + t d), of the BSDF `bsdf`
    // (Lambertian or rough metal).
    size_t push_quad_hit(size_t entry,
                         Vec3 d,
                         float u,
                         float v,
                         const Quad& quad,
                         const BsdfParams& bsdf,
                         Color beta);
    size_t push_sphere_hit(
        size_t entry, Vec3 d, Point3 p, const Sphere& sphere, const BsdfParams& bsdf, Color beta);
    size_t push_triangle_hit(size_t entry,
                             Vec3 d,
                             float u,
                             float v,
                             const Point3 (&p)[3],
                             const Normal3* n,
                             const BsdfParams& bsdf,
                             Color beta);
    void set_light_sample(size_t row, int32_t quad, float probability, float u1, float u2);
    void set_sphere_light_sample(size_t row, int32_t sphere, float probability, float u1, float u2);
    void set_step(size_t row, const ContinuationSamples& u, float u_roulette, bool roulette);

  private:
    void start_row(size_t row, size_t entry, const BsdfParams& bsdf, Color beta);
};

// Rows k < b.n pushed with a hit: their p, ng, ns, wo (surface_at's and resolve_segment's), bit
// for bit; afterwards every row's vertex is given.
void resolve_surface_hits(SurfaceBlock& b);

// Rows k < b.n, whose vertices are given (resolve_surface_hits): next_event's light sample
// (times beta) and continue_path's step, bit for bit.
void surface_vertices(SurfaceBlock& b, const LightSet& lights, bool mis, MisHeuristic heuristic);

}  // namespace wavetrace
