// The continuation of a path at a Lambertian or a glossy surface vertex (glossy-inl.h), or at a
// vertex in a medium of isotropic phase function, sampled by the BSDF (cosine-weighted / each
// glossy lobe's / uniform sphere), with Russian roulette and the next ray's origin: what
// continue_path does at such a vertex, written once over lanes. The megakernel runs
// it with OneLane inside continue_path; the wavefront's shade kernel runs it over the surface
// vertices of a chunk, a vector of paths at a time (blocks/lane_kernels.cpp). Per-target
// header, see math/lanes-inl.h.
#if defined(WAVETRACE_SHADING_SURFACE_STEP_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SHADING_SURFACE_STEP_INL_H_
#undef WAVETRACE_SHADING_SURFACE_STEP_INL_H_
#else
#define WAVETRACE_SHADING_SURFACE_STEP_INL_H_
#endif

#include "bsdfs/diffuse-inl.h"
#include "bsdfs/geometric_side-inl.h"
#include "bsdfs/glossy-inl.h"
#include "bsdfs/specular-inl.h"
#include "math/lanes-inl.h"
#include "sampling/warp-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Russian roulette survival probability for path throughput beta (times the path's eta scale):
// paths go on while max(beta) >= 1/2; below, one survives with probability 2 max(beta), its
// throughput raised back to 1/2 (a weight window's lower half). Chosen by efficiency,
// 1 / (rel. MSE x time) against converged references (docs/sampling.md): against the
// former clamp(max(beta), 0.05, 0.95) it ends fewer paths early that carry light.
template <class L>
HWY_INLINE typename L::F SurvivalProbability(V3<typename L::F> beta) {
    return L::Min(L::Max(MaxComponent<L>(beta), L::Set(1e-4f)) * L::Set(2.0f), L::Set(1.0f));
}

template <class L>
struct Roulette {
    typename L::M survives;
    typename L::F scale;  // the factor for the surviving throughput: 1 / q, or 1
};
// Russian roulette on the throughput beta after a vertex, where `applies` (the path is deep
// enough): the path survives with probability q = SurvivalProbability(beta), u < q, and its
// throughput is divided by q so that the estimate stays unbiased.
template <class L>
HWY_INLINE Roulette<L> RussianRoulette(V3<typename L::F> beta,
                                       typename L::F u,
                                       typename L::M applies) {
    const typename L::F q = SurvivalProbability<L>(beta);
    return {L::Or(L::Not(applies), u < q), L::Select(applies, L::Set(1.0f) / q, L::Set(1.0f))};
}

// A medium vertex has ng = 0 (Vertex::on_surface) and ns = +z (its frame): the geometric-side
// test then passes every direction, and the origin offset is zero.
template <class L>
struct StepVertex {
    V3<typename L::F> p, ng, ns;  // position, geometric and shading normals
    V3<typename L::F> wo;         // unit, pointing away from the vertex
    LaneBsdf<L> bsdf;
    V3<typename L::F> beta;              // path throughput before this vertex
    typename L::F u_lobe, u1, u2, u_rr;  // lobe, direction and Russian roulette samples
    typename L::M roulette;              // whether Russian roulette applies at this bounce
    typename L::F eta_scale;  // the path's eta scale (path_vertex.h): roulette weighs beta by it
    bool geometric_side_test = true;  // Scene::geometric_side_test
};

template <class L>
struct StepResult {
    typename L::M alive;           // false: no valid direction, or the path ended by roulette
    typename L::M transmitted;     // wi leaves through the surface (a dielectric's refraction)
    typename L::M delta;           // wi is a Dirac-delta lobe's (pdf 0)
    V3<typename L::F> origin, wi;  // the next ray
    V3<typename L::F> weight;      // f |cos| / p, divided by the survival probability
    typename L::F pdf;             // BSDF density of wi (for MIS at the emitter it may hit)
    typename L::F eta_scale;       // the path's eta scale after the vertex
};

