#include "shading/path_vertex.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/bump_terminator.h"
#include "bsdfs/geometric_side-inl.h"
#include "bsdfs/thin_dielectric.h"
#include "lights/environment_light-inl.h"
#include "lights/light_sample-inl.h"
#include "lights/sphere_light-inl.h"
#include "media/medium_flight-inl.h"
#include "media/medium_segment.h"
#include "sampling/bounce_dims.h"
#include "sampling/sampler-inl.h"
#include "sampling/sampler.h"
#include "sampling/warp.h"
#include "scene/camera_ray-inl.h"
#include "scene/material_lookup.h"
#include "scene/normal_maps.h"
#include "shading/lane_routes.h"
#include "shading/mis-inl.h"
#include "shading/surface_step-inl.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

namespace {

// The coat's normal at the hit in the shading frame f; out of line, so that the vertices
// without one do not carry its code.
[[gnu::noinline]] Vec3 coat_in_frame(const Scene& scene,
                                     const Material& m,
                                     const SurfaceHit& hit,
                                     const Frame& f) {
    return f.to_local(coat_normal(scene, m, mapped_point(hit)));
}

// Frame::from_normal, inlined here: it runs at every vertex.
Frame frame_from_normal(Vec3 n) {
    lanes::V3<float> s, t;
    lanes::OrthonormalBasis<OneLane>(lanes::to_lanes(n), &s, &t);
    return {lanes::to_vec3(s), lanes::to_vec3(t), n};
}

}  // namespace

Vertex surface_vertex(const Scene& scene, const SurfaceHit& hit, Vec3 wo) {
    Vertex v;
    v.p = hit.p;
    v.ng = hit.ng;
    const Material& m = scene.materials[hit.material];
    Normal3 n = hit.ns;
    if (m.has_normal_maps()) {
        n = mapped_normal(scene, m, mapped_point(hit), wo);
        if (m.bump_shadowing) {
            v.unbent = hit.ns;
            v.bump_alpha2 = bump_shadowing_alpha2(hit.ns, n);
        }
    }
    v.interior = hit.interior;
    v.material = hit.material;
    v.geometric_side_test = scene.geometric_side_test;
    v.bsdf = material_bsdf(
        m, m.albedo != kNone ? eval_texture(scene, m.albedo, hit.texture_point()) : Color(0.0f));
    if (m.kind == MaterialKind::MetallicRoughness)
        metallic_roughness_at(scene, m, hit.texture_point(), &v.bsdf);
    auto textured_alpha = [&](TextureId t) {
        return std::clamp(eval_texture(scene, t, hit.texture_point()).x, 1e-4f, 1.0f);
    };
    v.uv = hit.uv;
    if (m.kind == MaterialKind::Principled) principled_at(scene, m, hit.uv, hit.p, &v.bsdf);
    if (m.alpha_u_texture != kNone) v.bsdf.alpha = textured_alpha(m.alpha_u_texture);
    if (m.alpha_v_texture != kNone) v.bsdf.alpha_v = textured_alpha(m.alpha_v_texture);
    v.frame = frame_from_normal(n);
    if (m.anisotropic() && v.bsdf.alpha != v.bsdf.alpha_v) {
        // An anisotropic roughness runs along dp/du: the frame's s is dp/du made perpendicular
        // to the shading normal (Mitsuba 3's shading frame), where it has a direction.
        const Vec3 s = hit.dpdu - dot(n, hit.dpdu) * n;
        if (length_squared(s) > 1e-20f * length_squared(hit.dpdu) && length_squared(s) > 0.0f) {
            const Frame base = Frame::from_normal(n);
            v.frame_angle = std::atan2(dot(s, base.t), dot(s, base.s));
            v.frame = rotated_frame(n, v.frame_angle);
        }
    }
    // A coat under a mapped normal keeps its own (scene/normal_maps.h).
    if (m.kind == MaterialKind::MetallicRoughness && m.clearcoat > 0.0f && m.has_normal_maps())
        v.bsdf.coat_normal = coat_in_frame(scene, m, hit, v.frame);
    // A one-sided surface seen from behind reflects nothing: its albedo (a conductor's
    // reflectance) is 0 there.
    if (m.one_sided && !hit.front_face) v.bsdf.albedo = Color(0.0f);
    return v;
}

