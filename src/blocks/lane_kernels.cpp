#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "blocks/lane_kernels.cpp"
#include "blocks/lane_kernels.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <initializer_list>

#include "bsdfs/metallic_roughness.h"
#include "lights/environment_light-inl.h"
#include "lights/light_sample-inl.h"
#include "lights/sphere_light-inl.h"
#include "math/lanes-inl.h"
#include "media/medium_flight-inl.h"
#include "sampling/sampler-inl.h"
#include "scene/camera_ray-inl.h"
#include "scene/surface_point-inl.h"
#include "shading/mis-inl.h"
#include "shading/surface_step-inl.h"
#include "util/check.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Rows k .. k + Lanes(d) of three SoA rows (x, y, z) as one V3 of vectors, and back.
template <class D>
HWY_INLINE V3<hn::Vec<D>> Load3(D d, const float (*rows)[kShadeChunk], size_t k) {
    return {hn::Load(d, rows[0] + k), hn::Load(d, rows[1] + k), hn::Load(d, rows[2] + k)};
}
template <class D>
HWY_INLINE void Store3(D d, V3<hn::Vec<D>> v, float (*rows)[kShadeChunk], size_t k) {
    hn::Store(v.x, d, rows[0] + k);
    hn::Store(v.y, d, rows[1] + k);
    hn::Store(v.z, d, rows[2] + k);
}

// Rows [0, n) of `in` copied to `out`, and row 0 repeated to kShadeChunk: whole vectors of
// ordinary values.
template <class T>
HWY_INLINE void PadRows(const T* in, size_t n, T* out) {
    std::copy(in, in + n, out);
    std::fill(out + n, out + kShadeChunk, in[0]);
}

// n rounded up to whole vectors of N lanes, and entries [n, padded) of each of `rows` set to
// entry 0: the last vector then computes on ordinary values.
HWY_INLINE size_t Padded(size_t n, size_t N) {
    return (n + N - 1) / N * N;
}
template <class T>
HWY_INLINE void PadTail(std::initializer_list<T*> rows, size_t n, size_t padded) {
    for (T* row : rows) std::fill(row + n, row + padded, row[0]);
}
// The same for rows of three (x, y, z).
HWY_INLINE void PadTail3(std::initializer_list<float (*)[kShadeChunk]> rows,
                         size_t n,
                         size_t padded) {
    for (float(*xyz)[kShadeChunk] : rows) PadTail<float>({xyz[0], xyz[1], xyz[2]}, n, padded);
}

void DrawCameraRays(const CameraFrame* camera,
                    const Sampler& sampler,
                    const uint32_t* sample,
                    const uint32_t* pixel,
                    const float* x,
                    const float* y,
                    size_t n,
                    bool flights,
                    CameraRayBlock* out) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    HWY_ALIGN uint32_t px[kShadeChunk], sx[kShadeChunk];
    HWY_ALIGN float fx[kShadeChunk], fy[kShadeChunk];
    PadRows(pixel, n, px);
    PadRows(sample, n, sx);
    PadRows(x, n, fx);
    PadRows(y, n, fy);
    for (size_t k = 0; k < n; k += N) {
        V3<hn::Vec<decltype(df)>> o, d;
        const auto state = PathState<L>(sampler, hn::Load(d32, px + k), hn::Load(d32, sx + k));
        SampledCameraRay<L>(*camera, state, hn::Load(df, fx + k), hn::Load(df, fy + k), &o, &d);
        if (flights)
            hn::Store(OpticalDepth<L>(SampleDim<L>(
                          state, hn::Set(d64, uint64_t(bounce_dim(0, kDimMediumDistance))))),
                      df, out->flight + k);
        for (int a = 0; a < 3; ++a) {
            hn::Store(a == 0 ? o.x : a == 1 ? o.y : o.z, df, out->o[a] + k);
            hn::Store(a == 0 ? d.x : a == 1 ? d.y : d.z, df, out->d[a] + k);
        }
    }
}

// Rows k .. k + Lanes(df) of a SampleBlock from one vector of vertices' draws: the light
// choice alone (its pair's medium distance has been used), then by pairs (the Sobol samplers
// draw a pair together), zeros for the one-sample strategies' pairs where they are not drawn,
// and with `flights` the next bounce's first dimension, its medium distance, as an optical
// depth.
template <class DF, class LightSelect, class Pair, class Flight>
HWY_INLINE void StoreVertexDims(DF df,
                                size_t k,
                                bool one_sample,
                                bool flights,
                                const LightSelect& light_select,
                                const Pair& pair,
                                const Flight& flight,
                                SampleBlock* out) {
    static_assert(kDimMediumDistance == 0);
    hn::Store(light_select(), df, out->u[kDimLightSelect] + k);
    for (uint32_t d = kDimLightU; d < kBounceDims; d += 2) {
        hn::Vec<DF> a = hn::Zero(df), b = hn::Zero(df);
        if (one_sample || !one_sample_pair(d / 2)) pair(d, &a, &b);
        hn::Store(a, df, out->u[d] + k);
        hn::Store(b, df, out->u[d + 1] + k);
    }
    if (flights) hn::Store(flight(), df, out->next_flight + k);
}

