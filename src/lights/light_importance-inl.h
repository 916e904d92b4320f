// A light's importance at a point (lights/light_bounds.h), written once over lanes: each lane
// one light of a LightBoundsColumns, the point and its normal the same in all. LightSelection
// runs it over a scene's lights a vector at a time. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_LIGHTS_LIGHT_IMPORTANCE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_LIGHTS_LIGHT_IMPORTANCE_INL_H_
#undef WAVETRACE_LIGHTS_LIGHT_IMPORTANCE_INL_H_
#else
#define WAVETRACE_LIGHTS_LIGHT_IMPORTANCE_INL_H_
#endif

#include "lights/light_bounds.h"
#include "math/lanes-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// cos(max(a - b, 0)) and sin(max(a - b, 0)) from the cosines and sines of angles in [0, pi].
template <class L>
HWY_INLINE typename L::F CosOfDifference(typename L::F cos_a,
                                         typename L::F sin_a,
                                         typename L::F cos_b,
                                         typename L::F sin_b) {
    return L::Select(cos_a >= cos_b, L::Set(1.0f), cos_a * cos_b + sin_a * sin_b);
}
template <class L>
HWY_INLINE typename L::F SinOfDifference(typename L::F cos_a,
                                         typename L::F sin_a,
                                         typename L::F cos_b,
                                         typename L::F sin_b) {
    return L::Select(cos_a >= cos_b, L::Set(0.0f), sin_a * cos_b - cos_a * sin_b);
}

// Light k's bounds in lanes, from columns entry k (LightBoundsColumns' fields).
template <class L>
struct LightBoundsLanes {
    V3<typename L::F> centre, axis;
    typename L::F radius2, cos_o, sin_o, cos_e, two_sided, phi, kind;
};

// The bounds of LightBoundsColumns entries in lanes: get(column) gives a column's lanes (a load
// of consecutive entries, one entry broadcast, or one entry for OneLane).
template <class L, class Get>
HWY_INLINE LightBoundsLanes<L> LightBoundsFrom(const LightBoundsColumns& c, Get get) {
    return {{get(c.centre[0]), get(c.centre[1]), get(c.centre[2])},
            {get(c.axis[0]), get(c.axis[1]), get(c.axis[2])},
            get(c.radius2),
            get(c.cos_o),
            get(c.sin_o),
            get(c.cos_e),
            get(c.two_sided),
            get(c.phi),
            get(c.kind)};
}

// The importance at p (normal n; surface: the lanes where n is not zero) of the lights in the
// lanes, as light_bounds.h states it: one vertex and a light in each lane, or one light and a
// vertex in each. Without `cones` every light emits in every direction (cos_o -1), and the
// same result comes with less work.
template <class L>
HWY_INLINE typename L::F LightImportance(const LightBoundsLanes<L>& b,
                                         V3<typename L::F> p,
                                         V3<typename L::F> n,
                                         typename L::M surface,
                                         bool cones) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F min_cos_at_point = L::Set(1.0f / 16.0f);
    const V3<F> w = p - b.centre;  // from the light to the point
    const F d2 = Dot(w, w);
    // The half-angle theta_b of the cone from p that holds the light's sphere (every direction
    // from inside it; none for a point).
    const F sin2_b =
        L::Select(b.radius2 > zero, L::Select(d2 > b.radius2, b.radius2 / d2, one), zero);
    const F sin_b = L::Sqrt(sin2_b), cos_b = L::Sqrt(L::Max(one - sin2_b, zero));
    const F d = L::Sqrt(d2);
    const V3<F> wn = Select3<L>(d > zero, w * (one / d), b.axis);
    F cos_p = one;
    auto beyond = zero > one;  // outside the cone: none (no lane, yet)
    if (cones) {
        // theta' = max(theta_w - theta_o - theta_b, 0), theta_w between the axis and wn.
        F cos_w = Dot(b.axis, wn);
        cos_w = L::Select(b.two_sided > zero, L::Abs(cos_w), cos_w);
        const F sin_w = L::Sqrt(L::Max(one - cos_w * cos_w, zero));
        const F cos_x = CosOfDifference<L>(cos_w, sin_w, b.cos_o, b.sin_o);
        const F sin_x = SinOfDifference<L>(cos_w, sin_w, b.cos_o, b.sin_o);
        const auto cone = b.cos_o > L::Set(-1.0f);
        cos_p = L::Select(cone, CosOfDifference<L>(cos_x, sin_x, cos_b, sin_b), one);
        beyond = L::And(cone, cos_p < b.cos_e);
    }
    F importance = b.phi * cos_p / L::Max(L::Max(d2, L::Set(0.5f) * b.radius2), L::Set(1e-20f));
    importance = L::Select(beyond, zero, importance);
    F directional = b.phi, background = b.phi * L::Set(4.0f * kPi);
    if (L::Any(surface)) {
        const F cos_i = L::Abs(Dot(n, wn));
        const F sin_i = L::Sqrt(L::Max(one - cos_i * cos_i, zero));
        importance = L::Select(
            surface,
            importance * L::Max(CosOfDifference<L>(cos_i, sin_i, cos_b, sin_b), min_cos_at_point),
            importance);
        directional = L::Select(surface, b.phi * L::Max(L::Abs(Dot(b.axis, n)), min_cos_at_point),
                                directional);
        background = L::Select(surface, b.phi * L::Set(kPi), background);
    }
    importance = L::Max(importance, zero);
    const F kind = b.kind;
    return L::Select(
        kind == L::Set(float(LightBounds::Kind::Directional)), directional,
        L::Select(kind == L::Set(float(LightBounds::Kind::Background)), background, importance));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_LIGHTS_LIGHT_IMPORTANCE_INL_H_
