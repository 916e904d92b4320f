// The wavefront's kernels that run in SIMD lanes, over a chunk of a queue: camera rays
// (scene/camera_ray-inl.h), the uniform numbers of each vertex (sampling/sampler-inl.h), the
// points and normals of surface hits (scene/surface_point-inl.h), the continuation
// (shading/surface_step-inl.h) of Lambertian, glossy (bsdfs/glossy-inl.h) and isotropic-phase
// vertices, their light samples towards quad, triangle, sphere and environment lights
// (lights/light_sample-inl.h, lights/environment_light-inl.h), and the environment's radiance
// for rays that leave the scene. The formulas are the ones the megakernel runs in one lane;
// these run them a vector at a time, on the best target the CPU has (Highway's dynamic
// dispatch), with the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bsdfs/lane_lobe.h"
#include "queues/light_sample_queue.h"
#include "queues/shadow_queue.h"
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

// Rows k < n of `out`: generate_camera_ray(camera, sampler, pixel[k], sample[k], x[k], y[k]),
// bit for bit, and with `flights` (a scene with media) the camera segment's optical depth
// segment_flight(scene, sampler, pixel[k], sample[k], 0).
void draw_camera_rays(const CameraRays& camera,
                      const Sampler& sampler,
                      const uint32_t* sample,
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

// Rows k < n of `out`: vertex_samples(sampler, pixel[k], sample[k], bounce[k], one_sample), bit
// for bit, and with `flights` (a scene with media) segment_flight(scene, sampler, pixel[k],
// sample[k], bounce[k] + 1).
void draw_vertex_samples(const Sampler& sampler,
                         const uint32_t* sample,
                         const uint32_t* pixel,
                         const uint16_t* bounce,
                         size_t n,
                         bool one_sample,
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

// How a VertexBlock row's vertex is found: given, or resolved from its hit on a shape.
enum class HitShape : int32_t { Given, Quad, Triangle, Sphere };
// What a glossy or a delta row adds to its albedo and roughness: its kind, a conductor's complex
// index of refraction and distribution, a dielectric's index (in eta, every channel) and
// distribution, a metallic-roughness surface's Schlick F0, metallic, clearcoat
// and its roughness, and one-sidedness. Only the rows of those kinds are set; the kernels read
// the others as zero where no lane of a vector is of such a kind.
struct GlossyRows {
    alignas(64) float eta[3][kShadeChunk];
    alignas(64) float k[3][kShadeChunk];
    alignas(64) int32_t beckmann[kShadeChunk];  // 1: Beckmann, 0: GGX
    alignas(64) float f0[kShadeChunk], metallic[kShadeChunk], transmission[kShadeChunk];
    alignas(64) float clearcoat[kShadeChunk], coat_alpha[kShadeChunk];
    alignas(64) int32_t one_sided[kShadeChunk];
    alignas(64) int32_t kind[kShadeChunk];  // MaterialKind: which a delta row's lobe is

    // Row `row` of the BSDF b: a conductor's, a dielectric's, a metallic-roughness surface's or a
    // delta lobe's.
    void set(size_t row, const BsdfParams& b);
};

// Vertices of a chunk that run in SIMD lanes (SoA, `n` rows): Lambertian and glossy surface
// vertices (is_lane_bsdf), and medium vertices of isotropic phase function, each given
// (push) or resolved from its hit on a quad, a triangle or a sphere (push_*_hit, then
// resolve_surface_hits: surface_at's point and normals, resolve_segment's wo); then each row's
// continuation, continue_path's (step_vertices). Flags are int32 rows (0 or 1), and kinds
// int32 enums, so that a vector compare makes them masks.
struct VertexBlock {
    // in: the hit of a row whose vertex is resolved here: the ray's direction, the hit's (u, v)
    // (sphere: u is the radius), the corners (quad: q, u, v; triangle: p0, p1, p2; sphere: the
    // hit point o + t d and the centre) and, for triangles of a mesh with normals (smooth), the
    // vertex normals
    alignas(64) int32_t shape[kShadeChunk];  // HitShape
    alignas(64) float dir[3][kShadeChunk];
    alignas(64) float hit_u[kShadeChunk], hit_v[kShadeChunk];
    alignas(64) float corner[3][3][kShadeChunk];
    alignas(64) float vertex_normal[3][3][kShadeChunk];
    alignas(64) int32_t smooth[kShadeChunk];
    alignas(64) int32_t flip_v[kShadeChunk];  // a quad's texture v is 1 - hit_v (Quad::flip_v)
    // the vertex: in for given rows, out of resolve_surface_hits for the others
    alignas(64) float p[3][kShadeChunk];
    alignas(64) float ng[3][kShadeChunk];  // zero in a medium
    alignas(64) float ns[3][kShadeChunk];  // +z in a medium
    alignas(64) float wo[3][kShadeChunk];
    alignas(64) float albedo[3][kShadeChunk];
    alignas(64) float alpha[kShadeChunk];   // the glossy lobes' roughness
    alignas(64) int32_t lobe[kShadeChunk];  // LaneLobe
    GlossyRows glossy;                      // the conductor and metallic-roughness rows'
    MaterialId material[kShadeChunk];       // the surface's, for the light sample
    MediumId interior[kShadeChunk];         // the surface's inside medium (path_vertex.h Vertex)
    alignas(64) float beta[3][kShadeChunk];
    // in: the continuation's lobe, direction and roulette samples, and whether roulette applies
    alignas(64) float u_lobe[kShadeChunk], u1[kShadeChunk], u2[kShadeChunk], u_rr[kShadeChunk];
    alignas(64) int32_t roulette[kShadeChunk];
    alignas(64) float eta_scale[kShadeChunk];  // the path's (path_vertex.h), for roulette
    uint32_t entry[kShadeChunk];               // the wave entry of each row
    size_t n = 0;
    bool geometric_side_test = true;  // Scene::geometric_side_test, for every row
    // out: the next ray, the throughput factor and the BSDF density, for rows with alive = 1;
    // whether the ray leaves through the surface (a transmission), whether it is a delta lobe's,
    // and the path's eta scale after it
    alignas(64) float origin[3][kShadeChunk];
    alignas(64) float wi[3][kShadeChunk];
    alignas(64) float weight[3][kShadeChunk];
    alignas(64) float pdf[kShadeChunk];
    alignas(64) int32_t alive[kShadeChunk];
    alignas(64) int32_t transmitted[kShadeChunk];
    alignas(64) int32_t delta[kShadeChunk];  // wi is a Dirac-delta lobe's (pdf 0)
    alignas(64) float next_eta_scale[kShadeChunk];

    // Appends the vertex v (is_lane_vertex) of wave entry `entry`, arriving from wo with
    // throughput beta; returns its row.
    size_t push(size_t entry, const Vertex& v, Vec3 wo, Color beta);
    // The same for a vertex to resolve from the ray direction `d` and its hit at (u, v) on a
    // quad, a triangle (p, and vertex normals n or nullptr) or a sphere (at its point
    // p = o + t d), of the BSDF `bsdf` (is_lane_bsdf) of material m.
    size_t push_quad_hit(size_t entry,
                         Vec3 d,
                         float u,
                         float v,
                         const Quad& quad,
                         MaterialId m,
                         const BsdfParams& bsdf,
                         Color beta);
    size_t push_sphere_hit(size_t entry,
                           Vec3 d,
                           Point3 p,
                           const Sphere& sphere,
                           MaterialId m,
                           const BsdfParams& bsdf,
                           Color beta);
    size_t push_triangle_hit(size_t entry,
                             Vec3 d,
                             float u,
                             float v,
                             const Point3 (&p)[3],
                             const Normal3* n,
                             MaterialId m,
                             const BsdfParams& bsdf,
                             Color beta);
    // Row `row`'s continuation samples; roulette: whether Russian roulette applies, on the
    // throughput times the path's eta scale.
    void set_step(size_t row,
                  const ContinuationSamples& u,
                  float u_roulette,
                  bool applies,
                  float path_eta_scale = 1.0f) {
        eta_scale[row] = path_eta_scale;
        u_lobe[row] = u.lobe;
        u1[row] = u.bsdf_u1;
        u2[row] = u.bsdf_u2;
        u_rr[row] = u_roulette;
        roulette[row] = applies ? 1 : 0;
    }

  private:
    size_t start_row(
        size_t entry, HitShape shape, MaterialId m, const BsdfParams& bsdf, Color beta);
};

// Rows k < b.n pushed with a hit: their p, ng, ns, wo (surface_at's and resolve_segment's), bit
// for bit.
void resolve_surface_hits(VertexBlock& b);

// Rows k < b.n, whose vertices are given (resolve_surface_hits): continue_path's step, bit for
// bit.
void step_vertices(VertexBlock& b);

// Light samples of rows [first, first + n) of the light-sample queue towards a quad or triangle
// light of constant radiance, a sphere light of constant radiance seen from outside, or the
// environment map: next_event's sample (lights/light_sample-inl.h), unweighted, bit for bit.
// The vertices are read from the queue where they are; the block holds what the kernel adds per
// row.
struct LightSampleBlock {
    const LightSampleQueue* queue = nullptr;
    size_t first = 0, n = 0;
    bool geometric_side_test = true;  // Scene::geometric_side_test, for every row
    // the vertex's lobe (LaneLobe) and, for a conductor or a metallic-roughness surface, what
    // the queue does not hold of its BSDF; the light, as its index among the LightSet's planar
    // emitters, its sphere emitters or its point and directional lights (all -1 and environment
    // 0: the row's light is another kind, not sampled here), and its selection probability
    alignas(64) int32_t lobe[kShadeChunk];
    GlossyRows glossy;
    alignas(64) int32_t planar[kShadeChunk], sphere[kShadeChunk], delta[kShadeChunk];
    alignas(64) int32_t environment[kShadeChunk];  // 1: the light is the environment map
    alignas(64) float select_prob[kShadeChunk];
};

// The rows of b with a light sample that contributes (next_event's valid ones), in row order, as
// shadow rays appended to `shadows` from entry `first_shadow` (contribution: the row's beta
// times the sample's value); returns how many.
size_t sample_lights_in_lanes(LightSampleBlock& b,
                              const LightSet& lights,
                              ShadowQueue& shadows,
                              size_t first_shadow);

// Directions sampled from the environment map for the vertices that are not lane vertices (SoA,
// rows k < n): EnvironmentLightPoint's, which LightSet::sample takes, bit for bit; their BSDFs
// are then evaluated in scalar code (direct_sample_from).
struct EnvironmentPointBlock {
    alignas(64) float u1[kShadeChunk], u2[kShadeChunk];  // in: the light sample's numbers
    alignas(64) float select_prob[kShadeChunk];          // in
    alignas(64) float wi[3][kShadeChunk];                // out
    alignas(64) float radiance[3][kShadeChunk];          // out
    alignas(64) float pdf[kShadeChunk];                  // out: selection included
    size_t n = 0;
};

// Rows k < b.n of b.
void environment_light_points(EnvironmentPointBlock& b, const LightSet& lights);

// Rays of a chunk that leave the scene under an environment map (SoA, rows k < n): what each
// finds there, resolve_segment's (lights/environment_light-inl.h's Escape), bit for bit.
struct EscapeBlock {
    alignas(64) float dir[3][kShadeChunk];       // in: the ray's direction, of any length
    alignas(64) float select_prob[kShadeChunk];  // in, with_pdf: the background's selection
    alignas(64) float radiance[3][kShadeChunk];  // out: the map's radiance
    alignas(64) float pdf_light[kShadeChunk];    // out, with_pdf: the light sample's density
    size_t n = 0;
};

// Rows k < b.n of b; with_pdf: their pdf_light too (MIS weighs the radiance).
void escape_rays(EscapeBlock& b, const LightSet& lights, bool with_pdf);

// out[k] = direct_weight(strategy, heuristic, pdf_light[k], pdf_bsdf[k]) for k < n, bit for bit,
// the heuristic `at_infinity` for the rows of infinite tmax[k] and `finite` for the others: the
// MIS weights a vector at a time.
void direct_weights(Strategy strategy,
                    MisHeuristic finite,
                    MisHeuristic at_infinity,
                    const float* pdf_light,
                    const float* pdf_bsdf,
                    const float* tmax,
                    size_t n,
                    float* out);

}  // namespace wavetrace
