#include "embree/embree_mirror.h"

#include <chrono>
#include <string>

#include "scene/opacity.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

// Embree's filter function for hits on masked geometry: each candidate hit (its distance in
// the ray's tfar) goes through the alpha masks as in our traversals (scene/opacity.h), and a
// cut-away one is rejected, so that Embree goes on to the next.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
    const Scene& scene = *static_cast<const Scene*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN* r = args->ray;
        RTCHitN* h = args->hit;
        const unsigned n = args->N;
        Ray ray;
        ray.o = {RTCRayN_org_x(r, n, i), RTCRayN_org_y(r, n, i), RTCRayN_org_z(r, n, i)};
        ray.d = {RTCRayN_dir_x(r, n, i), RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i)};
        const PrimRef prim =
            PrimRef::make(static_cast<PrimKind>(RTCHitN_geomID(h, n, i)), RTCHitN_primID(h, n, i));
        if (cut_away(scene, prim, RTCRayN_tfar(r, n, i), RTCHitN_u(h, n, i), RTCHitN_v(h, n, i),
                     ray))
            args->valid[i] = 0;
    }
}

void attach(const Scene& s, RTCScene scene, RTCGeometry g, PrimKind kind) {
    if (has_alpha_masks(s)) {
        rtcSetGeometryUserData(g, const_cast<Scene*>(&s));
        rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
        rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, static_cast<unsigned>(kind));
    rtcReleaseGeometry(g);
}

template <class T>
T* buffer(
    RTCGeometry g, RTCBufferType type, RTCFormat format, size_t stride, size_t n, size_t& total) {
    total += stride * n;
    return static_cast<T*>(rtcSetNewGeometryBuffer(g, type, 0, format, stride, n));
}

// Embree's memory monitor: `bytes` allocated (> 0) or freed (< 0) by the device.
bool count_bytes(void* held, ssize_t bytes, bool /*post*/) {
    *static_cast<std::atomic<long long>*>(held) += bytes;
    return true;
}

// Embree's own kernels capped at the SIMD target ours run on (use_simd_target), so that a
// comparison restricted to e.g. AVX2 holds on both sides; the best target: Embree's default.
std::string embree_config() {
    const std::string ours = simd_target();
    if (ours == simd_targets().front()) return "";
    if (ours == "AVX3") return "max_isa=avx512";
    if (ours == "AVX2") return "max_isa=avx2";
    if (ours == "SSE4") return "max_isa=sse4.2";
    return "max_isa=sse2";
}

}  // namespace

EmbreeMirror::EmbreeMirror(const Scene& s, RTCBuildQuality quality, bool robust) {
    const std::string config = embree_config();
    device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    rtcSetDeviceMemoryMonitorFunction(device_, count_bytes, &bytes_held_);
    auto start = std::chrono::steady_clock::now();
    scene_ = rtcNewScene(device_);
    if (robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, quality);
    if (!s.triangles.empty()) {
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(g, quality);
        auto* v = buffer<float>(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 12,
                                s.positions.size(), geometry_bytes_);
        for (size_t i = 0; i < s.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) v[3 * i + k] = s.positions[i][k];
        auto* idx = buffer<uint32_t>(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, 12,
                                     s.triangles.size(), geometry_bytes_);
        for (size_t i = 0; i < s.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) idx[3 * i + k] = s.triangles[i].v[k];
        attach(s, scene_, g, PrimKind::Triangle);
    }
    if (!s.quads.empty()) {
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
        rtcSetGeometryBuildQuality(g, quality);
        auto* v = buffer<float>(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 12,
                                4 * s.quads.size(), geometry_bytes_);
        auto* idx = buffer<uint32_t>(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT4, 16, s.quads.size(),
                                     geometry_bytes_);
        for (size_t i = 0; i < s.quads.size(); ++i) {
            const Quad& q = s.quads[i];
            const Point3 corners[4] = {q.q, q.q + q.u, q.q + q.u + q.v, q.q + q.v};
            for (int c = 0; c < 4; ++c) {
                for (int k = 0; k < 3; ++k) v[3 * (4 * i + c) + k] = corners[c][k];
                idx[4 * i + c] = static_cast<uint32_t>(4 * i + c);
            }
        }
        attach(s, scene_, g, PrimKind::Quad);
    }
    if (!s.spheres.empty()) {
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        rtcSetGeometryBuildQuality(g, quality);
        auto* v = buffer<float>(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT4, 16, s.spheres.size(),
                                geometry_bytes_);
        for (size_t i = 0; i < s.spheres.size(); ++i) {
            for (int k = 0; k < 3; ++k) v[4 * i + k] = s.spheres[i].center[k];
            v[4 * i + 3] = s.spheres[i].radius;
        }
        attach(s, scene_, g, PrimKind::Sphere);
    }
    rtcCommitScene(scene_);
    build_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

EmbreeMirror::~EmbreeMirror() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
}