Vertex medium_vertex(const Scene& scene, MediumId medium, Point3 p) {
    Vertex v;
    v.p = p;
    v.frame = Frame::from_normal({0, 0, 1});
    v.material = scene.media[medium].phase;
    const Material& phase = scene.materials[v.material];
    v.bsdf.kind = MaterialKind::Isotropic;
    v.bsdf.albedo = eval_texture(scene, phase.albedo, {}, p);
    return v;
}

bool can_sample_lights(const Vertex& v, const LightSet& lights) {
    return !lights.empty() && !v.bsdf.is_delta() &&
           (v.bsdf.kind == MaterialKind::Lambertian || v.bsdf.kind == MaterialKind::Metal ||
            v.bsdf.kind == MaterialKind::Isotropic || v.bsdf.kind == MaterialKind::Conductor ||
            v.bsdf.kind == MaterialKind::Dielectric || v.bsdf.kind == MaterialKind::Plastic ||
            v.bsdf.kind == MaterialKind::MetallicRoughness ||
            v.bsdf.kind == MaterialKind::Principled);
}

Point3 offset_origin(const Vertex& v, Vec3 w) {
    if (!v.on_surface()) return v.p;
    return lanes::to_vec3(lanes::OffsetRayOrigin<OneLane>(
        lanes::to_lanes(v.p), lanes::to_lanes(v.ng), lanes::to_lanes(w)));
}

namespace {

// Whether the strategy picks the continuation at v by one-sample MIS of two techniques (light
// and mixture, where v can sample lights) rather than by BSDF sampling alone.
bool one_sample_continuation(Strategy strategy, const Vertex& v, const LightSet& lights) {
    return (strategy == Strategy::Mixture || strategy == Strategy::Light) &&
           can_sample_lights(v, lights) && lights.has_area_lights();
}

// f |cos| at a vertex for world directions, zero where wi leaves through the geometric surface
// (CrossesGeometricSurface) but the BSDF would reflect it, or stays on wo's side but the BSDF
// would transmit it (a rough dielectric, a metallic-roughness surface with transmission).
Color eval_world(const Vertex& v, Vec3 wo, Vec3 wi, float* pdf) {
    using lanes::to_lanes;
    Vec3 lo = v.frame.to_local(wo), li = v.frame.to_local(wi);
    const bool transmits = (v.bsdf.kind == MaterialKind::Dielectric ||
                            v.bsdf.kind == MaterialKind::MetallicRoughness ||
                            v.bsdf.kind == MaterialKind::Principled) &&
                           lo.z * li.z < 0.0f;
    if (v.geometric_side_test &&
        lanes::WrongGeometricSide<OneLane>(to_lanes(wo), to_lanes(wi), to_lanes(v.ng), transmits)) {
        *pdf = 0.0f;
        return {};
    }
    return bsdf_eval(v.bsdf, lo, li, pdf) * bump_shadowing(v.unbent, v.frame.n, v.bump_alpha2, wi);
}

}  // namespace

DirectSample sample_direct(const Scene& scene,
                           const LightSet& lights,
                           const Vertex& v,
                           Vec3 wo,
                           LightChoice light,
                           float u1,
                           float u2) {
    return direct_sample_from(v, wo, lights.sample(scene, v.p, light, u1, u2));
}

DirectSample direct_sample_from(const Vertex& v, Vec3 wo, const LightSample& ls) {
    DirectSample d;
    if (!ls.valid || max_component(ls.radiance) <= 0.0f) return d;
    Color f = eval_world(v, wo, ls.wi, &d.pdf_bsdf);
    if (max_component(f) <= 0.0f) return d;
    if (ls.delta) d.pdf_bsdf = 0.0f;  // no BSDF sample finds a point light: MIS weight 1
    d.value = f * ls.radiance / ls.pdf;
    d.pdf_light = ls.pdf;
    lanes::V3<float> origin, dir;
    float tmax;
    lanes::ShadowRayTo<OneLane>(lanes::to_lanes(v.p), lanes::to_lanes(v.ng), lanes::to_lanes(ls.wi),
                                ls.dist, &origin, &dir, &tmax);
    d.shadow = Ray{lanes::to_vec3(origin), lanes::to_vec3(dir), 0.0f, tmax};
    d.valid = true;
    return d;
}

