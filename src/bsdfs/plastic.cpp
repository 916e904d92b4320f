#include "bsdfs/plastic.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "bsdfs/fresnel.h"
#include "microfacets/microfacet.h"
#include "sampling/warp.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {

float CoatingTable::transmittance_at(float cos_theta) const {
    const float x = std::clamp(cos_theta, 0.0f, 1.0f) * float(kSize - 1);
    const int i = std::min(static_cast<int>(x), kSize - 2);
    const float w = x - float(i);
    return (1.0f - w) * transmittance[i] + w * transmittance[i + 1];
}

float plastic_internal_reflectance(float eta) {
    return -1.440f / (eta * eta) + 0.710f / eta + 0.668f + 0.0636f * eta;
}

namespace {

// The directional albedo of the coating's specular reflection F D G1(o) G1(i) / (4 cos_o) from
// o = (sqrt(1 - mu^2), 0, mu): the mean of F(o.m) G1(i) over its visible normals m, taken on an
// n x n midpoint grid of the sampling square (sample_visible maps it onto the visible normals
// with their density, so the grid's mean is the integral).
double specular_albedo(const MicrofacetDistribution& md, float mu, float eta, int n) {
    const Vec3 o{std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu};
    double sum = 0.0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const Vec3 m = md.sample_visible(o, (a + 0.5f) / n, (b + 0.5f) / n);
            const float cos_om = dot(o, m);
            const Vec3 i = 2.0f * cos_om * m - o;
            if (!(cos_om > 0.0f) || !(i.z > 0.0f)) continue;
            sum += double(fresnel_dielectric(cos_om, eta)) * md.g1(i);
        }
    return sum / (double(n) * n);
}

// The coating's transmittance from o = (sqrt(1 - mu^2), 0, mu) into the material: the mean of
// (1 - F(o.m)) G1(t) over o's visible normals m, t the refraction of o at m, on the same grid
// (Mitsuba 3's eval_transmittance: light refracted into a facet that the surface then masks
// does not reach the base).
double specular_transmittance(const MicrofacetDistribution& md, float mu, float eta, int n) {
    const Vec3 o{std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu};
    double sum = 0.0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const Vec3 m = md.sample_visible(o, (a + 0.5f) / n, (b + 0.5f) / n);
            const float cos_om = dot(o, m);
            const float sin2_t = (1.0f - cos_om * cos_om) / (eta * eta);
            if (!(cos_om > 0.0f) || !(sin2_t < 1.0f)) continue;
            const float cos_t = std::sqrt(1.0f - sin2_t);
            const Vec3 t = -o / eta + (cos_om / eta - cos_t) * m;
            if (!(t.z < 0.0f)) continue;
            sum += double(1.0f - fresnel_dielectric(cos_om, eta)) * md.g1(t);
        }
    return sum / (double(n) * n);
}

// The probability of the specular lobe given its share E of the light (see plastic.h).
float specular_probability(float e, float w) {
    const float s = e * w, d = (1.0f - e) * (1.0f - w);
    return s + d > 0.0f ? s / (s + d) : 0.0f;
}

// The base's reflectance seen through the coating's inner bounces, over eta^2.
Color base_reflectance(const BsdfParams& b, float fdr) {
    const Color r = b.albedo;
    const Color denom = b.nonlinear ? Color(1.0f) - r * fdr : Color(1.0f - fdr);
    return r / denom / (b.eta * b.eta);
}

struct Lobes {
    Color value{0.0f};  // f cos_i of the non-delta lobes
    float pdf = 0.0f;   // their density, each weighted by its probability
};

// Both directions above the surface.
Lobes eval_plastic_upper(const BsdfParams& b, Vec3 o, Vec3 i) {
    Lobes l;
    if (b.alpha == 0.0f) {
        const float fo = fresnel_dielectric(o.z, b.eta), fi = fresnel_dielectric(i.z, b.eta);
        const float p_spec = specular_probability(fo, b.specular_weight);
        l.value = base_reflectance(b, plastic_internal_reflectance(b.eta)) *
                  ((1.0f - fo) * (1.0f - fi) * i.z * kInvPi);
        l.pdf = (1.0f - p_spec) * i.z * kInvPi;
        return l;
    }
    const CoatingTable& table = *b.coating;
    const float to = table.transmittance_at(o.z), ti = table.transmittance_at(i.z);
    const float p_spec = specular_probability(1.0f - to, b.specular_weight);
    const MicrofacetDistribution md = microfacet_of(b);
    const Vec3 h = normalize(o + i);
    const float d = md.d(h), g1_o = md.g1(o);
    const float spec = fresnel_dielectric(dot(o, h), b.eta) * d * g1_o * md.g1(i) / (4.0f * o.z);
    l.value = b.specular * spec +
              base_reflectance(b, table.internal_reflectance) * (to * ti * i.z * kInvPi);
    l.pdf = p_spec * g1_o * d / (4.0f * o.z) + (1.0f - p_spec) * i.z * kInvPi;
    return l;
}

}  // namespace

CoatingTable rough_coating_table(Microfacet distribution, float alpha, float eta) {
    // 64 x 64 normals per direction: the albedos agree with a 256 x 256 grid to 1e-4 for
    // alpha >= 0.01 (tests/test_plastic.cpp).
    constexpr int kGrid = 64;
    const MicrofacetDistribution md{distribution, alpha, alpha};
    CoatingTable t;
    // The entries in parallel (a scene's load waits on them: 0.5 M visible normals a table),
    // the inner reflectance's sum in order, so that the table is the same on any thread count.
    double inner_terms[CoatingTable::kSize];
    tbb::parallel_for(0, CoatingTable::kSize, [&](int k) {
        const float mu = std::max(1e-6f, float(k) / float(CoatingTable::kSize - 1));
        t.transmittance[k] = float(specular_transmittance(md, mu, eta, kGrid));
        inner_terms[k] = mu * specular_albedo(md, mu, 1.0f / eta, kGrid);
    });
    double inner = 0.0;
    for (const double term : inner_terms) inner += term;
    t.internal_reflectance = float(2.0 * inner / CoatingTable::kSize);
    return t;
}

Color plastic_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    *pdf = 0.0f;
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return {};
    const Lobes l = eval_plastic_upper(b, wo, wi);
    *pdf = l.pdf;
    return l.value;
}

BsdfSample plastic_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2) {
    BsdfSample s;
    if (!(wo.z > 0.0f)) return s;
    if (b.alpha == 0.0f) {
        const float fo = fresnel_dielectric(wo.z, b.eta);
        const float p_spec = specular_probability(fo, b.specular_weight);
        if (u_lobe < p_spec) {
            s.wi = {-wo.x, -wo.y, wo.z};
            s.weight = b.specular * (fo / p_spec);
            s.delta = s.valid = true;
            return s;
        }
    }
    Vec3 i;
    if (b.alpha > 0.0f && u_lobe < specular_probability(1.0f - b.coating->transmittance_at(wo.z),
                                                        b.specular_weight)) {
        const Vec3 m = microfacet_of(b).sample_visible(wo, u1, u2);
        i = 2.0f * dot(wo, m) * m - wo;
    } else {
        i = sample_cosine_hemisphere(u1, u2);
    }
    if (!(i.z > 0.0f)) return s;  // reflected below the surface: lost
    // The value and density from (wo, i) as eval computes them, so that weight = eval / pdf.
    const Lobes l = eval_plastic_upper(b, wo, i);
    if (!(l.pdf > 0.0f)) return s;
    s.wi = i;
    s.pdf = l.pdf;
    s.weight = l.value / l.pdf;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
