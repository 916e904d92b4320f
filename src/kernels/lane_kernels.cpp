#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kernels/lane_kernels.cpp"
#include "kernels/lane_kernels.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "math/lanes-inl.h"
#include "render/sampler-inl.h"
#include "scene/camera_ray-inl.h"
#include "shading/lambertian_step-inl.h"
#include "shading/quad_light_nee-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

void DrawCameraRays(const CameraFrame* camera,
                    uint64_t seed,
                    uint32_t sample,
                    const uint32_t* pixel,
                    const float* x,
                    const float* y,
                    size_t n,
                    CameraRayBlock* out) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    HWY_ALIGN uint32_t px[kShadeChunk];
    HWY_ALIGN float fx[kShadeChunk], fy[kShadeChunk];
    for (size_t k = 0; k < kShadeChunk; ++k) {
        const size_t j = k < n ? k : 0;
        px[k] = pixel[j];
        fx[k] = x[j];
        fy[k] = y[j];
    }
    for (size_t k = 0; k < n; k += N) {
        const auto state = PathState<L>(seed, hn::Load(d32, px + k), sample);
        auto u = [&](uint32_t dim) { return SampleDim<L>(state, hn::Set(d64, dim)); };
        V3<hn::Vec<decltype(df)>> o, d;
        CameraRay<L>(*camera, hn::Load(df, fx + k) + u(kDimPixelX),
                     hn::Load(df, fy + k) + u(kDimPixelY), u(kDimLensU), u(kDimLensV), &o, &d);
        for (int a = 0; a < 3; ++a) {
            hn::Store(a == 0 ? o.x : a == 1 ? o.y : o.z, df, out->o[a] + k);
            hn::Store(a == 0 ? d.x : a == 1 ? d.y : d.z, df, out->d[a] + k);
        }
    }
}

void DrawVertexSamples(uint64_t seed,
                       uint32_t sample,
                       const uint32_t* pixel,
                       const uint16_t* bounce,
                       size_t n,
                       SampleBlock* out) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    // Counters as 32-bit rows padded to whole vectors: the pixel and the bounce's first
    // dimension.
    HWY_ALIGN uint32_t px[kShadeChunk], first_dim[kShadeChunk];
    for (size_t k = 0; k < kShadeChunk; ++k) {
        const size_t j = k < n ? k : 0;
        px[k] = pixel[j];
        first_dim[k] = bounce_dim(bounce[j], BounceDim(0));
    }
    for (size_t k = 0; k < n; k += N) {
        const auto state = PathState<L>(seed, hn::Load(d32, px + k), sample);
        const auto first = hn::PromoteTo(d64, hn::Load(d32, first_dim + k));
        for (uint32_t d = kDimLightSelect; d < kBounceDims; ++d)
            hn::Store(SampleDim<L>(state, hn::Add(first, hn::Set(d64, d))), df, out->u[d] + k);
    }
}

void LambertianSteps(LambertianBlock* b) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    if (b->n == 0) return;
    // Pad the last vector with copies of row 0, so that every lane computes on real numbers.
    const size_t padded = (b->n + N - 1) / N * N;
    for (size_t k = b->n; k < padded; ++k) {
        for (int a = 0; a < 3; ++a) {
            b->p[a][k] = b->p[a][0];
            b->ng[a][k] = b->ng[a][0];
            b->ns[a][k] = b->ns[a][0];
            b->wo[a][k] = b->wo[a][0];
            b->albedo[a][k] = b->albedo[a][0];
            b->beta[a][k] = b->beta[a][0];
        }
        b->u1[k] = b->u1[0];
        b->u2[k] = b->u2[0];
        b->u_rr[k] = b->u_rr[0];
        b->roulette[k] = b->roulette[0];
    }
    auto load3 = [&](const float(*rows)[kShadeChunk], size_t k) {
        return V3<F>{hn::Load(d, rows[0] + k), hn::Load(d, rows[1] + k), hn::Load(d, rows[2] + k)};
    };
    auto store3 = [&](V3<F> v, float(*rows)[kShadeChunk], size_t k) {
        hn::Store(v.x, d, rows[0] + k);
        hn::Store(v.y, d, rows[1] + k);
        hn::Store(v.z, d, rows[2] + k);
    };
    for (size_t k = 0; k < b->n; k += N) {
        const LambertianVertex<L> v{
            load3(b->p, k),           load3(b->ng, k),
            load3(b->ns, k),          load3(b->wo, k),
            load3(b->albedo, k),      load3(b->beta, k),
            hn::Load(d, b->u1 + k),   hn::Load(d, b->u2 + k),
            hn::Load(d, b->u_rr + k), hn::Gt(hn::Load(d, b->roulette + k), hn::Zero(d))};
        const LambertianStepResult<L> r = LambertianStep(v);
        store3(r.origin, b->origin, k);
        store3(r.wi, b->wi, k);
        store3(r.weight, b->weight, k);
        hn::Store(r.pdf, d, b->pdf + k);
        hn::Store(hn::IfThenElseZero(r.alive, hn::Set(d, 1.0f)), d, b->alive + k);
    }
}