Continuation sample_continuation(Strategy strategy,
                                 const Scene& scene,
                                 const LightSet& lights,
                                 const Vertex& v,
                                 Vec3 wo,
                                 const ContinuationSamples& u) {
    Continuation c;
    if (!one_sample_continuation(strategy, v, lights)) {
        Vec3 lo = v.frame.to_local(wo);
        BsdfSample s = bsdf_sample(v.bsdf, lo, u.lobe, u.bsdf_u1, u.bsdf_u2);
        if (!s.valid) return c;
        c.wi = v.frame.to_world(s.wi);
        // Reflection must stay on wo's side of the geometric surface, transmission cross it.
        if (v.on_surface() && v.geometric_side_test &&
            lanes::WrongGeometricSide<OneLane>(lanes::to_lanes(wo), lanes::to_lanes(c.wi),
                                               lanes::to_lanes(v.ng), s.transmitted))
            return c;
        c.weight = s.weight * bump_shadowing(v.unbent, v.frame.n, v.bump_alpha2, c.wi);
        c.pdf_bsdf = s.pdf;
        c.delta = s.delta;
        c.transmitted = s.transmitted;
        c.valid = true;
        return c;
    }
    // One-sample combination of two techniques, each picked with probability 1/2; the sample
    // is weighted by the combined density (Veach 1997, §9.2.4, one-sample model with the
    // balance heuristic). Mixture pairs light sampling with BSDF sampling; Light pairs it with
    // a uniform sphere, a "defensive" component (Hesterberg 1995) without which light-sampled
    // directions could never find indirect light arriving from where no light is.
    if (u.technique < 0.5f) {
        LightSample ls = lights.sample_direction_light(scene, v.p, u.select, u.u1, u.u2);
        if (!ls.valid) return c;
        c.wi = ls.wi;
    } else if (strategy == Strategy::Light) {
        c.wi = sample_uniform_sphere(u.u1, u.u2);
    } else {
        Vec3 lo = v.frame.to_local(wo);
        BsdfSample s = bsdf_sample(v.bsdf, lo, u.lobe, u.bsdf_u1, u.bsdf_u2);
        if (!s.valid) return c;
        c.wi = v.frame.to_world(s.wi);
    }
    float pdf_b;
    Color f = eval_world(v, wo, c.wi, &pdf_b);
    float pdf_l = lights.pdf_direction(scene, v.p, c.wi);
    float other = strategy == Strategy::Light ? uniform_sphere_pdf() : pdf_b;
    float pdf = 0.5f * pdf_l + 0.5f * other;
    if (!(pdf > 0.0f) || max_component(f) <= 0.0f) return c;
    c.weight = f / pdf;
    c.pdf_bsdf = pdf_b;
    // Whichever technique chose it, a direction through the surface is a transmission: the
    // path changes media (a light sampled from inside rough glass).
    c.transmitted = v.on_surface() && dot(wo, v.ng) * dot(c.wi, v.ng) < 0.0f;
    c.valid = true;
    return c;
}

bool samples_lights(const Estimator& config, const Vertex& v, const LightSet& lights) {
    const bool nee = config.strategy == Strategy::Nee || config.strategy == Strategy::Mis;
    return nee && can_sample_lights(v, lights);
}

int32_t sphere_light_sample_at(Point3 p,
                               bool lane_vertex,
                               const LightSet& lights,
                               LightChoice choice) {
    if (!lane_vertex) return -1;
    const int32_t k = lights.sphere_emitter_index(choice);
    if (k < 0) return -1;
    const SphereEmitterColumns& c = lights.sphere_emitter_columns();
    const lanes::V3<float> centre{c.centre[0][size_t(k)], c.centre[1][size_t(k)],
                                  c.centre[2][size_t(k)]};
    return lanes::SphereOutside<OneLane>(lanes::to_lanes(p), centre, c.radius[size_t(k)]) ? k : -1;
}