#if HWY_TARGET != HWY_SCALAR
// The Sobol and ZSobol samplers' rows of DrawVertexSamples, two vectors of 64-bit lanes at a
// time: each pair's hash in 64-bit lanes (SobolPairHash), the rest of its formulas on the
// hash's words in 32-bit lanes (WordLanes), twice as many to a vector. SampleDim's and
// SampleDimPair's numbers, bit for bit.
void DrawSobolVertexSamples(const Sampler& sampler,
                            const uint32_t* sx,
                            const uint32_t* px,
                            const uint32_t* first_dim,
                            size_t n,
                            bool one_sample,
                            bool flights,
                            SampleBlock* out) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    using Words = SobolWords<D64>;
    using W = Words::W;
    using F = Words::F;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> dh;  // a 64-bit vector's lane count of words
    const hn::Rebind<float, Words::D32> df;
    const size_t N = hn::Lanes(d64);
    for (size_t k = 0; k < n; k += 2 * N) {
        const auto s0 = PathState<L>(sampler, hn::Load(dh, px + k), hn::Load(dh, sx + k));
        const auto s1 = PathState<L>(sampler, hn::Load(dh, px + k + N), hn::Load(dh, sx + k + N));
        const auto first0 = hn::PromoteTo(d64, hn::Load(dh, first_dim + k));
        const auto first1 = hn::PromoteTo(d64, hn::Load(dh, first_dim + k + N));
        const W::U64 reversed_index = Words::ReversedIndex(s0, s1);
        // Dimensions first + d and first + d + 1 (d even) of every row.
        const auto pair_dims = [&](uint32_t d, F* a, F* b) {
            const auto dims = hn::Set(d64, d);
            const auto h0 = SobolPairHash<L>(s0, hn::ShiftRight<1>(hn::Add(first0, dims)));
            const auto h1 = SobolPairHash<L>(s1, hn::ShiftRight<1>(hn::Add(first1, dims)));
            Words::PairDims(reversed_index, h0, h1, a, b);
        };
        static_assert(kDimLightSelect == 1);  // the second of pair 0
        StoreVertexDims(
            df, k, one_sample, flights,
            [&] {
                F a, b;
                pair_dims(0, &a, &b);
                return b;
            },
            pair_dims,
            [&] {
                F a, b;
                pair_dims(kBounceDims, &a, &b);
                return OpticalDepth<W>(a);
            },
            out);
    }
}
#endif

void DrawVertexSamples(const Sampler& sampler,
                       const uint32_t* sample,
                       const uint32_t* pixel,
                       const uint16_t* bounce,
                       size_t n,
                       bool one_sample,
                       bool flights,
                       SampleBlock* out) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    // Counters as 32-bit rows padded to whole vectors: the pixel and the bounce's first
    // dimension.
    HWY_ALIGN uint32_t px[kShadeChunk], sx[kShadeChunk], first_dim[kShadeChunk];
    PadRows(pixel, n, px);
    PadRows(sample, n, sx);
    for (size_t k = 0; k < kShadeChunk; ++k)
        first_dim[k] = bounce_dim(bounce[k < n ? k : 0], BounceDim(0));
#if HWY_TARGET != HWY_SCALAR
    if (sampler.kind != SamplerKind::Independent) {
        DrawSobolVertexSamples(sampler, sx, px, first_dim, n, one_sample, flights, out);
        return;
    }
#endif
    for (size_t k = 0; k < n; k += N) {
        const auto state = PathState<L>(sampler, hn::Load(d32, px + k), hn::Load(d32, sx + k));
        const auto first = hn::PromoteTo(d64, hn::Load(d32, first_dim + k));
        StoreVertexDims(
            df, k, one_sample, flights,
            [&] { return SampleDim<L>(state, hn::Add(first, hn::Set(d64, kDimLightSelect))); },
            [&](uint32_t d, auto* a, auto* b) {
                SampleDimPair<L>(state, hn::Add(first, hn::Set(d64, d)), a, b);
            },
            [&] {
                return OpticalDepth<L>(
                    SampleDim<L>(state, hn::Add(first, hn::Set(d64, kBounceDims))));
            },
            out);
    }
}

void MediumSegments(MediumSegmentBlock* b, size_t n) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    const size_t padded = Padded(n, N);
    PadTail<float>({b->t, b->medium, b->density, b->flight}, n, padded);
    PadTail3({b->dir}, n, padded);
    const F zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    for (size_t k = 0; k < n; k += N) {
        const V3<F> dir = Load3(d, b->dir, k);
        const F dir_length = hn::Sqrt(Dot(dir, dir));
        // scatters_in_medium's segment: (t - tmin) |dir| with tmin = 0, infinite for a miss.
        const F seg = hn::Mul(hn::Load(d, b->t + k), dir_length);
        F flight = hn::Load(d, b->flight + k), dist;
        const auto in_medium = hn::Gt(hn::Load(d, b->medium + k), zero);
        const auto scatters = hn::And(
            in_medium, ScattersInMedium<L>(seg, hn::Load(d, b->density + k), &flight, &dist));
        hn::Store(dir_length, d, b->dir_length + k);
        hn::Store(hn::IfThenElse(in_medium, flight, hn::Load(d, b->flight + k)), d, b->flight + k);
        hn::Store(dist, d, b->dist + k);
        hn::Store(hn::IfThenElseZero(scatters, one), d, b->scatters + k);
    }
}

