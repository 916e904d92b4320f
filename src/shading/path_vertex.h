// The per-vertex steps of path tracing, as plain functions over plain data: resolving a hit
// into a scattering vertex, next-event estimation, choosing the continuation for each
// strategy, the weight of emission a path finds, media. Both engines call exactly these; only
// the organisation of the work around them differs.
#pragma once

#include <cmath>
#include <cstdint>

#include "bsdfs/bsdf.h"
#include "media/free_flight.h"
#include "media/medium_stack.h"
#include "sampling/sampler.h"
#include "scene/normal_maps.h"
#include "shading/lights.h"
#include "shading/mis.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/material.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/estimator.h"
#include "wavetrace/shading/surface.h"

namespace wavetrace {

struct Scene;

// A point where a path scatters: on a surface, or inside a medium (ng = 0).
struct Vertex {
    Point3 p;
    Frame frame;       // local z = shading normal (surfaces) or any axis (media)
    float frame_angle = 0.0f;  // anisotropic BSDFs: frame is rotated_frame(n, frame_angle)
    Normal3 ng{0.0f};  // geometric normal, outward; zero inside a medium
    BsdfParams bsdf;
    MediumId interior = kNone;    // the surface's inside medium, for transmission
    MaterialId material = kNone;  // whose BSDF it is (a medium's: its phase function)
    bool geometric_side_test = true;  // Scene::geometric_side_test, at a surface
    // A mapped normal's shadowing (bsdfs/bump_terminator.h): the unperturbed normal and the
    // shadowing's alpha^2; 0: none (the BSDF is not scaled).
    Normal3 unbent{0.0f};
    float bump_alpha2 = 0.0f;
    Vec2 uv;  // a surface's texture coordinates (light_sample looks a principled BSDF up there)
    bool on_surface() const { return ng.x != 0 || ng.y != 0 || ng.z != 0; }
};

// The frame about n whose s is turned by `angle` from Frame::from_normal(n)'s towards its t:
// how a vertex of an anisotropic BSDF holds the tangent its roughness runs along, one number
// from which the light_sample kernel rebuilds the frame bit for bit.
inline Frame rotated_frame(Normal3 n, float angle) {
    const Frame f = Frame::from_normal(n);
    if (angle == 0.0f) return f;
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * f.s + s * f.t, c * f.t - s * f.s, n};
}

// What the normal and bump maps read of a surface hit.
inline MappedPoint mapped_point(const SurfaceHit& hit) {
    return {hit.p, hit.ng, hit.ns, hit.uv, hit.dpdu, hit.dpdv};
}

// The vertex of a surface hit seen from direction wo (unit, back along the arriving ray).
Vertex surface_vertex(const Scene& scene, const SurfaceHit& hit, Vec3 wo);
// The BSDF of a surface of material m and albedo `albedo` (its albedo texture's value there).
inline BsdfParams material_bsdf(const Material& m, Color albedo) {
    BsdfParams b;
    // A reflecting emitter scatters as a Lambertian surface of its albedo.
    b.kind = m.kind == MaterialKind::DiffuseLight ? MaterialKind::Lambertian : m.kind;
    b.albedo = albedo;
    b.alpha = m.roughness * m.roughness;
    b.eta = m.ior;
    if (m.kind == MaterialKind::Conductor || m.kind == MaterialKind::Dielectric ||
        m.kind == MaterialKind::Plastic) {
        b.alpha = m.alpha_u;
        b.alpha_v = m.alpha_v;
        b.conductor_eta = m.eta;
        b.conductor_k = m.k;
        b.distribution = m.distribution;
    }
    if (m.kind == MaterialKind::Plastic) {
        b.specular = m.specular;
        b.specular_weight = m.specular_weight;
        b.nonlinear = m.nonlinear;
        b.coating = &m.coating;
        b.one_sided = m.one_sided;
        b.alpha_v = b.alpha;  // isotropic
    }
    if (m.kind == MaterialKind::MetallicRoughness) {
        b.alpha_v = b.alpha;  // isotropic, roughness^2
        b.metallic = m.metallic;
        b.transmission = m.transmission;
        b.clearcoat = m.clearcoat;
        b.clearcoat_alpha = m.clearcoat_roughness * m.clearcoat_roughness;
        b.one_sided = m.one_sided;
    }
    return b;
}
Vertex medium_vertex(const Scene& scene, MediumId medium, Point3 p);
// Where a path scatters in a medium: world distance `dist` along `ray` from its origin, for a
// direction of length dir_length.
inline Point3 scattering_point(const Ray& ray, float dist, float dir_length) {
    return ray.o + (ray.tmin + dist / dir_length) * ray.d;
}