DirectSample next_event(const Scene& scene,
                        const LightSet& lights,
                        const Estimator& config,
                        const Vertex& v,
                        Vec3 wo,
                        const VertexSamples& u) {
    if (!samples_lights(config, v, lights)) return {};
    const LightChoice light = lights.select(u.light_select, v.p, v.ng);
    DirectSample d = next_event(scene, lights, v, wo, u, light);
    d.select_total = light.total;
    return d;
}

DirectSample next_event(const Scene& scene,
                        const LightSet& lights,
                        const Vertex& v,
                        Vec3 wo,
                        const VertexSamples& u,
                        LightChoice choice) {
    const int32_t planar = planar_light_sample_at(v, lights, choice);
    const int32_t sphere = planar < 0 ? sphere_light_sample_at(v, lights, choice) : -1;
    const int32_t delta = delta_light_sample_at(is_lane_vertex(v), lights, choice);
    const bool environment =
        planar < 0 && sphere < 0 && delta < 0 && environment_light_sample_at(v, lights, choice);
    if (planar < 0 && sphere < 0 && delta < 0 && !environment)
        return sample_direct(scene, lights, v, wo, choice, u.light_u, u.light_v);
    using lanes::to_lanes, lanes::to_vec3;
    const lanes::LightSampleVertex<OneLane> lv{
        to_lanes(v.p),           to_lanes(v.ng), to_lanes(v.frame.n), to_lanes(wo),
        lanes::to_lanes(v.bsdf), u.light_u,      u.light_v,           v.geometric_side_test};
    const size_t k = size_t(planar >= 0 ? planar : sphere >= 0 ? sphere : delta);
    auto fetch = [&](const std::vector<float>& column) { return column[k]; };
    const lanes::LightPoint<OneLane> point =
        delta >= 0 ? lanes::DeltaLightPoint(
                         lv.p, lanes::DeltaLightFrom<OneLane>(lights.delta_light_columns(), fetch,
                                                              choice.probability))
        : environment ? lanes::EnvironmentLightPoint<OneLane>(
                            lights.environment_view(), lights.environment_tables(), u.light_u,
                            u.light_v, choice.probability)
        : planar >= 0 ? lanes::PlanarLightPoint(
                            lv.p,
                            lanes::PlanarLightFrom<OneLane>(lights.planar_emitter_columns(), fetch,
                                                            choice.probability),
                            u.light_u, u.light_v)
                      : lanes::SphereLightPoint(
                            lv.p,
                            lanes::SphereLightFrom<OneLane>(lights.sphere_emitter_columns(), fetch,
                                                            choice.probability),
                            u.light_u, u.light_v);
    const lanes::VertexLightSample<OneLane> r = lanes::SampleTowards(lv, point);
    DirectSample d;
    if (!r.valid) return d;
    d.value = to_vec3(r.value);
    d.pdf_light = r.pdf_light;
    d.pdf_bsdf = delta >= 0 ? 0.0f : r.pdf_bsdf;  // no BSDF sample finds a delta light
    d.shadow = Ray{to_vec3(r.origin), to_vec3(r.wi), 0.0f, r.tmax};
    d.valid = true;
    return d;
}

bool scatters_in_medium(const Scene& scene,
                        MediumId m,
                        const Ray& ray,
                        const Hit& hit,
                        float dir_length,
                        float& flight,
                        float* s,
                        Color* weight) {
    *weight = Color(1.0f);
    if (m == kNone) return false;
    const float seg = hit.found() ? (hit.t - ray.tmin) * dir_length : kInfinity;
    const Medium& medium = scene.media[m];
    if (medium.heterogeneous())
        return grid_flight(medium, scene.volume_grids[medium.density_grid], ray.at(ray.tmin),
                           ray.d / dir_length, seg, flight, s, weight);
    if (medium.chromatic()) {
        const ChromaticFlight f = chromatic_flight(medium.sigma_t, seg, flight);
        *s = f.dist;
        *weight = f.weight;
        return f.scatters;
    }
    return lanes::ScattersInMedium<OneLane>(seg, medium.sigma_t.x, &flight, s);
}

