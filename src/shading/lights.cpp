#include "shading/lights.h"

#include <algorithm>
#include <cmath>

#include "accel/intersect.h"
#include "lights/environment_light-inl.h"
#include "lights/light_bounds.h"
#include "lights/sphere_light-inl.h"
#include "sampling/warp.h"
#include "scene/delta_lights.h"
#include "scene/material_lookup.h"
#include "shading/path_vertex.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/surface.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane, lanes::to_lanes, lanes::to_vec3;
namespace {

// Geometry of a sphere seen from outside: the cone of directions it subtends.
struct SphereCone {
    float one_minus_cos;  // 1 - cos(theta_max), computed without cancellation
    bool outside;
};
SphereCone sphere_cone(const Sphere& s, Point3 ref) {
    if (!lanes::SphereOutside<OneLane>(to_lanes(ref), to_lanes(s.center), s.radius))
        return {0.0f, false};
    return {lanes::SphereConeOneMinusCos<OneLane>(to_lanes(ref), to_lanes(s.center), s.radius),
            true};
}

}  // namespace

LightSet::LightSet(const Scene& scene, bool mis_compensation) {
    emitters_ = collect_emitters(scene);
    std::vector<float> power;
    std::vector<LightBounds> light_bounds;
    // Each light its own group, but the emissive triangles of one material (a mesh light) one.
    std::vector<uint32_t> group;
    for (uint32_t i = 0; i < emitters_.size(); ++i) {
        PrimRef prim = emitters_[i];
        index_[prim.bits] = i;
        const Material& m = scene.materials[scene.prim_material(prim)];
        const Texture& e = scene.textures[m.emission];
        float lum = e.kind == TextureKind::Solid ? luminance(e.color) : 1.0f;
        // The lanes' emitters emit one radiance in every direction.
        const bool uniform = e.kind == TextureKind::Solid && !m.coats_emission();
        power.push_back(scene.prim_area(prim) * kPi * lum * (m.two_sided ? 2.0f : 1.0f));
        light_bounds.push_back(emitter_bounds(scene, prim, lum, m.two_sided || !uniform));
        const bool triangle = prim.kind() == PrimKind::Triangle;
        group.push_back(triangle ? scene.prim_material(prim) : LightSelection::kOwnGroup);
        planar_of_.push_back(-1);
        if ((prim.kind() == PrimKind::Quad || triangle) && uniform) {
            // A quad's corner and edges, or a triangle's first vertex and the edges from it.
            Point3 q;
            Vec3 u, v;
            if (triangle) {
                const Triangle& t = scene.triangles[prim.index()];
                q = scene.positions[t.v[0]];
                u = scene.positions[t.v[1]] - q;
                v = scene.positions[t.v[2]] - q;
            } else {
                const Quad& quad = scene.quads[prim.index()];
                q = quad.q;
                u = quad.u;
                v = quad.v;
            }
            PlanarEmitterColumns& c = planar_columns_;
            planar_of_.back() = static_cast<int32_t>(c.area.size());
            const Normal3 n = normalize(cross(u, v));
            for (int a = 0; a < 3; ++a) {
                c.q[a].push_back(q[a]);
                c.u[a].push_back(u[a]);
                c.v[a].push_back(v[a]);
                c.n[a].push_back(n[a]);
                c.radiance[a].push_back(e.color[a]);
            }
            c.area.push_back(scene.prim_area(prim));
            c.two_sided.push_back(m.two_sided ? 1.0f : 0.0f);
            c.triangle.push_back(triangle ? 1.0f : 0.0f);
        }
        sphere_of_.push_back(-1);
        if (prim.kind() == PrimKind::Sphere && uniform) {
            const Sphere& sp = scene.spheres[prim.index()];
            SphereEmitterColumns& c = sphere_columns_;
            sphere_of_.back() = static_cast<int32_t>(c.radius.size());
            for (int a = 0; a < 3; ++a) {
                c.centre[a].push_back(sp.center[a]);
                c.radiance[a].push_back(e.color[a]);
            }
            c.radius.push_back(sp.radius);
            c.two_sided.push_back(m.two_sided ? 1.0f : 0.0f);
        }
    }
    const size_t emitters = emitters_.size();
    std::vector<float> area_power = power;
    const Aabb bounds = scene.bounds();
    const float scene_radius = bounds.empty() ? 1.0f : 0.5f * length(bounds.extent());
    for (const Light& l : scene.lights) {
        power.push_back(delta_light_power(scene, l, scene_radius));
        light_bounds.push_back(delta_light_bounds(scene, l, scene_radius));
        group.push_back(LightSelection::kOwnGroup);
        delta_of_.push_back(-1);
        const bool directional = l.kind == Light::Kind::Directional;
        if (!directional && l.kind != Light::Kind::Point) continue;
        DeltaLightColumns& c = delta_columns_;
        delta_of_.back() = static_cast<int32_t>(c.directional.size());
        const Vec3 at = directional ? -l.direction : l.position;
        for (int a = 0; a < 3; ++a) {
            c.at[a].push_back(at[a]);
            c.intensity[a].push_back(l.intensity[a]);
        }
        c.directional.push_back(directional ? 1.0f : 0.0f);
    }
    delta_count_ = scene.lights.size();
    background_ = !scene.background.is_black();
    if (background_) {
        const Background& bg = scene.background;
        const float r = scene_radius;
        float lum = luminance(bg.radiance);
        if (bg.kind == Background::Kind::Environment) {
            const ImageData& img = scene.images[bg.image];
            // Texel weights: luminance (with MIS compensation, its excess over the mean radiance,
            // where that excess carries at least 1% of the map's light) times the texel's solid
            // angle (for a latitude-longitude map, in proportion to sin(theta), the area of its
            // band of the sphere; equal-area texels are all alike), plus a small floor so that
            // no direction the lookup can light has zero density.
            const bool equal_area = bg.mapping == Background::Mapping::EqualArea;
            auto area = [&](int y) {
                return equal_area ? 1.0f : std::sin(kPi * (y + 0.5f) / img.height);
            };
            std::vector<float> w(static_cast<size_t>(img.width) * img.height);
            double mean = 0, total_area = 0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    float v = luminance(img.texel(x, y)) * area(y);
                    w[static_cast<size_t>(y) * img.width + x] = v;
                    mean += v;
                    total_area += area(y);
                }
            // The mean radiance over the sphere, each texel weighted by its solid angle.
            const double mean_radiance = mean / total_area;
            mean /= static_cast<double>(w.size());
            double w_mean = mean;  // of the weights sampled by
            if (mis_compensation) {
                std::vector<float> excess(w.size());
                double sum = 0;
                for (int y = 0; y < img.height; ++y)
                    for (int x = 0; x < img.width; ++x) {
                        const size_t i = static_cast<size_t>(y) * img.width + x;
                        const double l = luminance(img.texel(x, y));
                        excess[i] = static_cast<float>(std::max(0.0, l - mean_radiance) * area(y));
                        sum += excess[i];
                    }
                // A map (nearly) constant has (almost) no excess: it keeps the plain weights.
                if (sum >= 0.01 * mean * static_cast<double>(w.size())) {
                    w = std::move(excess);
                    w_mean = sum / static_cast<double>(w.size());
                    environment_compensated_ = true;
                }
            }
            for (float& v : w) v += static_cast<float>(1e-3 * w_mean) + 1e-12f;
            environment_ = Distribution2D(w, img.width, img.height);
            environment_view_ = wavetrace::environment_view(scene);
            // The mean luminance over the sphere (the mean of sin(theta) over rows is 2 / pi).
            lum *= static_cast<float>(equal_area ? mean : mean * 2.0 / kPi);
        }
        power.push_back(4.0f * kPi * kPi * r * r * lum);
        area_power.push_back(power.back());
        LightBounds b;
        b.kind = LightBounds::Kind::Background;
        b.phi = lum;
        light_bounds.push_back(b);
        group.push_back(LightSelection::kOwnGroup);
    }
    count_ = power.size();
    if (count_ > 0) selection_ = LightSelection(power, light_bounds, group);
    if (delta_count_ > 0 && !area_power.empty()) {
        area_select_ = Distribution1D(area_power);
        double share = 0;
        for (size_t i = 0; i < count_; ++i)
            if (i < emitters || i >= emitters + delta_count_)
                share += selection_.power_probability(i);
        area_fraction_ = static_cast<float>(share);
    }
}