// Whether next-event estimation and light-sampled directions apply at this vertex.
bool can_sample_lights(const Vertex& v, const LightSet& lights);

// A ray origin just off the surface on the side `w` leaves towards, so that the new ray does
// not hit the surface it starts on.
Point3 offset_origin(const Vertex& v, Vec3 w);

// Medium boundaries one ray segment may cross before the path is given up (a guard against
// degenerate geometry, e.g. a ray trapped between coincident boundaries).
inline constexpr int kMaxBoundaryCrossings = 64;

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
    float select_total = 0.0f;  // the light choice's (LightChoice::total), valid or not
};
DirectSample sample_direct(const Scene& scene,
                           const LightSet& lights,
                           const Vertex& v,
                           Vec3 wo,
                           LightChoice light,
                           float u1,
                           float u2);
// The same for the light sample ls taken from v's point (LightSet::sample's).
DirectSample direct_sample_from(const Vertex& v, Vec3 wo, const LightSample& ls);

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
Continuation sample_continuation(Strategy strategy,
                                 const Scene& scene,
                                 const LightSet& lights,
                                 const Vertex& v,
                                 Vec3 wo,
                                 const ContinuationSamples& u);

// The strategies' MIS weights (Veach 1997, §9.2), the one place they are decided: the
// megakernel calls them at each vertex, the wavefront in its mis_combine kernel.
// The heuristics they weigh by (MisHeuristics, shading/mis.h): the configured one, and at
// infinity the balance heuristic where the environment map is sampled with MIS compensation.
inline MisHeuristics mis_heuristics(const Estimator& config, const LightSet& lights) {
    return {config.heuristic,
            lights.environment_compensated() ? MisHeuristic::Balance : config.heuristic};
}

// Weight of emission Le found by a ray whose previous vertex chose it with BSDF density
// pdf_bsdf, when a light sample from that vertex would have had density pdf_light.
// `counts_fully`: a camera ray, or the previous vertex could not sample lights (delta lobes).
// Bsdf, Light and Mixture count all emission found (Light and Mixture weight their one-sample
// continuation instead), NEE only where no light sample could have found it.
inline float emission_weight(
    Strategy strategy, MisHeuristic heuristic, bool counts_fully, float pdf_bsdf, float pdf_light) {
    if (counts_fully || strategy == Strategy::Bsdf || strategy == Strategy::Light ||
        strategy == Strategy::Mixture)
        return 1.0f;
    return strategy == Strategy::Mis ? mis_weight(heuristic, pdf_bsdf, pdf_light) : 0.0f;
}

// Weight of a next-event (shadow ray) contribution: 1 for NEE, w(p_l, p_b) for MIS.
inline float direct_weight(Strategy strategy,
                           MisHeuristic heuristic,
                           float pdf_light,
                           float pdf_bsdf) {
    return strategy == Strategy::Mis ? mis_weight(heuristic, pdf_light, pdf_bsdf) : 1.0f;
}

// --- path segments ----------------------------------------------------------------------
// What the vertex a segment starts from leaves for the emission the segment may find.
struct PreviousVertex {
    Point3 p;
    float pdf_bsdf = 0.0f;
    bool counts_fully = true;  // camera ray, or a vertex that could not sample lights
    Normal3 n{0.0f};           // geometric normal (zero in a medium): its light selection
    float select_total = 0.0f;  // ... and its LightChoice::total
};

enum class SegmentEvent : uint8_t {
    Scatter,   // the path scatters at `vertex` (a surface or a point in a medium), after adding
               // `emission` (non-zero only at an emitter that also reflects)
    Emission,  // the segment ends on an emitter or in the background: `emission`
    Cross,     // the segment crossed a medium boundary and goes on as `next`
    End,       // absorbed: a black background, the back of an emitter, or too many crossings
};

