// The per-vertex steps of path tracing, as plain functions over plain data: resolving a hit
// into a scattering vertex, next-event estimation, choosing the continuation for each
// strategy, the weight of emission a path finds, media. Both engines call exactly these; only
// the organisation of the work around them differs.
#pragma once

#include <cstdint>

#include "wavetrace/math/frame.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/render/render.h"
#include "wavetrace/scene/bvh.h"
#include "wavetrace/scene/surface.h"
#include "wavetrace/shading/bsdf.h"
#include "wavetrace/shading/lights.h"
#include "wavetrace/shading/medium_stack.h"

namespace wavetrace {

struct Scene;

// A point where a path scatters: on a surface, or inside a medium (ng = 0).
struct Vertex {
    Point3 p;
    Frame frame;        // local z = shading normal (surfaces) or any axis (media)
    Normal3 ng{0.0f};   // geometric normal, outward; zero inside a medium
    BsdfParams bsdf;
    MediumId interior = kNone;  // the surface's inside medium, for transmission
    bool on_surface() const { return ng.x != 0 || ng.y != 0 || ng.z != 0; }
};

Vertex surface_vertex(const Scene& scene, const SurfaceHit& hit);
Vertex medium_vertex(const Scene& scene, MediumId medium, Point3 p);

// Whether next-event estimation and light-sampled directions apply at this vertex.
bool can_sample_lights(const Vertex& v, const LightSet& lights);

// A ray origin just off the surface on the side `w` leaves towards, so that the new ray does
// not hit the surface it starts on (offset relative to the point's magnitude).
Point3 offset_origin(const Vertex& v, Vec3 w);

// --- next-event estimation -------------------------------------------------------------
// One light sample from vertex v for a path arriving from direction wo (unit, pointing away
// from v). value = f |cos| Le / p_light: the unweighted, unoccluded contribution; the caller
// multiplies by the shadow ray's transmittance and the strategy's weight.
struct DirectSample {
    Color value{0.0f};
    float pdf_light = 0.0f;
    float pdf_bsdf = 0.0f;
    Ray shadow;  // unit direction, tmax just short of the light
    bool valid = false;
};
DirectSample sample_direct(const Scene& scene, const LightSet& lights, const Vertex& v, Vec3 wo,
                           float u_select, float u1, float u2);

// Fraction of light that gets through along a shadow ray: 0 if a surface blocks it, else the
// product of exp(-density * length) over the media it crosses (boundaries without a surface
// let it through). `media` is the stack at the ray's origin. Counts the rays it traces.
float transmittance(const Scene& scene, const Bvh& bvh, Ray shadow, MediumStack media,
                    uint64_t* rays);

// --- continuation -------------------------------------------------------------------------
struct Continuation {
    Vec3 wi;
    Color weight{0.0f};     // f |cos| / p for the strategy's direction density p
    float pdf_bsdf = 0.0f;  // BSDF density of wi (for MIS at the emitter it may hit)
    bool delta = false;
    bool transmitted = false;
    bool valid = false;
};
// The uniform numbers a continuation may use, drawn from the bounce's sample dimensions.
struct ContinuationSamples {
    float technique, select, u1, u2;  // one-sample strategies' light/uniform direction
    float lobe, bsdf_u1, bsdf_u2;     // BSDF sampling
};
Continuation sample_continuation(Strategy strategy, const Scene& scene, const LightSet& lights,
                                 const Vertex& v, Vec3 wo, const ContinuationSamples& u);

// Weight of emission Le found by a ray whose previous vertex chose it with BSDF density
// pdf_bsdf, when a light sample from that vertex would have had density pdf_light.
// `counts_fully`: a camera ray, or the previous vertex could not sample lights (delta lobes).
float emission_weight(Strategy strategy, MisHeuristic heuristic, bool counts_fully,
                      float pdf_bsdf, float pdf_light);

// Russian roulette survival probability for path throughput beta.
float survival_probability(Color beta);

// --- media ----------------------------------------------------------------------------------
// Free-flight distance (world units) in a homogeneous medium of extinction `density`,
// sampled proportional to density * exp(-density * s): -ln(1 - u) / density.
float sample_free_flight(float density, float u);
// The media containing point p, found by walking a ray out of the scene and pairing the
// boundaries it enters and leaves (convex, properly nested boundaries assumed).
MediumStack media_at(const Scene& scene, const Bvh& bvh, Point3 p);

}  // namespace wavetrace