float LightSet::selection_probability(PrimRef prim, Point3 p, Normal3 n, float total) const {
    auto it = index_.find(prim.bits);
    return it == index_.end() ? 0.0f : selection_.probability(it->second, p, n, total);
}

float LightSet::background_selection_probability(Point3 p, Normal3 n, float total) const {
    return background_ ? selection_.probability(count_ - 1, p, n, total) : 0.0f;
}

LightSample LightSet::sample_direction_light(
    const Scene& scene, Point3 ref, float u_select, float u1, float u2) const {
    if (!has_area_lights()) return {};
    if (delta_count_ == 0) return sample(scene, ref, selection_.select_by_power(u_select), u1, u2);
    // Among the other lights alone; its density's selection factor is the light's share of
    // their power, select_'s probability / area_fraction_ (pdf_direction).
    LightChoice c;
    c.index = area_select_.sample_discrete(u_select, &c.probability);
    if (c.index >= emitters_.size()) c.index = count_ - 1;  // the background
    return sample(scene, ref, c, u1, u2);
}

LightSample LightSet::sample(
    const Scene& scene, Point3 ref, LightChoice choice, float u1, float u2) const {
    LightSample ls;
    if (count_ == 0) return ls;
    const float select_prob = choice.probability;
    const size_t i = choice.index;

    if (i >= emitters_.size() && i < emitters_.size() + delta_count_) {
        const Light& l = scene.lights[i - emitters_.size()];
        ls.pdf = select_prob;
        ls.delta = true;
        if (const int32_t k = delta_of_[i - emitters_.size()]; k >= 0) {  // point, directional
            auto fetch = [&](const std::vector<float>& column) { return column[size_t(k)]; };
            const lanes::LightPoint<OneLane> point = lanes::DeltaLightPoint(
                to_lanes(ref), lanes::DeltaLightFrom<OneLane>(delta_columns_, fetch, select_prob));
            ls.wi = to_vec3(point.wi);
            ls.dist = point.dist;
            ls.radiance = to_vec3(point.radiance);
            ls.valid = point.valid;
            return ls;
        }
        // A spot's or projector's intensity / d^2 along the direction to the light.
        const Vec3 d = l.position - ref;
        const float dist2 = length_squared(d);
        if (!(dist2 > 0.0f)) return ls;
        ls.dist = std::sqrt(dist2);
        ls.wi = d / ls.dist;
        ls.radiance = delta_light_intensity(scene, l, -ls.wi) / dist2;
        ls.valid = std::isfinite(ls.dist) && ls.pdf > 0.0f;
        return ls;
    }

    if (background_ && i == count_ - 1) {
        const Background& bg = scene.background;
        float pdf;
        if (bg.kind == Background::Kind::Constant) {
            ls.wi = sample_uniform_sphere(u1, u2);
            pdf = uniform_sphere_pdf();
        } else {
            const lanes::LightPoint<OneLane> point = lanes::EnvironmentLightPoint<OneLane>(
                environment_view_, environment_.tables(), u1, u2, select_prob);
            return environment_light_sample(to_vec3(point.wi), to_vec3(point.radiance), point.pdf);
        }
        ls.radiance = eval_background(scene, ls.wi);
        ls.pdf = pdf * select_prob;
        ls.valid = ls.pdf > 0.0f;
        return ls;
    }

    // A point on an emissive primitive, expressed as a Hit along the segment ref -> point
    // (t = 1) so that surface_at() supplies its normal, uv and side like any other hit.
    PrimRef prim = emitters_[i];
    Hit hit{1.0f, prim, 0.0f, 0.0f};
    Point3 p;
    float pdf_solid = 0;
    switch (prim.kind()) {
        case PrimKind::Quad: {
            const Quad& q = scene.quads[prim.index()];
            hit.u = u1;
            hit.v = u2;
            p = q.q + u1 * q.u + u2 * q.v;
            break;
        }
        case PrimKind::Triangle: {
            const Triangle& t = scene.triangles[prim.index()];
            sample_uniform_triangle(u1, u2, &hit.u, &hit.v);
            p = (1 - hit.u - hit.v) * scene.positions[t.v[0]] + hit.u * scene.positions[t.v[1]] +
                hit.v * scene.positions[t.v[2]];
            break;
        }
        case PrimKind::Sphere: {
            const Sphere& s = scene.spheres[prim.index()];
            SphereCone cone = sphere_cone(s, ref);
            if (cone.outside) {
                p = to_vec3(lanes::SphereConePoint<OneLane>(to_lanes(ref), to_lanes(s.center),
                                                            s.radius, u1, u2, &pdf_solid));
            } else {
                p = s.center + s.radius * sample_uniform_sphere(u1, u2);
            }
            break;
        }
    }
    Vec3 d = p - ref;
    float dist2 = length_squared(d);
    if (!(dist2 > 0.0f)) return ls;
    ls.dist = std::sqrt(dist2);
    ls.wi = d / ls.dist;
    SurfaceHit sh = surface_at(scene, Ray{ref, d}, hit);
    if (pdf_solid == 0.0f) {
        float cos_l = std::fabs(dot(sh.ng, ls.wi));
        if (cos_l <= 0.0f) return ls;
        pdf_solid = uniform_area_to_solid_angle(dist2, cos_l, scene.prim_area(prim));
    }
    ls.radiance = emitted_radiance(scene, sh, -ls.wi);
    ls.pdf = pdf_solid * select_prob;
    ls.prim = prim;
    ls.valid = std::isfinite(ls.pdf) && ls.pdf > 0.0f;
    return ls;
}

