#pragma once

#include <algorithm>
#include <span>

#include "accel/intersector.h"
#include "kernels/wave.h"

namespace wavetrace {

// An intersector that also traces a stream of rays one by one in one call (our BVH), with the
// hits of one call per ray.
template <class T>
concept StreamIntersector = Intersector<T> &&
    requires(const T& t, std::span<const Ray> rays, std::span<Hit> hits, std::span<bool> occluded) {
    t.intersect_each(rays, hits);
    t.occluded_each(rays, occluded);
};

// Rays gathered from the queue kBatch at a time, for the batch calls below.
inline constexpr size_t kRayBatch = 64;

// Rays [begin, end) of the queue gathered kRayBatch at a time, each batch's hits from
// trace(rays, hits) stored back: the loop of the batch calls below.
template <class Trace>
void trace_in_batches(
    const RayQueue& rays, size_t begin, size_t end, HitQueue& hits, const Trace& trace) {
    Ray batch[kRayBatch];
    Hit found[kRayBatch];
    for (size_t b = begin; b < end; b += kRayBatch) {
        const size_t m = std::min(kRayBatch, end - b);
        for (size_t k = 0; k < m; ++k) batch[k] = ray_at(rays, b + k);
        trace(std::span<const Ray>(batch, m), std::span<Hit>(found, m));
        for (size_t k = 0; k < m; ++k) set_hit(hits, b + k, found[k]);
    }
}

// Closest hit of rays[i] into hits[i].
template <Intersector Tracer>
void intersect(
    const Tracer& tracer, const RayQueue& rays, size_t begin, size_t end, HitQueue& hits) {
    if constexpr (StreamIntersector<Tracer>) {
        trace_in_batches(rays, begin, end, hits, [&](std::span<const Ray> r, std::span<Hit> h) {
            tracer.intersect_each(r, h);
        });
    } else {
        for (size_t i = begin; i < end; ++i) set_hit(hits, i, tracer.intersect(ray_at(rays, i)));
    }
}

// An intersector that also traces packets of rays together, with the same hits as one by one
// (our BVH: 8 rays per packet). Embree's mirror does not qualify: rtcIntersect8 rounds some hits
// differently from rtcIntersect1, which would make the two engines trace different paths.
template <class T>
concept PacketIntersector = Intersector<T> &&
    requires(const T& t, std::span<const Ray> rays, std::span<Hit> hits) {
    t.intersect_packet(rays, hits);
};

// The same for coherent rays (a wave's camera rays, in 4x2 pixel tiles): traced as packets
// where the intersector has them, with the same hits as one by one. (Where a packet's rays
// part ways, each walks on alone: wide_bvh_packets.cpp.)
template <Intersector Tracer>
void intersect_coherent(
    const Tracer& tracer, const RayQueue& rays, size_t begin, size_t end, HitQueue& hits) {
    if constexpr (PacketIntersector<Tracer>) {
        trace_in_batches(rays, begin, end, hits, [&](std::span<const Ray> r, std::span<Hit> h) {
            tracer.intersect_packet(r, h);
        });
    } else {
        intersect(tracer, rays, begin, end, hits);
    }
}

}  // namespace wavetrace
