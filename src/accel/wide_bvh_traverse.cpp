// Single-ray traversal of the wide BVH with SIMD box and primitive tests
// (wide_ray_walk-inl.h, wide_leaf_tests-inl.h), compiled for every x86 (SSE4, AVX2, AVX-512) and
// ARM target Highway knows and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "accel/wide_bvh_traverse.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "accel/wide_bvh.h"
#include "accel/wide_leaf_tests-inl.h"
#include "accel/wide_ray_walk-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
// One traversal for both queries, from the root (wide_ray_walk-inl.h).
template <bool AnyHit>
HWY_INLINE bool Traverse(const WideBvh& bvh, const Ray& ray, Hit* hit) {
    if (bvh.nodes.empty()) return false;
    float tmax = ray.tmax;
    return WalkSubtree<AnyHit>(bvh, RayLanes(ray), 0, &tmax, hit);
}

bool IntersectWide(const WideBvh& bvh, const Ray& ray, Hit* hit) {
    return Traverse<false>(bvh, ray, hit);
}

bool OccludedWide(const WideBvh& bvh, const Ray& ray) {
    Hit unused;
    return Traverse<true>(bvh, ray, &unused);
}

bool AnyHitWide(const WideBvh& bvh, const Ray& ray, Hit* hit) {
    return Traverse<true>(bvh, ray, hit);
}

// Rays one after the other in one call: the stream of a wave's incoherent rays without a
// dispatch per ray.
void IntersectEach(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits) {
    for (size_t i = 0; i < n; ++i) {
        hits[i] = Hit{};
        Traverse<false>(bvh, rays[i], &hits[i]);
    }
}

void OccludedEach(const WideBvh& bvh, const Ray* rays, size_t n, bool* occluded) {
    for (size_t i = 0; i < n; ++i) {
        Hit unused;
        occluded[i] = Traverse<true>(bvh, rays[i], &unused);
    }
}

void AnyHitEach(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits) {
    for (size_t i = 0; i < n; ++i) {
        hits[i] = Hit{};
        Traverse<true>(bvh, rays[i], &hits[i]);
    }
}

const char* TargetName() {
    return hwy::TargetName(HWY_TARGET);
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(IntersectWide);
HWY_EXPORT(OccludedWide);
HWY_EXPORT(AnyHitWide);
HWY_EXPORT(TargetName);
HWY_EXPORT(IntersectEach);
HWY_EXPORT(OccludedEach);
HWY_EXPORT(AnyHitEach);

void wide_intersect_each(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits) {
    HWY_DYNAMIC_DISPATCH(IntersectEach)(bvh, rays, n, hits);
}

void wide_occluded_each(const WideBvh& bvh, const Ray* rays, size_t n, bool* occluded) {
    HWY_DYNAMIC_DISPATCH(OccludedEach)(bvh, rays, n, occluded);
}

void wide_any_hit_each(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits) {
    HWY_DYNAMIC_DISPATCH(AnyHitEach)(bvh, rays, n, hits);
}

bool wide_intersect(const WideBvh& bvh, const Ray& ray, Hit* hit) {
    return HWY_DYNAMIC_DISPATCH(IntersectWide)(bvh, ray, hit);
}

bool wide_occluded(const WideBvh& bvh, const Ray& ray) {
    return HWY_DYNAMIC_DISPATCH(OccludedWide)(bvh, ray);
}

bool wide_any_hit(const WideBvh& bvh, const Ray& ray, Hit* hit) {
    return HWY_DYNAMIC_DISPATCH(AnyHitWide)(bvh, ray, hit);
}

const char* wide_simd_target() {
    return HWY_DYNAMIC_DISPATCH(TargetName)();
}

namespace {

int64_t g_disabled = 0;  // the better targets use_simd_target turned off

// Every target compiled in that this CPU runs, the best first. Highway 1.0's SupportedTargets()
// makes the best of them the choice again before it applies DisableTargets' mask, so asking it
// would undo use_simd_target: the mask is cleared to list them all, and the choice made again.
std::vector<int64_t> runnable_targets() {
    hwy::DisableTargets(0);
    std::vector<int64_t> all = hwy::SupportedAndGeneratedTargets();
    hwy::DisableTargets(g_disabled);
    hwy::GetChosenTarget().Update(hwy::SupportedTargets());
    return all;
}

}  // namespace

std::vector<int64_t> wide_simd_targets() {
    return runnable_targets();
}

void use_wide_simd_target(int64_t target) {
    hwy::SetSupportedTargetsForTest(target);
    hwy::GetChosenTarget().Update(hwy::SupportedTargets());
}

std::vector<std::string> simd_targets() {
    std::vector<std::string> names;
    for (int64_t t : runnable_targets()) names.push_back(hwy::TargetName(t));
    return names;
}

bool use_simd_target(const std::string& name) {
    auto lower = [](std::string s) {
        for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    // Highway's better targets (the lower bits) disabled, or none; a name not among the targets
    // keeps the previous choice.
    int64_t chosen = -1;
    for (int64_t t : runnable_targets())
        if (name.empty() ? chosen < 0 : lower(hwy::TargetName(t)) == lower(name)) chosen = t;
    if (chosen < 0) return false;
    g_disabled = name.empty() ? 0 : chosen - 1;
    hwy::DisableTargets(g_disabled);
    hwy::GetChosenTarget().Update(hwy::SupportedTargets());
    return true;
}

}  // namespace wavetrace
#endif  // HWY_ONCE