float LightSet::prim_pdf_given_selection(
    const Scene& scene, Point3 ref, PrimRef prim, Vec3 wi, float dist) const {
    if (prim.kind() == PrimKind::Sphere) {
        SphereCone cone = sphere_cone(scene.spheres[prim.index()], ref);
        if (cone.outside) return 1.0f / (2.0f * kPi * cone.one_minus_cos);
    }
    Point3 p = ref + dist * wi;
    Normal3 n;
    switch (prim.kind()) {
        case PrimKind::Quad:
            n = cross(scene.quads[prim.index()].u, scene.quads[prim.index()].v);
            break;
        case PrimKind::Triangle: {
            const Triangle& t = scene.triangles[prim.index()];
            n = cross(scene.positions[t.v[1]] - scene.positions[t.v[0]],
                      scene.positions[t.v[2]] - scene.positions[t.v[0]]);
            break;
        }
        case PrimKind::Sphere:
            n = p - scene.spheres[prim.index()].center;
            break;
    }
    float cos_l = std::fabs(dot(normalize(n), wi));
    if (cos_l <= 0.0f) return 0.0f;
    return uniform_area_to_solid_angle(dist * dist, cos_l, scene.prim_area(prim));
}

float LightSet::pdf_prim(const Scene& scene,
                         Point3 ref,
                         Normal3 ref_n,
                         float ref_total,
                         PrimRef prim,
                         Vec3 wi,
                         float dist) const {
    float sel = selection_probability(prim, ref, ref_n, ref_total);
    return sel > 0.0f ? sel * prim_pdf_given_selection(scene, ref, prim, wi, dist) : 0.0f;
}