void ResolveSurfaceHits(VertexBlock* b) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const hn::RebindToSigned<D> di;
    const size_t N = hn::Lanes(d);
    if (b->n == 0) return;
    const size_t padded = Padded(b->n, N);
    PadTail<float>({b->hit_u, b->hit_v}, b->n, padded);
    PadTail3({b->p, b->ng, b->ns, b->wo, b->dir, b->corner[0], b->corner[1], b->corner[2],
              b->vertex_normal[0], b->vertex_normal[1], b->vertex_normal[2]},
             b->n, padded);
    PadTail<int32_t>({b->shape, b->smooth}, b->n, padded);
    auto is = [&](hn::Vec<decltype(di)> shape, HitShape s) {
        return hn::RebindMask(d, hn::Eq(shape, hn::Set(di, int32_t(s))));
    };
    for (size_t k = 0; k < b->n; k += N) {
        V3<F> p = Load3(d, b->p, k), ng = Load3(d, b->ng, k), ns = Load3(d, b->ns, k),
              wo = Load3(d, b->wo, k);
        // The vertices to resolve from their hits: surface_at's point and normals, and the
        // unit direction back along the ray, -d / |d|, as resolve_segment computes it.
        const auto shape = hn::Load(di, b->shape + k);
        const auto quad_hit = is(shape, HitShape::Quad);
        const auto triangle_hit = is(shape, HitShape::Triangle);
        const auto sphere_hit = is(shape, HitShape::Sphere);
        const auto any_hit = hn::Not(is(shape, HitShape::Given));
        if (hn::AllFalse(d, any_hit)) continue;
        // Each shape's rows take its point and normals.
        auto take = [&](hn::Mask<D> m, const SurfacePoint<L>& s) {
            p = Select3<L>(m, s.p, p);
            ng = Select3<L>(m, s.ng, ng);
            ns = Select3<L>(m, s.ns, ns);
        };
        const F u = hn::Load(d, b->hit_u + k), v = hn::Load(d, b->hit_v + k);
        const V3<F> c[3] = {Load3(d, b->corner[0], k), Load3(d, b->corner[1], k),
                            Load3(d, b->corner[2], k)};
        if (!hn::AllFalse(d, quad_hit)) take(quad_hit, QuadPoint<L>(c[0], c[1], c[2], u, v));
        if (!hn::AllFalse(d, triangle_hit)) {
            const V3<F> vn[3] = {Load3(d, b->vertex_normal[0], k), Load3(d, b->vertex_normal[1], k),
                                 Load3(d, b->vertex_normal[2], k)};
            const auto smooth =
                hn::RebindMask(d, hn::Ne(hn::Load(di, b->smooth + k), hn::Zero(di)));
            take(triangle_hit, TrianglePoint<L>(c, vn, smooth, u, v));
        }
        if (!hn::AllFalse(d, sphere_hit)) take(sphere_hit, SpherePoint<L>(c[0], c[1], u));
        const V3<F> dir = Normalize<L>(Load3(d, b->dir, k));
        wo = Select3<L>(any_hit, Neg3<L>(dir), wo);
        Store3(d, p, b->p, k);
        Store3(d, ng, b->ng, k);
        Store3(d, ns, b->ns, k);
        Store3(d, wo, b->wo, k);
    }
}

// Masks of the rows of each lobe; glossy: a rough metal, conductor or dielectric, or a
// metallic-roughness surface.
template <class D>
struct LobeMasks {
    hn::Mask<D> lambertian, metal, conductor, dielectric, metallic_roughness, phase, glossy,
        specular;
};
template <class D>
HWY_INLINE LobeMasks<D> LobesAt(D d, const int32_t* lobe, size_t k) {
    const hn::RebindToSigned<D> di;
    const auto l = hn::Load(di, lobe + k);
    auto is = [&](LaneLobe x) { return hn::RebindMask(d, hn::Eq(l, hn::Set(di, int32_t(x)))); };
    const auto metal = is(LaneLobe::RoughMetal), conductor = is(LaneLobe::RoughConductor),
               dielectric = is(LaneLobe::RoughDielectric),
               metallic_roughness = is(LaneLobe::MetallicRoughness);
    return {is(LaneLobe::Lambertian),
            metal,
            conductor,
            dielectric,
            metallic_roughness,
            is(LaneLobe::Phase),
            hn::Or(hn::Or(hn::Or(metal, conductor), dielectric), metallic_roughness),
            is(LaneLobe::Specular)};
}

// The BSDF of rows k .. of the given albedo and roughness: the glossy rows read where a lane of
// the vector is of their kind (else zeros, which no lane reads).
template <class D>
HWY_INLINE LaneBsdf<FloatLanes<D>> LaneBsdfAt(D d,
                                              V3<hn::Vec<D>> albedo,
                                              hn::Vec<D> alpha,
                                              const GlossyRows& rows,
                                              size_t k,
                                              const LobeMasks<D>& lobes) {
    const hn::RebindToSigned<D> di;
    auto flag = [&](const int32_t* row) {
        return hn::RebindMask(d, hn::Ne(hn::Load(di, row + k), hn::Zero(di)));
    };
    const hn::Vec<D> zero = hn::Zero(d);
    const hn::Mask<D> none = hn::FirstN(d, 0);
    LaneBsdf<FloatLanes<D>> b{albedo,
                              alpha,
                              {zero, zero, zero},
                              {zero, zero, zero},
                              none,
                              zero,
                              zero,
                              zero,
                              zero,
                              zero,
                              none,
                              lobes.metal,
                              lobes.conductor,
                              lobes.dielectric,
                              lobes.metallic_roughness,
                              lobes.phase,
                              lobes.specular};
    if (!hn::AllFalse(d, lobes.specular)) {  // a delta row's kind
        const auto kind = hn::Load(di, rows.kind + k);
        auto of = [&](MaterialKind x) {
            return hn::And(lobes.specular,
                           hn::RebindMask(d, hn::Eq(kind, hn::Set(di, int32_t(x)))));
        };
        b.metal = hn::Or(b.metal, of(MaterialKind::Metal));
        b.conductor = hn::Or(b.conductor, of(MaterialKind::Conductor));
        b.dielectric = hn::Or(b.dielectric, of(MaterialKind::Dielectric));
    }
    if (!hn::AllFalse(d, hn::Or(b.conductor, b.dielectric))) {
        b.eta = Load3(d, rows.eta, k);
        b.k = Load3(d, rows.k, k);
        b.beckmann = flag(rows.beckmann);
    }
    if (!hn::AllFalse(d, lobes.metallic_roughness)) {
        b.f0 = hn::Load(d, rows.f0 + k);
        b.metallic = hn::Load(d, rows.metallic + k);
        b.transmission = hn::Load(d, rows.transmission + k);
        b.clearcoat = hn::Load(d, rows.clearcoat + k);
        b.coat_alpha = hn::Load(d, rows.coat_alpha + k);
        b.one_sided = flag(rows.one_sided);
    }
    return b;
}

