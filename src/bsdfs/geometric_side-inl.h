// The geometric-side test every reflection at a surface passes, written once over lanes for
// eval_world (shading/path_vertex.cpp), the light samples (light_sample-inl.h) and the
// continuations (surface_step-inl.h). Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_GEOMETRIC_SIDE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_GEOMETRIC_SIDE_INL_H_
#undef WAVETRACE_BSDFS_GEOMETRIC_SIDE_INL_H_
#else
#define WAVETRACE_BSDFS_GEOMETRIC_SIDE_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Whether wo and wi lie on opposite sides of the geometric surface of normal ng. A reflecting
// lobe evaluated with the shading normal would then carry light through the surface where the
// two normals disagree (Veach 1997, §5.3), so such directions get no reflection. A vertex in a
// medium has ng = 0 and passes every direction.
template <class L>
HWY_INLINE typename L::M CrossesGeometricSurface(V3<typename L::F> wo,
                                                 V3<typename L::F> wi,
                                                 V3<typename L::F> ng) {
    return Dot(wo, ng) * Dot(wi, ng) < L::Set(0.0f);
}

// Where a sample wi from wo fails the geometric-side test: a transmission (`transmits`) must
// cross the geometric surface, a reflection must stay on wo's side.
template <class L>
HWY_INLINE typename L::M WrongGeometricSide(V3<typename L::F> wo,
                                            V3<typename L::F> wi,
                                            V3<typename L::F> ng,
                                            typename L::M transmits) {
    const typename L::M crosses = CrossesGeometricSurface<L>(wo, wi, ng);
    return L::Or(L::AndNot(transmits, crosses), L::AndNot(crosses, transmits));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_GEOMETRIC_SIDE_INL_H_