struct SegmentResult {
    SegmentEvent event = SegmentEvent::End;
    Vertex vertex;
    Vec3 wo;               // Scatter: unit direction back along the segment
    Color emission{0.0f};  // Emission, Scatter: the radiance found, unweighted
    // The density with which the previous vertex's light sample would have found it, where the
    // MIS weight needs it (emission_weight; else 0).
    float emission_pdf_light = 0.0f;
    bool at_infinity = false;  // Emission: the background's, found by leaving the scene
    Ray next;  // Cross: the continuing ray
    // The free flight's weight over this segment, which multiplies all the path finds from
    // here on (the emission above included): 1 but in chromatic media (chromatic_flight).
    Color weight{1.0f};
};

// The medium part of a segment in medium m (kNone: none) towards its closest hit, for a ray of
// direction length dir_length: true when the path scatters in the medium first, at world
// distance *s from the origin; else the optical depth the segment crosses is spent from
// `flight` (the rest carries over past the boundary: free flights are memoryless). *weight is
// the flight's weight for the path throughput: 1 in grey media, whose sampling density is
// the transmittance's own; chromatic_flight's in chromatic media.
bool scatters_in_medium(const Scene& scene,
                        MediumId m,
                        const Ray& ray,
                        const Hit& hit,
                        float dir_length,
                        float& flight,
                        float* s,
                        Color* weight);

// The fraction of light a thin sheet lets straight through at s along unit direction dir:
// 1 - R' (thin_dielectric.h) at the vertex's shading normal, the probability with which a
// path passes it there.
float sheet_transmittance(const Scene& scene, const SurfaceHit& s, Vec3 dir);

// A segment of unit direction dir reaches s, a medium boundary (an Interface surface): the path
// crosses into or out of its interior (`media`) and goes straight on, from just past it.
Ray cross_boundary(const Scene& scene, const SurfaceHit& s, Vec3 dir, MediumStack& media);

// Resolves one ray segment given its closest hit: medium scattering before the hit (consuming
// `flight`, the optical depth left, drawn once per segment), escaping, emitters, medium
// boundaries (updating `media`), or a surface to scatter at.
SegmentResult resolve_segment(const Scene& scene,
                              const LightSet& lights,
                              const Estimator& config,
                              const Ray& ray,
                              const Hit& hit,
                              MediumStack& media,
                              float& flight,
                              const PreviousVertex& prev);

// The continuation of a path at a scattering vertex, Russian roulette included: the next ray,
// the factor for the path throughput, the record for weighting emission the next segment
// finds, and the media after a transmission. `alive` is false when the path ends here.
// `depth` is the vertex's (see next_depth), which decides where roulette starts; `prev`, the
// record the segment that reached v came with, which a path passing a thin sheet keeps: the
// emission it finds beyond is weighted as seen from the vertex before the sheet, whose light
// samples pass the sheet too (trace.h, shadows_pass).
//
// `eta_scale` is the path's eta scale: the product of eta^2 over its refractions so far. A
// refraction puts 1 / eta^2 into the throughput (radiance is compressed entering a denser
// medium, Veach 1997, §5.2), which leaving the medium undoes; roulette decides on the
// throughput times the eta scale, so that it does not end paths inside glass for a factor that
// leaving it would take back (pbrt-v4's etaScale, Mitsuba 3's eta^2 in its roulette).
struct PathStep {
    bool alive = false;
    bool passed_sheet = false;  // went straight through a thin sheet: a null event
    Ray next;
    Color weight{0.0f};
    PreviousVertex prev;
    float eta_scale = 1.0f;  // the path's after this step
};
PathStep continue_path(const Scene& scene,
                       const LightSet& lights,
                       const Estimator& config,
                       const Vertex& v,
                       Vec3 wo,
                       const PreviousVertex& prev,
                       int depth,
                       Color beta,
                       float eta_scale,
                       MediumStack& media,
                       const ContinuationSamples& u,
                       float u_roulette);