// Rows [n, padded) of the glossy rows: row 0's.
HWY_INLINE void PadGlossyTail(GlossyRows& rows, size_t n, size_t padded) {
    PadTail3({rows.eta, rows.k}, n, padded);
    PadTail<float>({rows.f0, rows.metallic, rows.transmission, rows.clearcoat, rows.coat_alpha}, n,
                   padded);
    PadTail<int32_t>({rows.beckmann, rows.one_sided, rows.kind}, n, padded);
}

void StepVertices(VertexBlock* b) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    const D d;
    const hn::RebindToSigned<D> di;
    const size_t N = hn::Lanes(d);
    if (b->n == 0) return;
    const size_t padded = Padded(b->n, N);
    PadTail3({b->p, b->ng, b->ns, b->wo, b->albedo, b->beta}, b->n, padded);
    PadTail<float>({b->u1, b->u2, b->u_rr, b->alpha, b->eta_scale}, b->n, padded);
    PadTail<int32_t>({b->lobe, b->roulette}, b->n, padded);
    PadTail<float>({b->u_lobe}, b->n, padded);
    PadGlossyTail(b->glossy, b->n, padded);
    for (size_t k = 0; k < b->n; k += N) {
        const LobeMasks<D> lobes = LobesAt(d, b->lobe, k);
        const StepVertex<L> v{
            Load3(d, b->p, k),
            Load3(d, b->ng, k),
            Load3(d, b->ns, k),
            Load3(d, b->wo, k),
            LaneBsdfAt(d, Load3(d, b->albedo, k), hn::Load(d, b->alpha + k), b->glossy, k, lobes),
            Load3(d, b->beta, k),
            hn::Load(d, b->u_lobe + k),
            hn::Load(d, b->u1 + k),
            hn::Load(d, b->u2 + k),
            hn::Load(d, b->u_rr + k),
            hn::RebindMask(d, hn::Ne(hn::Load(di, b->roulette + k), hn::Zero(di))),
            hn::Load(d, b->eta_scale + k),
            b->geometric_side_test};
        // Each lane's lobe: vectors of one lobe run one step, mixed ones each of theirs.
        // The first lobe present gives the vector's result, the others' lanes are selected in.
        const bool lambertian = !hn::AllFalse(d, lobes.lambertian),
                   glossy = !hn::AllFalse(d, lobes.glossy), phase = !hn::AllFalse(d, lobes.phase),
                   specular = !hn::AllFalse(d, lobes.specular);
        StepResult<L> r = lambertian ? LambertianStep(v)
                          : glossy   ? GlossyStep(v)
                          : phase    ? PhaseStep(v)
                                     : SpecularStep(v);
        auto take = [&](hn::Mask<D> m, const StepResult<L>& s) {
            r.alive = hn::Or(hn::And(m, s.alive), hn::AndNot(m, r.alive));
            r.transmitted = hn::Or(hn::And(m, s.transmitted), hn::AndNot(m, r.transmitted));
            r.delta = hn::Or(hn::And(m, s.delta), hn::AndNot(m, r.delta));
            r.origin = Select3<L>(m, s.origin, r.origin);
            r.wi = Select3<L>(m, s.wi, r.wi);
            r.weight = Select3<L>(m, s.weight, r.weight);
            r.pdf = hn::IfThenElse(m, s.pdf, r.pdf);
            r.eta_scale = hn::IfThenElse(m, s.eta_scale, r.eta_scale);
        };
        if (lambertian && glossy) take(lobes.glossy, GlossyStep(v));
        if ((lambertian || glossy) && phase) take(lobes.phase, PhaseStep(v));
        if ((lambertian || glossy || phase) && specular) take(lobes.specular, SpecularStep(v));
        Store3(d, r.origin, b->origin, k);
        Store3(d, r.wi, b->wi, k);
        Store3(d, r.weight, b->weight, k);
        hn::Store(r.pdf, d, b->pdf + k);
        hn::Store(hn::IfThenElseZero(hn::RebindMask(di, r.alive), hn::Set(di, 1)), di,
                  b->alive + k);
        hn::Store(hn::IfThenElseZero(hn::RebindMask(di, r.transmitted), hn::Set(di, 1)), di,
                  b->transmitted + k);
        hn::Store(hn::IfThenElseZero(hn::RebindMask(di, r.delta), hn::Set(di, 1)), di,
                  b->delta + k);
        hn::Store(r.eta_scale, d, b->next_eta_scale + k);
    }
}

// Rows k .. k + Lanes(d) of a queue's column; rows at or past n repeat row 0, so that the last
// vector computes on ordinary values and reads nothing past the rows.
template <class D>
HWY_INLINE hn::Vec<D> LoadColumn(D d, const float* column, size_t k, size_t n) {
    const size_t N = hn::Lanes(d);
    if (k + N <= n) return hn::LoadU(d, column + k);
    HWY_ALIGN float rows[kShadeChunk];
    for (size_t j = 0; j < N; ++j) rows[j] = column[k + j < n ? k + j : 0];
    return hn::Load(d, rows);
}