// The part every lobe shares, for a sampled wi of throughput factor `weight` (ok: a valid
// sample; transmitted: wi refracted through the surface): reflection stays on wo's side of the
// geometric surface, so that light does not leak through it where the shading normal disagrees,
// and a transmission crosses it; a dielectric's refraction scales the path's eta scale by the
// squared relative index it crossed (into the dielectric from its front: eta; a thin-walled
// transmission crosses no index); Russian roulette on the throughput
// after this vertex; the origin just off the surface on wi's side.
template <class L>
HWY_INLINE StepResult<L> FinishStep(const StepVertex<L>& v,
                                    V3<typename L::F> wi,
                                    V3<typename L::F> weight,
                                    typename L::F pdf,
                                    typename L::M ok,
                                    typename L::M transmitted) {
    using F = typename L::F;
    StepResult<L> r;
    r.wi = wi;
    r.pdf = pdf;
    r.transmitted = transmitted;
    r.delta = L::Not(L::All());
    if (v.geometric_side_test)
        ok = L::AndNot(WrongGeometricSide<L>(v.wo, wi, v.ng, transmitted), ok);
    r.eta_scale = v.eta_scale;
    if (const auto refracted = L::And(transmitted, v.bsdf.dielectric); L::Any(refracted)) {
        const F eta = SeenEta<L>(v.bsdf.eta.x, Dot(v.wo, v.ns));
        r.eta_scale = L::Select(refracted, v.eta_scale * (eta * eta), v.eta_scale);
    }
    const Roulette<L> rr = RussianRoulette<L>(v.beta * weight * r.eta_scale, v.u_rr, v.roulette);
    r.alive = L::And(ok, rr.survives);
    r.weight = weight * rr.scale;
    r.origin = OffsetRayOrigin<L>(v.p, v.ng, wi);
    return r;
}

template <class L>
HWY_INLINE StepResult<L> LambertianStep(const StepVertex<L>& v) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    V3<F> s, t;
    OrthonormalBasis<L>(v.ns, &s, &t);
    // Reflection on wo's side of the shading surface: the local z of wi takes wo's sign.
    const F wo_z = Dot(v.wo, v.ns);
    const V3<F> h = CosineHemisphere<L>(v.u1, v.u2);
    const F wi_z = h.z * L::Select(wo_z < zero, L::Neg(one), one);
    const F pdf = LambertianPdf<L>(wi_z);
    const V3<F> wi = s * h.x + t * h.y + v.ns * wi_z;
    return FinishStep(v, wi, v.bsdf.albedo, pdf, L::And(wo_z != zero, pdf > zero),
                      L::Not(L::All()));
}

// A glossy lobe (LaneBsdf::glossy: a rough metal, conductor or dielectric, or a
// metallic-roughness surface): a sample of it in the shading frame.
template <class L>
HWY_INLINE StepResult<L> GlossyStep(const StepVertex<L>& v) {
    const GlossyLobeSample<L> m = GlossySample<L>(v.bsdf, v.ns, v.wo, v.u_lobe, v.u1, v.u2);
    return FinishStep(v, m.wi, m.weight, m.pdf, m.valid, m.transmitted);
}

// A Dirac-delta lobe (LaneBsdf::delta: a mirror, a smooth metal, conductor or dielectric).
template <class L>
HWY_INLINE StepResult<L> SpecularStep(const StepVertex<L>& v) {
    const GlossyLobeSample<L> m = SpecularSample<L>(v.bsdf, v.ns, v.wo, v.u_lobe);
    StepResult<L> r = FinishStep(v, m.wi, m.weight, m.pdf, m.valid, m.transmitted);
    r.delta = L::All();
    return r;
}

// The isotropic phase function, f = albedo / (4 pi): a uniform direction of weight albedo.
template <class L>
HWY_INLINE StepResult<L> PhaseStep(const StepVertex<L>& v) {
    const V3<typename L::F> wi = UniformSphere<L>(v.u1, v.u2);
    return FinishStep(v, wi, v.bsdf.albedo, PhasePdf<L>(), L::All(), L::Not(L::All()));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SHADING_SURFACE_STEP_INL_H_
