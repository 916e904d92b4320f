// The camera ray through a film position, written once over lanes: CameraRays::generate is the
// one-lane instance, the wavefront's generate kernel runs it a vector of pixels at a time
// (kernels/generate_lanes.cpp). Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_SCENE_CAMERA_RAY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SCENE_CAMERA_RAY_INL_H_
#undef WAVETRACE_SCENE_CAMERA_RAY_INL_H_
#else
#define WAVETRACE_SCENE_CAMERA_RAY_INL_H_
#endif

#include "math/lanes-inl.h"
#include "sampling/pixel_filter-inl.h"
#include "sampling/sampler-inl.h"
#include "wavetrace/scene/camera.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

template <class L>
HWY_INLINE V3<typename L::F> Broadcast(Vec3 v) {
    return {L::Set(v.x), L::Set(v.y), L::Set(v.z)};
}

// The camera of Ray Tracing in One Weekend (§12-13): a film on the focus plane, rays from a disk
// lens, or an orthographic camera's parallel rays from its film. (x, y) in pixels, (lens_u, lens_v)
// in [0,1)^2 pick the lens point by the polar map (r = sqrt(u1), phi = 2 pi u2). The direction is
// not normalized.
template <class L>
HWY_INLINE void CameraRay(const CameraFrame& c,
                          typename L::F x,
                          typename L::F y,
                          typename L::F lens_u,
                          typename L::F lens_v,
                          V3<typename L::F>* origin,
                          V3<typename L::F>* dir) {
    using F = typename L::F;
    const V3<F> target = Broadcast<L>(c.pixel00) + Broadcast<L>(c.du) * x + Broadcast<L>(c.dv) * y;
    if (c.orthographic()) {
        *origin = target;
        *dir = Broadcast<L>(c.parallel);
        return;
    }
    V3<F> o = Broadcast<L>(c.origin);
    if (c.has_lens()) {
        F sin_phi, cos_phi;
        SinCos2Pi<L>(lens_v, &sin_phi, &cos_phi);
        const F r = L::Sqrt(lens_u);
        o = o + (Broadcast<L>(c.lens_u) * (r * cos_phi) + Broadcast<L>(c.lens_v) * (r * sin_phi));
    }
    *origin = o;
    *dir = target - o;
}

// The camera ray of one sample of pixel (x, y), its path's sampler state `state`: placed about
// the pixel's centre by the reconstruction filter and on the lens by the camera dimensions
// (sampling/sampler.h). What generate_camera_ray (one lane) and the generate kernel (a vector
// of pixels) both run.
template <class L>
HWY_INLINE void SampledCameraRay(const CameraFrame& c,
                                 const SampleState<L>& state,
                                 typename L::F x,
                                 typename L::F y,
                                 V3<typename L::F>* origin,
                                 V3<typename L::F>* dir) {
    using F = typename L::F;
    F ux, uy;
    SampleDimPair<L>(state, L::Set64(kDimPixelX), &ux, &uy);
    const PixelFilter& f = c.filter;
    F fx, fy;
    if (f.kind == PixelFilter::Kind::Box && f.radius == 0.5f) {
        // Uniform over the pixel itself, written as it always was (bit for bit).
        fx = x + ux;
        fy = y + uy;
    } else {
        F ox, oy;
        if (f.kind == PixelFilter::Kind::Tent) {
            ox = TentOffset<L>(ux, f.radius);
            oy = TentOffset<L>(uy, f.radius);
        } else if (f.kind == PixelFilter::Kind::Gaussian) {
            ox = GaussianOffset<L>(ux, f.sigma, c.filter_erf);
            oy = GaussianOffset<L>(uy, f.sigma, c.filter_erf);
        } else {
            ox = (L::Set(2.0f) * ux - L::Set(1.0f)) * L::Set(f.radius);
            oy = (L::Set(2.0f) * uy - L::Set(1.0f)) * L::Set(f.radius);
        }
        fx = x + L::Set(0.5f) + ox;
        fy = y + L::Set(0.5f) + oy;
    }
    F lens_u = L::Set(0.0f), lens_v = L::Set(0.0f);  // unused without a lens
    if (c.has_lens()) SampleDimPair<L>(state, L::Set64(kDimLensU), &lens_u, &lens_v);
    CameraRay<L>(c, fx, fy, lens_u, lens_v, origin, dir);
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SCENE_CAMERA_RAY_INL_H_