// The environment map's light points of rows [0, n), of the vectors at k where wanted(k), from
// the columns u1(k), u2(k) and select_prob(k): EnvironmentLightPoint's, by stages. Every
// vector's row of the map is found before any vector's column, and every column before the
// directions and radiances, so that the vectors' cache misses (a row's guide and sums, its
// texels) overlap where one vector's chain of dependent gathers would wait on each in turn;
// each stage also prefetches what the next reads (a row's guide cell and total, the sums its
// search starts between, the texels), and a prefetch, unlike a gather, waits on nothing.
struct EnvironmentPoints {
    alignas(64) float wi[3][kShadeChunk], radiance[3][kShadeChunk];
    alignas(64) float pdf[kShadeChunk];
    alignas(64) int32_t valid[kShadeChunk];
};
template <class D, class Wanted, class U1, class U2, class SelectProb>
HWY_INLINE void EnvironmentPointsByStage(D d,
                                         const EnvironmentView& e,
                                         const Distribution2DTables& t,
                                         size_t n,
                                         const Wanted& wanted,
                                         const U1& u1,
                                         const U2& u2,
                                         const SelectProb& select_prob,
                                         EnvironmentPoints* out) {
    using L = FloatLanes<D>;
    const hn::RebindToSigned<D> di;
    const size_t N = hn::Lanes(d);
    HWY_ALIGN float u[kShadeChunk], v[kShadeChunk], pdf_uv[kShadeChunk];
    HWY_ALIGN int32_t row[kShadeChunk];
    for (size_t k = 0; k < n; k += N) {
        if (!wanted(k)) continue;
        hn::Vec<D> vk;
        hn::Vec<decltype(di)> rk;
        hn::Store(SampleMarginal<L>(t, u2(k), &vk, &rk), d, pdf_uv + k);
        hn::Store(vk, d, v + k);
        hn::Store(rk, di, row + k);
        PrefetchConditionalGuide<L>(t, rk, u1(k));
    }
    for (size_t k = 0; k < n; k += N)
        if (wanted(k)) PrefetchConditionalSums<L>(t, hn::Load(di, row + k), u1(k));
    for (size_t k = 0; k < n; k += N) {
        if (!wanted(k)) continue;
        hn::Vec<D> uk;
        const hn::Vec<D> pdf_u = SampleConditional<L>(t, hn::Load(di, row + k), u1(k), &uk);
        hn::Store(hn::Mul(hn::Load(d, pdf_uv + k), pdf_u), d, pdf_uv + k);
        hn::Store(uk, d, u + k);
        PrefetchEnvironmentTexels<L>(e, uk, hn::Load(d, v + k));
    }
    for (size_t k = 0; k < n; k += N) {
        if (!wanted(k)) continue;
        const LightPoint<L> p = EnvironmentLightPointAt<L>(
            e, hn::Load(d, u + k), hn::Load(d, v + k), hn::Load(d, pdf_uv + k), select_prob(k));
        Store3(d, p.wi, out->wi, k);
        Store3(d, p.radiance, out->radiance, k);
        hn::Store(p.pdf, d, out->pdf + k);
        hn::Store(hn::VecFromMask(di, hn::RebindMask(di, p.valid)), di, out->valid + k);
    }
}

