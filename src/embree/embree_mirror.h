// The scene mirrored into Embree 3, the reference our BVH is checked and benchmarked against:
// geometry id = primitive kind (triangles, quads as quads, spheres as sphere points),
// primitive id = index, so hits compare one to one with PrimRefs. Used only by tests and
// benchmarks; the renderer itself does not link Embree.
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstddef>

#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/ray.h"

namespace wavetrace {

struct Scene;

class EmbreeMirror {
  public:
    // quality: RTC_BUILD_QUALITY_MEDIUM (Embree's default) or RTC_BUILD_QUALITY_HIGH.
    explicit EmbreeMirror(const Scene& scene,
                          RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM,
                          bool robust = true);
    ~EmbreeMirror();
    EmbreeMirror(const EmbreeMirror&) = delete;
    EmbreeMirror& operator=(const EmbreeMirror&) = delete;

    Hit intersect(const Ray& ray) const;  // rtcIntersect1
    bool occluded(const Ray& ray) const;  // rtcOccluded1
    // rtcIntersect8 / rtcIntersect16 on `width` (8 or 16) rays at once; hits may be null when
    // only the tracing matters (benchmarks).
    void intersect_packet(const Ray* rays, int width, Hit* hits = nullptr) const;
    RTCScene scene() const { return scene_; }
    double build_ms() const { return build_ms_; }
    // What the device holds once the scene is built, as its memory monitor counts it
    // (rtcSetDeviceMemoryMonitorFunction): the acceleration structure and the vertex and index
    // buffers the mirror filled, whose share is geometry_bytes().
    size_t bytes() const { return static_cast<size_t>(bytes_held_); }
    size_t geometry_bytes() const { return geometry_bytes_; }

  private:
    RTCDevice device_;
    RTCScene scene_;
    double build_ms_ = 0;
    std::atomic<long long> bytes_held_{0};
    size_t geometry_bytes_ = 0;
};

}  // namespace wavetrace
