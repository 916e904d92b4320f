// A path's free flight through a homogeneous medium along one ray segment: whether it scatters
// before the segment ends, and where; written once over lanes. scatters_in_medium (both
// engines' resolve_segment) runs the one-lane instance; the wavefront's shade kernel runs it
// over the segments of a chunk (blocks/lane_kernels.cpp). Per-target header, see
// math/lanes-inl.h.
#if defined(WAVETRACE_MEDIA_MEDIUM_FLIGHT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MEDIA_MEDIUM_FLIGHT_INL_H_
#undef WAVETRACE_MEDIA_MEDIUM_FLIGHT_INL_H_
#else
#define WAVETRACE_MEDIA_MEDIUM_FLIGHT_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// A segment of world length seg (infinity: it hits nothing) in a medium of `density`, with the
// optical depth *flight still to travel: the path scatters where that depth runs out, at world
// distance *dist = flight / density from the segment's origin, if that comes before the
// segment's end; else the depth the segment crosses is spent from *flight, and the rest carries
// over past the boundary (free flights are memoryless).
template <class L>
HWY_INLINE typename L::M ScattersInMedium(typename L::F seg,
                                          typename L::F density,
                                          typename L::F* flight,
                                          typename L::F* dist) {
    *dist = *flight / density;
    const auto scatters = *dist < seg;
    *flight = L::Select(scatters, *flight, *flight - density * seg);
    return scatters;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MEDIA_MEDIUM_FLIGHT_INL_H_