size_t SampleLights(LightSampleBlock* b,
                    const PlanarEmitterColumns* planars,
                    const SphereEmitterColumns* spheres,
                    const DeltaLightColumns* deltas,
                    const EnvironmentView* environment,
                    Distribution2DTables environment_tables,
                    ShadowQueue* shadows,
                    size_t first_shadow) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const hn::RebindToSigned<D> di;
    const size_t N = hn::Lanes(d);
    const size_t n = b->n;
    if (n == 0) return 0;
    const LightSampleQueue& q = *b->queue;
    const size_t at = b->first;
    PadTail<float>({b->select_prob}, n, Padded(n, N));
    PadTail<int32_t>({b->lobe, b->planar, b->sphere, b->delta, b->environment}, n, Padded(n, N));
    PadGlossyTail(b->glossy, n, Padded(n, N));
    const auto environment_at = [&](size_t k) {
        return hn::RebindMask(d, hn::Ne(hn::Load(di, b->environment + k), hn::Zero(di)));
    };
    EnvironmentPoints on_map;
    EnvironmentPointsByStage(
        d, *environment, environment_tables, n,
        [&](size_t k) { return !hn::AllFalse(d, environment_at(k)); },
        [&](size_t k) { return LoadColumn(d, q.u1.data() + at, k, n); },
        [&](size_t k) { return LoadColumn(d, q.u2.data() + at, k, n); },
        [&](size_t k) { return hn::Load(d, b->select_prob + k); }, &on_map);
    size_t s = first_shadow;
    for (size_t k = 0; k < n; k += N) {
        auto column = [&](const std::vector<float>& c) {
            return LoadColumn(d, c.data() + at, k, n);
        };
        auto column3 = [&](const std::vector<float>& x, const std::vector<float>& y,
                           const std::vector<float>& z) {
            return V3<F>{column(x), column(y), column(z)};
        };
        // Each row's own planar or sphere light: gathered from the columns, or broadcast when the
        // rows share one light (a scene with one light, or a chunk whose samples picked the
        // same), which saves the gathers.
        const auto planar = hn::Load(di, b->planar + k);
        const auto sphere = hn::Load(di, b->sphere + k);
        const auto delta = hn::Load(di, b->delta + k);
        const auto has_planar = hn::RebindMask(d, hn::Gt(planar, hn::Set(di, -1)));
        const auto has_sphere = hn::RebindMask(d, hn::Gt(sphere, hn::Set(di, -1)));
        const auto has_delta = hn::RebindMask(d, hn::Gt(delta, hn::Set(di, -1)));
        const auto has_environment = environment_at(k);
        const auto has_light =
            hn::Or(hn::Or(has_planar, has_sphere), hn::Or(has_delta, has_environment));
        if (hn::AllFalse(d, has_light)) continue;
        const LobeMasks<D> lobes = LobesAt(d, b->lobe, k);
        const F u1 = column(q.u1), u2 = column(q.u2);
        const LightSampleVertex<L> v{column3(q.p_x, q.p_y, q.p_z),
                                     column3(q.ng_x, q.ng_y, q.ng_z),
                                     column3(q.ns_x, q.ns_y, q.ns_z),
                                     column3(q.wo_x, q.wo_y, q.wo_z),
                                     LaneBsdfAt(d, column3(q.albedo_x, q.albedo_y, q.albedo_z),
                                                column(q.alpha), b->glossy, k, lobes),
                                     u1,
                                     u2,
                                     b->geometric_side_test};
        auto fetcher = [&](hn::Vec<decltype(di)> light) {
            const auto index = hn::Max(light, hn::Zero(di));
            const int32_t first = hn::GetLane(index);
            const bool shared = hn::AllTrue(di, hn::Eq(index, hn::Set(di, first)));
            return [=, &d](const std::vector<float>& c) {
                return shared ? hn::Set(d, c[size_t(first)]) : hn::GatherIndex(d, c.data(), index);
            };
        };
        const F select_prob = hn::Load(d, b->select_prob + k);
        LightPoint<L> point;
        const bool any_planar = !hn::AllFalse(d, has_planar);
        if (any_planar)
            point = PlanarLightPoint(
                v.p, PlanarLightFrom<L>(*planars, fetcher(planar), select_prob), u1, u2);
        const bool any_sphere = !hn::AllFalse(d, has_sphere);
        if (any_sphere) {
            const LightPoint<L> on_sphere = SphereLightPoint(
                v.p, SphereLightFrom<L>(*spheres, fetcher(sphere), select_prob), u1, u2);
            point = any_planar ? SelectLightPoint<L>(has_sphere, on_sphere, point) : on_sphere;
        }
        const bool any_delta = !hn::AllFalse(d, has_delta);
        if (any_delta) {
            const LightPoint<L> at_delta =
                DeltaLightPoint(v.p, DeltaLightFrom<L>(*deltas, fetcher(delta), select_prob));
            point = any_planar || any_sphere ? SelectLightPoint<L>(has_delta, at_delta, point)
                                             : at_delta;
        }
        if (!hn::AllFalse(d, has_environment)) {
            const LightPoint<L> map{
                hn::RebindMask(d, hn::Ne(hn::Load(di, on_map.valid + k), hn::Zero(di))),
                Load3(d, on_map.wi, k), hn::Set(d, kInfinity), hn::Load(d, on_map.pdf + k),
                Load3(d, on_map.radiance, k)};
            point = any_planar || any_sphere || any_delta
                        ? SelectLightPoint<L>(has_environment, map, point)
                        : map;
        }
        VertexLightSample<L> r = SampleTowards(v, point);
        // No BSDF sample finds a point or directional light: their MIS weight is 1.
        if (any_delta) r.pdf_bsdf = hn::IfThenZeroElse(has_delta, r.pdf_bsdf);
        // The rows that append, packed to the queue's next entries in row order (the rows past
        // n repeat row 0 and stay out).
        const auto append = hn::And(hn::FirstN(d, n - k), hn::And(has_light, r.valid));
        const size_t count = hn::CountTrue(d, append);
        if (count == 0) continue;
        WT_DCHECK_LE(s + count, shadows->capacity);
        const V3<F> contribution = column3(q.beta_x, q.beta_y, q.beta_z) * r.value;
        const F out[] = {r.origin.x,     r.origin.y,     r.origin.z,  r.wi.x,
                         r.wi.y,         r.wi.z,         r.tmax,      contribution.x,
                         contribution.y, contribution.z, r.pdf_light, r.pdf_bsdf};
        float* const rows[] = {shadows->origin_x.data(),       shadows->origin_y.data(),
                               shadows->origin_z.data(),       shadows->dir_x.data(),
                               shadows->dir_y.data(),          shadows->dir_z.data(),
                               shadows->tmax.data(),           shadows->contribution_x.data(),
                               shadows->contribution_y.data(), shadows->contribution_z.data(),
                               shadows->pdf_light.data(),      shadows->pdf_bsdf.data()};
        constexpr size_t kRows = std::size(rows);
        if (count == N) {  // every row appends: whole vectors
            for (size_t j = 0; j < kRows; ++j) hn::StoreU(out[j], d, rows[j] + s);
            std::copy(q.path.begin() + at + k, q.path.begin() + at + k + N,
                      shadows->path.begin() + s);
            std::copy(q.media.begin() + at + k, q.media.begin() + at + k + N,
                      shadows->media.begin() + s);
        } else {  // row by row, from the vectors stored aside
            HWY_ALIGN float lanes[kRows][kShadeChunk];
            HWY_ALIGN int32_t appends[kShadeChunk];
            for (size_t j = 0; j < kRows; ++j) hn::Store(out[j], d, lanes[j]);
            hn::Store(hn::VecFromMask(di, hn::RebindMask(di, append)), di, appends);
            for (size_t l = 0, to = s; l < N; ++l) {
                if (appends[l] == 0) continue;
                for (size_t j = 0; j < kRows; ++j) rows[j][to] = lanes[j][l];
                shadows->media[to] = q.media[at + k + l];
                shadows->path[to++] = q.path[at + k + l];
            }
        }
        s += count;
    }
    return s - first_shadow;
}