float sheet_transmittance(const Scene& scene, const SurfaceHit& s, Vec3 dir) {
    const Vertex v = surface_vertex(scene, s, -dir);
    const float cos_i = std::fabs(dot(dir, v.frame.n));
    return cos_i > 0.0f ? 1.0f - thin_dielectric_reflectance(cos_i, v.bsdf.eta) : 0.0f;
}

Ray cross_boundary(const Scene& scene, const SurfaceHit& s, Vec3 dir, MediumStack& media) {
    media.cross(s.interior, s.front_face, scene.medium_boundaries);
    return Ray{s.p + origin_offset(s.p) * dir, dir};
}

SegmentResult resolve_segment(const Scene& scene,
                              const LightSet& lights,
                              const Estimator& config,
                              const Ray& ray,
                              const Hit& hit,
                              MediumStack& media,
                              float& flight,
                              const PreviousVertex& prev) {
    SegmentResult r;
    const float dir_length = length(ray.d);
    const Vec3 dir = ray.d / dir_length;
    const MediumId m = media.current();
    if (float s; scatters_in_medium(scene, m, ray, hit, dir_length, flight, &s, &r.weight)) {
        r.event = SegmentEvent::Scatter;
        r.vertex = medium_vertex(scene, m, scattering_point(ray, s, dir_length));
        r.wo = -dir;
        return r;
    }
    // Emission found by this segment, with the density with which the previous vertex's light
    // sampling would have produced it, which the MIS weight needs.
    auto found = [&](Color le, PrimRef prim, float dist) {
        r.event = SegmentEvent::Emission;
        r.emission = le;
        if (config.strategy == Strategy::Mis && !prev.counts_fully)
            r.emission_pdf_light =
                prim.valid()
                    ? lights.pdf_prim(scene, prev.p, prev.n, prev.select_total, prim, dir, dist)
                    : lights.pdf_background(scene, prev.p, prev.n, prev.select_total, dir);
    };
    if (!hit.found()) {
        r.at_infinity = true;
        if (lights.has_environment()) {  // the formula the wavefront's shade runs in lanes
            const bool with_pdf = config.strategy == Strategy::Mis && !prev.counts_fully;
            float u, v;
            lanes::EnvironmentUvOfRay<OneLane>(lights.environment_view(), lanes::to_lanes(ray.d),
                                               &u, &v);
            const lanes::EscapedRay<OneLane> e = lanes::Escape<OneLane>(
                lights.environment_view(), lights.environment_tables(), u, v,
                with_pdf
                    ? lights.background_selection_probability(prev.p, prev.n, prev.select_total)
                    : 0.0f,
                with_pdf);
            r.event = SegmentEvent::Emission;
            r.emission = lanes::to_vec3(e.radiance);
            r.emission_pdf_light = e.pdf_light;
        } else if (!scene.background.is_black()) {
            found(eval_background(scene, dir), PrimRef{}, kInfinity);
        }
        return r;
    }
    SurfaceHit s = surface_at(scene, ray, hit);
    const MaterialKind kind = scene.materials[s.material].kind;
    if (kind == MaterialKind::Interface) {
        r.event = SegmentEvent::Cross;
        r.next = cross_boundary(scene, s, dir, media);
        return r;
    }
    if (const Material& mat = scene.materials[s.material]; mat.is_emissive()) {
        Color le = emitted_radiance(scene, s, -dir);
        if (max_component(le) > 0.0f) found(le, hit.prim, length(s.p - prev.p));
        // An emitter that also reflects (an albedo, e.g. an MTL light with Kd, or any emissive
        // material but diffuse_light): its emission is counted here and the path scatters on.
        if (kind == MaterialKind::DiffuseLight && mat.albedo == kNone) return r;
        r.event = SegmentEvent::Scatter;
        r.vertex = surface_vertex(scene, s, -dir);
        r.wo = -dir;
        return r;
    }
    r.event = SegmentEvent::Scatter;
    r.vertex = surface_vertex(scene, s, -dir);
    r.wo = -dir;
    return r;
}