float LightSet::background_pdf_given_selection(const Scene& scene, Vec3 wi) const {
    if (scene.background.kind == Background::Kind::Constant) return uniform_sphere_pdf();
    return lanes::EnvironmentPdf<OneLane>(environment_view_, environment_.tables(), to_lanes(wi));
}

float LightSet::pdf_background(
    const Scene& scene, Point3 ref, Normal3 ref_n, float ref_total, Vec3 wi) const {
    if (!background_) return 0.0f;
    return background_selection_probability(ref, ref_n, ref_total) *
           background_pdf_given_selection(scene, wi);
}

float LightSet::pdf_direction(const Scene& scene, Point3 ref, Vec3 wi) const {
    float pdf = background_ ? selection_.power_probability(count_ - 1) *
                                  background_pdf_given_selection(scene, wi)
                            : 0.0f;
    Ray ray{ref, wi};
    for (size_t k = 0; k < emitters_.size(); ++k) {
        const PrimRef prim = emitters_[k];
        PrimHit ph;
        bool hit = false;
        uint32_t i = prim.index();
        switch (prim.kind()) {
            case PrimKind::Quad: {
                const Quad& q = scene.quads[i];
                hit = intersect_quad(ray, q.q, q.u, q.v, &ph);
                break;
            }
            case PrimKind::Triangle: {
                const Triangle& t = scene.triangles[i];
                hit = intersect_triangle(ray, scene.positions[t.v[0]], scene.positions[t.v[1]],
                                         scene.positions[t.v[2]], &ph);
                break;
            }
            case PrimKind::Sphere: {
                const Sphere& s = scene.spheres[i];
                hit = intersect_sphere(ray, s.center, s.radius, &ph);
                break;
            }
        }
        if (hit && ph.t > 0.0f)
            pdf += selection_.power_probability(k) *
                   prim_pdf_given_selection(scene, ref, prim, wi, ph.t);
    }
    // The densities above select among all lights; sample_direction_light among all but the
    // point lights.
    return delta_count_ == 0 ? pdf : pdf / area_fraction_;
}

Color emitted_radiance(const Scene& scene, const SurfaceHit& hit, Vec3 wo) {
    if (hit.material == kNone) return {};
    const Material& m = scene.materials[hit.material];
    if (!m.is_emissive() || (!hit.front_face && !m.two_sided)) return {};
    const Color le = eval_texture(scene, m.emission, hit.uv, hit.p);
    if (!m.coats_emission()) return le;
    return le * emission_through_coat(scene, m, mapped_point(hit), wo);
}

}  // namespace wavetrace