void EnvironmentLightPoints(EnvironmentPointBlock* b,
                            const EnvironmentView* environment,
                            Distribution2DTables tables) {
    using D = hn::CappedTag<float, kShadeChunk>;
    const D d;
    const size_t n = b->n;
    if (n == 0) return;
    PadTail<float>({b->u1, b->u2, b->select_prob}, n, Padded(n, hn::Lanes(d)));
    EnvironmentPoints points;
    EnvironmentPointsByStage(
        d, *environment, tables, n, [](size_t) { return true; },
        [&](size_t k) { return hn::Load(d, b->u1 + k); },
        [&](size_t k) { return hn::Load(d, b->u2 + k); },
        [&](size_t k) { return hn::Load(d, b->select_prob + k); }, &points);
    for (int a = 0; a < 3; ++a) {
        std::copy(points.wi[a], points.wi[a] + n, b->wi[a]);
        std::copy(points.radiance[a], points.radiance[a] + n, b->radiance[a]);
    }
    std::copy(points.pdf, points.pdf + n, b->pdf);
}

void EscapeRays(EscapeBlock* b,
                const EnvironmentView* environment,
                Distribution2DTables tables,
                bool with_pdf) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    const size_t n = b->n;
    if (n == 0) return;
    PadTail3({b->dir}, n, Padded(n, N));
    if (with_pdf) PadTail<float>({b->select_prob}, n, Padded(n, N));
    // Every vector's (u, v) first, its texels and density fetched ahead, then the lookups: the
    // vectors' cache misses overlap.
    HWY_ALIGN float u[kShadeChunk], v[kShadeChunk];
    for (size_t k = 0; k < n; k += N) {
        hn::Vec<D> uk, vk;
        EnvironmentUvOfRay<L>(*environment, Load3(d, b->dir, k), &uk, &vk);
        hn::Store(uk, d, u + k);
        hn::Store(vk, d, v + k);
        PrefetchEnvironmentTexels<L>(*environment, uk, vk);
        if (with_pdf) PrefetchDistribution2DPdf<L>(tables, uk, vk);
    }
    for (size_t k = 0; k < n; k += N) {
        const EscapedRay<L> r =
            Escape<L>(*environment, tables, hn::Load(d, u + k), hn::Load(d, v + k),
                      with_pdf ? hn::Load(d, b->select_prob + k) : hn::Zero(d), with_pdf);
        Store3(d, r.radiance, b->radiance, k);
        hn::Store(r.pdf_light, d, b->pdf_light + k);
    }
}