void QuadLightSamples(QuadLightBlock* b, bool mis, MisHeuristic heuristic) {
    using D = hn::CappedTag<float, kShadeChunk>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    if (b->rows == 0) return;
    const size_t padded = (b->rows + N - 1) / N * N;
    for (size_t k = b->rows; k < padded; ++k) {
        for (auto* rows :
             {b->p, b->ng, b->ns, b->wo, b->albedo, b->beta, b->q, b->u, b->v, b->n, b->radiance})
            for (int a = 0; a < 3; ++a) rows[a][k] = rows[a][0];
        for (float* row : {b->u1, b->u2, b->area, b->select_prob, b->two_sided}) row[k] = row[0];
    }
    auto load3 = [&](const float(*rows)[kShadeChunk], size_t k) {
        return V3<F>{hn::Load(d, rows[0] + k), hn::Load(d, rows[1] + k), hn::Load(d, rows[2] + k)};
    };
    auto store3 = [&](V3<F> v, float(*rows)[kShadeChunk], size_t k) {
        hn::Store(v.x, d, rows[0] + k);
        hn::Store(v.y, d, rows[1] + k);
        hn::Store(v.z, d, rows[2] + k);
    };
    for (size_t k = 0; k < b->rows; k += N) {
        const LambertianNeeVertex<L> v{
            load3(b->p, k),      load3(b->ng, k),        load3(b->ns, k),       load3(b->wo, k),
            load3(b->albedo, k), hn::Load(d, b->u1 + k), hn::Load(d, b->u2 + k)};
        const QuadLightLanes<L> light{load3(b->q, k),
                                      load3(b->u, k),
                                      load3(b->v, k),
                                      load3(b->n, k),
                                      hn::Load(d, b->area + k),
                                      load3(b->radiance, k),
                                      hn::Gt(hn::Load(d, b->two_sided + k), hn::Zero(d)),
                                      hn::Load(d, b->select_prob + k)};
        const QuadLightNee<L> r = QuadLightSample(v, light, mis, heuristic);
        // As shade appends a scalar next_event's: beta (value weight), when the weight is > 0.
        store3(load3(b->beta, k) * (r.value * r.weight), b->contribution, k);
        store3(r.origin, b->origin, k);
        store3(r.wi, b->wi, k);
        hn::Store(r.tmax, d, b->tmax + k);
        const auto append = hn::And(r.valid, hn::Gt(r.weight, hn::Zero(d)));
        hn::Store(hn::IfThenElseZero(append, hn::Set(d, 1.0f)), d, b->valid + k);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(DrawCameraRays);
HWY_EXPORT(DrawVertexSamples);
HWY_EXPORT(LambertianSteps);
HWY_EXPORT(QuadLightSamples);

void draw_camera_rays(const CameraRays& camera,
                      uint64_t seed,
                      uint32_t sample,
                      const uint32_t* pixel,
                      const float* x,
                      const float* y,
                      size_t n,
                      CameraRayBlock& out) {
    HWY_DYNAMIC_DISPATCH(DrawCameraRays)(&camera.frame(), seed, sample, pixel, x, y, n, &out);
}

void draw_vertex_samples(uint64_t seed,
                         uint32_t sample,
                         const uint32_t* pixel,
                         const uint16_t* bounce,
                         size_t n,
                         SampleBlock& out) {
    HWY_DYNAMIC_DISPATCH(DrawVertexSamples)(seed, sample, pixel, bounce, n, &out);
}

void lambertian_steps(LambertianBlock& b) {
    HWY_DYNAMIC_DISPATCH(LambertianSteps)(&b);
}

void quad_light_samples(QuadLightBlock& b, bool mis, MisHeuristic heuristic) {
    HWY_DYNAMIC_DISPATCH(QuadLightSamples)(&b, mis, heuristic);
}

void QuadLightBlock::push(size_t entry_,
                          const Vertex& vertex,
                          Vec3 wo_,
                          Color beta_,
                          float u1_,
                          float u2_,
                          const QuadEmitter& light,
                          float select_prob_) {
    const size_t k = rows++;
    for (int a = 0; a < 3; ++a) {
        p[a][k] = vertex.p[a];
        ng[a][k] = vertex.ng[a];
        ns[a][k] = vertex.frame.n[a];
        wo[a][k] = wo_[a];
        albedo[a][k] = vertex.bsdf.albedo[a];
        beta[a][k] = beta_[a];
        q[a][k] = light.q[a];
        u[a][k] = light.u[a];
        v[a][k] = light.v[a];
        n[a][k] = light.n[a];
        radiance[a][k] = light.radiance[a];
    }
    u1[k] = u1_;
    u2[k] = u2_;
    area[k] = light.area;
    select_prob[k] = select_prob_;
    two_sided[k] = light.two_sided ? 1.0f : 0.0f;
    entry[k] = static_cast<uint32_t>(entry_);
}

void LambertianBlock::push(size_t entry,
                           const Vertex& v,
                           Vec3 wo_,
                           Color beta_,
                           const ContinuationSamples& u,
                           float u_roulette,
                           bool roulette_) {
    const size_t k = n++;
    for (int a = 0; a < 3; ++a) {
        p[a][k] = v.p[a];
        ng[a][k] = v.ng[a];
        ns[a][k] = v.frame.n[a];
        wo[a][k] = wo_[a];
        albedo[a][k] = v.bsdf.albedo[a];
        beta[a][k] = beta_[a];
    }
    u1[k] = u.bsdf_u1;
    u2[k] = u.bsdf_u2;
    u_rr[k] = u_roulette;
    roulette[k] = roulette_ ? 1.0f : 0.0f;
    this->entry[k] = static_cast<uint32_t>(entry);
}

}  // namespace wavetrace
#endif  // HWY_ONCE