bool takes_lane_step(const Estimator& config, const Vertex& v, const LightSet& lights) {
    return is_lane_vertex(v) && !one_sample_continuation(config.strategy, v, lights);
}

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
                       float u_roulette) {
    PathStep step;
    if (takes_lane_step(config, v, lights)) {
        using lanes::to_lanes, lanes::to_vec3;
        const lanes::StepVertex<OneLane> lv{to_lanes(v.p),
                                            to_lanes(v.ng),
                                            to_lanes(v.frame.n),
                                            to_lanes(wo),
                                            lanes::to_lanes(v.bsdf),
                                            to_lanes(beta),
                                            u.lobe,
                                            u.bsdf_u1,
                                            u.bsdf_u2,
                                            u_roulette,
                                            depth + 1 >= config.rr_depth,
                                            eta_scale,
                                            v.geometric_side_test};
        const lanes::StepResult<OneLane> r = lv.bsdf.delta      ? lanes::SpecularStep(lv)
                                             : lv.bsdf.glossy() ? lanes::GlossyStep(lv)
                                             : lv.bsdf.phase    ? lanes::PhaseStep(lv)
                                                                : lanes::LambertianStep(lv);
        if (!r.alive) return step;
        step.weight = to_vec3(r.weight);
        // Emission found after a delta lobe counts fully: no light sample could have found it.
        step.prev = {v.p, r.pdf, r.delta || lights.empty(), v.ng};
        step.next = Ray{to_vec3(r.origin), to_vec3(r.wi)};
        step.eta_scale = r.eta_scale;
        if (r.transmitted)
            media.cross(v.interior, dot(step.next.d, v.ng) < 0.0f, scene.medium_boundaries);
        step.alive = true;
        return step;
    }
    Continuation c = sample_continuation(config.strategy, scene, lights, v, wo, u);
    if (!c.valid) return step;
    step.eta_scale = eta_scale;
    if (c.transmitted && (v.bsdf.kind == MaterialKind::Dielectric ||
                          (v.bsdf.kind == MaterialKind::Principled && !v.bsdf.principled.thin))) {
        const float eta = lanes::SeenEta<OneLane>(v.bsdf.eta, dot(wo, v.frame.n));
        step.eta_scale *= eta * eta;
    }
    const lanes::Roulette<OneLane> rr = lanes::RussianRoulette<OneLane>(
        lanes::to_lanes(beta * c.weight * step.eta_scale), u_roulette,
        depth + 1 >= config.rr_depth);
    if (!rr.survives) return step;
    step.weight = c.weight * rr.scale;
    if (c.transmitted) media.cross(v.interior, dot(c.wi, v.ng) < 0.0f, scene.medium_boundaries);
    step.passed_sheet = c.transmitted && v.bsdf.kind == MaterialKind::ThinDielectric;
    step.prev = step.passed_sheet ? prev
                                  : PreviousVertex{v.p, c.pdf_bsdf,
                                                   c.delta || !can_sample_lights(v, lights), v.ng};
    step.next = Ray{offset_origin(v, c.wi), c.wi};
    step.alive = true;
    return step;
}

VertexSamples vertex_samples(const Sampler& sampler,
                             uint32_t pixel,
                             uint32_t sample,
                             int bounce,
                             bool one_sample,
                             float* next_flight) {
    // The vertex's pairs side by side in lanes: what the wavefront's rows draw, bit for bit.
    float u[kBounceDims];
    draw_bounce_dims(sampler, pixel, sample, bounce, one_sample, u, next_flight);
    return vertex_samples_of([&](BounceDim d) { return u[d]; });
}

Ray generate_camera_ray(
    const CameraRays& camera, const Sampler& sampler, uint32_t pixel, uint32_t sample, int x, int y) {
    lanes::V3<float> o, d;
    lanes::SampledCameraRay<OneLane>(camera.frame(), lanes::PathState<OneLane>(sampler, pixel, sample),
                                     float(x), float(y), &o, &d);
    return Ray{lanes::to_vec3(o), lanes::to_vec3(d)};
}

float segment_flight(
    const Scene& scene, const Sampler& sampler, uint32_t pixel, uint32_t sample, int bounce) {
    if (scene.media.empty()) return 0.0f;
    const auto state = lanes::PathState<OneLane>(sampler, pixel, sample);
    return lanes::OpticalDepth<OneLane>(
        lanes::SampleDim<OneLane>(state, bounce_dim(bounce, kDimMediumDistance)));
}

}  // namespace wavetrace