void MisWeights(MisHeuristic finite,
                MisHeuristic at_infinity,
                const float* pdf_a,
                const float* pdf_b,
                const float* tmax,
                size_t n,
                float* out) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    for (size_t k = 0; k < n; k += N) {
        const auto a = LoadColumn(d, pdf_a, k, n), b = LoadColumn(d, pdf_b, k, n);
        auto w = MisWeight<L>(finite, a, b);
        if (at_infinity != finite)
            w = hn::IfThenElse(hn::IsInf(LoadColumn(d, tmax, k, n)),
                               MisWeight<L>(at_infinity, a, b), w);
        if (k + N <= n) {
            hn::StoreU(w, d, out + k);
        } else {  // the tail's rows of the last vector
            HWY_ALIGN float rows[kShadeChunk];
            hn::Store(w, d, rows);
            std::copy(rows, rows + (n - k), out + k);
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(DrawCameraRays);
HWY_EXPORT(DrawVertexSamples);
HWY_EXPORT(MediumSegments);
HWY_EXPORT(ResolveSurfaceHits);
HWY_EXPORT(StepVertices);
HWY_EXPORT(SampleLights);
HWY_EXPORT(EnvironmentLightPoints);
HWY_EXPORT(EscapeRays);
HWY_EXPORT(MisWeights);

void draw_camera_rays(const CameraRays& camera,
                      const Sampler& sampler,
                      const uint32_t* sample,
                      const uint32_t* pixel,
                      const float* x,
                      const float* y,
                      size_t n,
                      bool flights,
                      CameraRayBlock& out) {
    HWY_DYNAMIC_DISPATCH(DrawCameraRays)
    (&camera.frame(), sampler, sample, pixel, x, y, n, flights, &out);
}

void draw_vertex_samples(const Sampler& sampler,
                         const uint32_t* sample,
                         const uint32_t* pixel,
                         const uint16_t* bounce,
                         size_t n,
                         bool one_sample,
                         bool flights,
                         SampleBlock& out) {
    HWY_DYNAMIC_DISPATCH(DrawVertexSamples)
    (sampler, sample, pixel, bounce, n, one_sample, flights, &out);
}

void medium_segments(MediumSegmentBlock& b, size_t n) {
    HWY_DYNAMIC_DISPATCH(MediumSegments)(&b, n);
}

void resolve_surface_hits(VertexBlock& b) {
    HWY_DYNAMIC_DISPATCH(ResolveSurfaceHits)(&b);
}

void step_vertices(VertexBlock& b) {
    HWY_DYNAMIC_DISPATCH(StepVertices)(&b);
}

size_t sample_lights_in_lanes(LightSampleBlock& b,
                              const LightSet& lights,
                              ShadowQueue& shadows,
                              size_t first_shadow) {
    return HWY_DYNAMIC_DISPATCH(SampleLights)(
        &b, &lights.planar_emitter_columns(), &lights.sphere_emitter_columns(),
        &lights.delta_light_columns(), &lights.environment_view(), lights.environment_tables(),
        &shadows, first_shadow);
}

void environment_light_points(EnvironmentPointBlock& b, const LightSet& lights) {
    HWY_DYNAMIC_DISPATCH(EnvironmentLightPoints)
    (&b, &lights.environment_view(), lights.environment_tables());
}

void escape_rays(EscapeBlock& b, const LightSet& lights, bool with_pdf) {
    HWY_DYNAMIC_DISPATCH(EscapeRays)
    (&b, &lights.environment_view(), lights.environment_tables(), with_pdf);
}

void direct_weights(Strategy strategy,
                    MisHeuristic finite,
                    MisHeuristic at_infinity,
                    const float* pdf_light,
                    const float* pdf_bsdf,
                    const float* tmax,
                    size_t n,
                    float* out) {
    if (strategy != Strategy::Mis) {
        std::fill(out, out + n, 1.0f);  // direct_weight's rule
        return;
    }
    HWY_DYNAMIC_DISPATCH(MisWeights)(finite, at_infinity, pdf_light, pdf_bsdf, tmax, n, out);
}

void GlossyRows::set(size_t row, const BsdfParams& b) {
    const Color e = lane_eta(b);
    for (int a = 0; a < 3; ++a) {
        eta[a][row] = e[a];
        k[a][row] = b.conductor_k[a];
    }
    beckmann[row] = b.distribution == Microfacet::Beckmann ? 1 : 0;
    f0[row] = schlick_f0(b.eta);
    metallic[row] = b.metallic;
    transmission[row] = b.transmission;
    clearcoat[row] = b.clearcoat;
    coat_alpha[row] = b.clearcoat_alpha;
    one_sided[row] = b.one_sided ? 1 : 0;
    kind[row] = int32_t(b.kind);
}

size_t VertexBlock::start_row(
    size_t entry_, HitShape shape_, MaterialId m, const BsdfParams& bsdf, Color beta_) {
    WT_DCHECK_LT(n, kShadeChunk);
    const size_t k = n++;
    shape[k] = int32_t(shape_);
    material[k] = m;
    lobe[k] = int32_t(lane_lobe(bsdf));
    if (bsdf.kind == MaterialKind::Conductor || bsdf.kind == MaterialKind::Dielectric ||
        bsdf.kind == MaterialKind::MetallicRoughness || lobe[k] == int32_t(LaneLobe::Specular))
        glossy.set(k, bsdf);
    interior[k] = kNone;
    for (int a = 0; a < 3; ++a) {
        albedo[a][k] = bsdf.albedo[a];
        beta[a][k] = beta_[a];
    }
    alpha[k] = bsdf.alpha;
    smooth[k] = 0;
    flip_v[k] = 0;
    entry[k] = static_cast<uint32_t>(entry_);
    return k;
}

size_t VertexBlock::push(size_t entry_, const Vertex& v, Vec3 wo_, Color beta_) {
    const size_t k = start_row(entry_, HitShape::Given, v.material, v.bsdf, beta_);
    interior[k] = v.interior;
    for (int a = 0; a < 3; ++a) {
        p[a][k] = v.p[a];
        ng[a][k] = v.ng[a];
        ns[a][k] = v.frame.n[a];
        wo[a][k] = wo_[a];
    }
    return k;
}

size_t VertexBlock::push_quad_hit(size_t entry_,
                                  Vec3 d,
                                  float u,
                                  float v,
                                  const Quad& quad,
                                  MaterialId m,
                                  const BsdfParams& bsdf,
                                  Color beta_) {
    const size_t k = start_row(entry_, HitShape::Quad, m, bsdf, beta_);
    hit_u[k] = u;
    hit_v[k] = v;
    flip_v[k] = quad.flip_v ? 1 : 0;
    for (int a = 0; a < 3; ++a) {
        dir[a][k] = d[a];
        corner[0][a][k] = quad.q[a];
        corner[1][a][k] = quad.u[a];
        corner[2][a][k] = quad.v[a];
    }
    return k;
}

size_t VertexBlock::push_sphere_hit(size_t entry_,
                                    Vec3 d,
                                    Point3 p_,
                                    const Sphere& sphere,
                                    MaterialId m,
                                    const BsdfParams& bsdf,
                                    Color beta_) {
    const size_t k = start_row(entry_, HitShape::Sphere, m, bsdf, beta_);
    hit_u[k] = sphere.radius;
    hit_v[k] = 0.0f;
    for (int a = 0; a < 3; ++a) {
        dir[a][k] = d[a];
        corner[0][a][k] = p_[a];
        corner[1][a][k] = sphere.center[a];
        corner[2][a][k] = 0.0f;
    }
    return k;
}

size_t VertexBlock::push_triangle_hit(size_t entry_,
                                      Vec3 d,
                                      float u,
                                      float v,
                                      const Point3 (&vertices)[3],
                                      const Normal3* normals,
                                      MaterialId m,
                                      const BsdfParams& bsdf,
                                      Color beta_) {
    const size_t k = start_row(entry_, HitShape::Triangle, m, bsdf, beta_);
    hit_u[k] = u;
    hit_v[k] = v;
    for (int a = 0; a < 3; ++a) {
        dir[a][k] = d[a];
        for (int c = 0; c < 3; ++c) {
            corner[c][a][k] = vertices[c][a];
            vertex_normal[c][a][k] = normals ? normals[c][a] : 0.0f;
        }
    }
    smooth[k] = normals ? 1 : 0;
    return k;
}

}  // namespace wavetrace
#endif  // HWY_ONCE