// --- path depth -----------------------------------------------------------------------------
// A path's vertices are numbered twice. The vertex index (`bounce`, 0 for the camera ray's)
// picks each vertex's sample dimensions. The depth counts what max_depth and roulette count:
// every vertex but the thin sheets the path passed straight through, which Mitsuba 3 treats as
// null events (its thindielectric's transmission is a Null lobe, and its volpath counts only
// non-null events), so that a window or a sheet around a medium does not shorten the paths
// that cross it.
// Sheets one path may pass uncounted (a guard against a stack of coincident sheets); past this
// each counts as a vertex.
inline constexpr int kMaxSheetPasses = 64;
// Whether a vertex reached at depth `depth` may scatter: the path may still grow.
inline bool may_scatter(const Estimator& config, int depth) {
    return depth + 1 < config.max_depth;
}
// Whether a path may go on from v, reached at depth `depth`: a thin sheet may always be passed,
// whatever the depth; anything else scatters only where may_scatter says so.
inline bool may_continue(const Estimator& config, const Vertex& v, int depth) {
    return may_scatter(config, depth) || v.bsdf.kind == MaterialKind::ThinDielectric;
}
// Whether a ray to a vertex of depth `depth` can still bring light: below max_depth, and where
// no ray finds a light (the scene's lights all points, spots and directional lights, the
// background black), only if that vertex may scatter and sample one in turn. The ray that ends
// a path at max_depth is traced for the emission it finds: in such a scene none, so the path
// ends before it (Mitsuba's `direct`-style scenes, max_depth 2, trace half the rays).
inline bool ray_may_bring_light(const Estimator& config, const LightSet& lights, int depth) {
    return depth < config.max_depth && (lights.has_area_lights() || may_scatter(config, depth));
}
// The depth of the vertex that `step`, taken at vertex `bounce` of depth `depth`, leads to; the
// path ends there unless ray_may_bring_light.
inline int next_depth(int bounce, int depth, const PathStep& step) {
    return step.passed_sheet && bounce - depth < kMaxSheetPasses ? depth : depth + 1;
}
// The uniform numbers of vertex `bounce` of path (pixel, sample) (sampling/sampler.h): both
// engines draw them alike; vertex_samples with next_flight also segment_flight of bounce + 1.
struct VertexSamples {
    float light_select, light_u, light_v;  // next-event estimation
    ContinuationSamples continuation;
    float roulette;
};
// Whether the strategy reads the pairs only one-sample strategies read (one_sample_pair).
inline bool reads_one_sample_pairs(Strategy strategy) {
    return strategy == Strategy::Mixture || strategy == Strategy::Light;
}
VertexSamples vertex_samples(const Sampler& sampler,
                             uint32_t pixel,
                             uint32_t sample,
                             int bounce,
                             bool one_sample,
                             float* next_flight = nullptr);
// The same from u(d), the value of bounce dimension d: the one mapping of dimensions to fields,
// for vertex_samples and for the rows the wavefront draws in SIMD lanes.
template <class DimValue>
VertexSamples vertex_samples_of(DimValue u) {
    return {u(kDimLightSelect),
            u(kDimLightU),
            u(kDimLightV),
            {u(kDimTechnique), u(kDimDirectionSelect), u(kDimDirectionU), u(kDimDirectionV),
             u(kDimBsdfLobe), u(kDimBsdfU), u(kDimBsdfV)},
            u(kDimRoulette)};
}
// Next-event estimation at a scattering vertex as the strategy does it, for both engines: the
// light sample, unweighted (its weight is direct_weight's); invalid when the strategy samples no
// lights, the vertex cannot, or the sample has no contribution. The contribution is
// value * weight times the shadow ray's transmittance.
DirectSample next_event(const Scene& scene,
                        const LightSet& lights,
                        const Estimator& config,
                        const Vertex& v,
                        Vec3 wo,
                        const VertexSamples& u);
// The same with the light already chosen, where samples_lights(config, v, lights) holds.
DirectSample next_event(const Scene& scene,
                        const LightSet& lights,
                        const Vertex& v,
                        Vec3 wo,
                        const VertexSamples& u,
                        LightChoice light);
// Whether next-event estimation happens at v: the strategy samples lights and v can.
bool samples_lights(const Estimator& config, const Vertex& v, const LightSet& lights);
// Optical depth a segment reaching vertex `bounce` may travel in media (0 in a scene without).
float segment_flight(
    const Scene& scene, const Sampler& sampler, uint32_t pixel, uint32_t sample, int bounce);
// The camera ray of sample `sample` of pixel (x, y), jittered over the pixel and the lens.
Ray generate_camera_ray(
    const CameraRays& camera, const Sampler& sampler, uint32_t pixel, uint32_t sample, int x, int y);

}  // namespace wavetrace