Hit EmbreeMirror::intersect(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = ray.o.x;
    rh.ray.org_y = ray.o.y;
    rh.ray.org_z = ray.o.z;
    rh.ray.dir_x = ray.d.x;
    rh.ray.dir_y = ray.d.y;
    rh.ray.dir_z = ray.d.z;
    rh.ray.tnear = ray.tmin;
    rh.ray.tfar = ray.tmax;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    Hit hit;
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        hit.t = rh.ray.tfar;
        hit.prim = PrimRef::make(static_cast<PrimKind>(rh.hit.geomID), rh.hit.primID);
        hit.u = rh.hit.u;
        hit.v = rh.hit.v;
    }
    return hit;
}

bool EmbreeMirror::occluded(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r{};
    r.org_x = ray.o.x;
    r.org_y = ray.o.y;
    r.org_z = ray.o.z;
    r.dir_x = ray.d.x;
    r.dir_y = ray.d.y;
    r.dir_z = ray.d.z;
    r.tnear = ray.tmin;
    r.tfar = ray.tmax;
    r.mask = ~0u;
    rtcOccluded1(scene_, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on occlusion
}

namespace {

template <int N>
void trace_packet(RTCScene scene, const Ray* rays, Hit* hits) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(64) RTCRayHitNt<N> rh;
    alignas(64) int valid[N];
    for (int k = 0; k < N; ++k) {
        valid[k] = -1;
        rh.ray.org_x[k] = rays[k].o.x;
        rh.ray.org_y[k] = rays[k].o.y;
        rh.ray.org_z[k] = rays[k].o.z;
        rh.ray.dir_x[k] = rays[k].d.x;
        rh.ray.dir_y[k] = rays[k].d.y;
        rh.ray.dir_z[k] = rays[k].d.z;
        rh.ray.tnear[k] = rays[k].tmin;
        rh.ray.tfar[k] = rays[k].tmax;
        rh.ray.mask[k] = ~0u;
        rh.ray.time[k] = 0;
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    if constexpr (N == 8)
        rtcIntersect8(valid, scene, &context, reinterpret_cast<RTCRayHit8*>(&rh));
    else
        rtcIntersect16(valid, scene, &context, reinterpret_cast<RTCRayHit16*>(&rh));
    if (!hits) return;
    for (int k = 0; k < N; ++k) {
        hits[k] = Hit{};
        if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
            hits[k].t = rh.ray.tfar[k];
            hits[k].prim = PrimRef::make(static_cast<PrimKind>(rh.hit.geomID[k]), rh.hit.primID[k]);
        }
    }
}

}  // namespace

void EmbreeMirror::intersect_packet(const Ray* rays, int width, Hit* hits) const {
    if (width == 8)
        trace_packet<8>(scene_, rays, hits);
    else
        trace_packet<16>(scene_, rays, hits);
}

}  // namespace wavetrace
