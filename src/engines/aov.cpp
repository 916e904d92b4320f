#include "wavetrace/engines/aov.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "sampling/sampler.h"
#include "bsdfs/fresnel.h"
#include "shading/path_vertex.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/surface.h"

namespace wavetrace {
namespace {

constexpr int kMaxInterfaceCrossings = 64;

Color albedo_of(const Scene& scene, const SurfaceHit& s) {
    const Material& m = scene.materials[s.material];
    switch (m.kind) {
        case MaterialKind::Lambertian:
        case MaterialKind::Plastic:            // its base
        case MaterialKind::MetallicRoughness:  // its base colour
        case MaterialKind::Principled:         // its base colour
        case MaterialKind::Metal:
        case MaterialKind::Mirror:
        case MaterialKind::Isotropic:
            return eval_texture(scene, m.albedo, s.texture_point());
        case MaterialKind::Dielectric:
        case MaterialKind::ThinDielectric:
            return Color(1.0f);
        case MaterialKind::Conductor:  // its reflectance at normal incidence
            return eval_texture(scene, m.albedo, s.texture_point()) *
                   fresnel_conductor(1.0f, m.eta, m.k);
        case MaterialKind::DiffuseLight: {
            Color e = eval_texture(scene, m.emission, s.uv, s.p);
            float peak = max_component(e);
            return peak > 0 ? e / peak : e;
        }
        case MaterialKind::Interface:
        case MaterialKind::Blend:  // surface_at has chosen one of its materials
            break;
    }
    return {};
}

// One primary ray's AOV value.
Color trace_aov(const Scene& scene, const Bvh& bvh, Aov aov, Ray ray) {
    for (int crossing = 0; crossing < kMaxInterfaceCrossings; ++crossing) {
        Hit hit = bvh.intersect(ray);
        if (!hit.found()) return aov == Aov::Depth ? Color(kInfinity) : Color{};
        SurfaceHit s = surface_at(scene, ray, hit);
        if (scene.materials[s.material].kind == MaterialKind::Interface) {
            // Step past the boundary by the engines' origin offset, along the same line (so
            // that depth stays measured from the camera).
            ray.tmin = hit.t + origin_offset(s.p) / length(ray.d);
            continue;
        }
        switch (aov) {
            case Aov::Albedo:
                return albedo_of(scene, s);
            case Aov::Normal:
                return s.front_face ? s.ns : -s.ns;
            case Aov::Depth:
                return Color(hit.t * length(ray.d));
        }
    }
    return {};
}

}  // namespace

Image render_aov(const Scene& scene, const Bvh& bvh, Aov aov, const AovSettings& settings) {
    Image image(settings.width, settings.height);
    CameraRays camera(scene.camera, settings.width, settings.height);
    const int spp = std::max(1, settings.spp);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, settings.height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y < rows.end(); ++y)
                for (int x = 0; x < settings.width; ++x) {
                    uint32_t pixel = static_cast<uint32_t>(y) * settings.width + x;
                    Color sum{};
                    for (int i = 0; i < spp; ++i) {
                        auto u = [&](uint32_t dim) {
                            return sample_1d(settings.seed, pixel, i, dim);
                        };
                        // One sample: the pixel centre; more: jittered over the pixel's square.
                        float jx = spp == 1 ? 0.5f : u(kDimPixelX);
                        float jy = spp == 1 ? 0.5f : u(kDimPixelY);
                        Ray ray = camera.generate(x + jx, y + jy, u(kDimLensU), u(kDimLensV));
                        sum += trace_aov(scene, bvh, aov, ray);
                    }
                    image.at(x, y) = sum / static_cast<float>(spp);
                }
        });
    return image;
}

}  // namespace wavetrace
