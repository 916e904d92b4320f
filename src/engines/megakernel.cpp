// The megakernel: per pixel sample, a recursive ray_color in the seed's style (depth-limited,
// with Russian roulette), calling the shared per-vertex functions of shading/path_vertex.h.
#include "wavetrace/render/megakernel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>

#include "wavetrace/render/sampler.h"
#include "wavetrace/scene/bvh.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {
namespace {

constexpr int kTile = 16;
constexpr int kMaxCrossings = 64;  // medium boundaries crossed by one ray segment

struct PathContext {
    const Scene& scene;
    const Bvh& bvh;
    const LightSet& lights;
    const RenderConfig& config;
    uint32_t pixel;
    uint32_t sample;
    uint64_t rays = 0;

    float u(int bounce, BounceDim d) const {
        return sample_1d(config.seed, pixel, sample, bounce_dim(bounce, d));
    }
};

// What the vertex before a ray segment leaves for the emission it may find.
struct Previous {
    Point3 p;
    float pdf_bsdf = 0.0f;
    bool counts_fully = true;  // camera ray, or a vertex that could not sample lights
};

Color ray_color(PathContext& ctx, Ray ray, int bounce, MediumStack media, const Previous& prev,
                Color beta);

// Emission reaching the previous vertex along `ray`, weighted by the strategy.
float weight_for_emitter(const PathContext& ctx, const Previous& prev, PrimRef prim, Vec3 wi,
                         float dist) {
    if (prev.counts_fully || ctx.config.strategy != Strategy::Mis)
        return emission_weight(ctx.config.strategy, ctx.config.heuristic, prev.counts_fully, 0, 0);
    float pdf_light = prim.valid() ? ctx.lights.pdf_prim(ctx.scene, prev.p, prim, wi, dist)
                                   : ctx.lights.pdf_background(ctx.scene, wi);
    return emission_weight(ctx.config.strategy, ctx.config.heuristic, false, prev.pdf_bsdf, pdf_light);
}

// Scattering at a vertex: next-event estimation, then the continuation, recursively.
Color scatter(PathContext& ctx, const Vertex& v, Vec3 wo, int bounce, MediumStack media, Color beta) {
    Color radiance{0.0f};
    // A vertex may scatter only if the path may still grow by a segment.
    if (bounce + 1 >= ctx.config.max_depth) return radiance;
    const Strategy strategy = ctx.config.strategy;
    const bool lights_ok = can_sample_lights(v, ctx.lights);

    if (lights_ok && (strategy == Strategy::Nee || strategy == Strategy::Mis)) {
        DirectSample d = sample_direct(ctx.scene, ctx.lights, v, wo, ctx.u(bounce, kDimLightSelect),
                                       ctx.u(bounce, kDimLightU), ctx.u(bounce, kDimLightV));
        if (d.valid) {
            float w = strategy == Strategy::Mis
                          ? mis_weight(ctx.config.heuristic, d.pdf_light, d.pdf_bsdf)
                          : 1.0f;
            if (w > 0.0f) {
                float tr = transmittance(ctx.scene, ctx.bvh, d.shadow, media, &ctx.rays);
                radiance += d.value * (w * tr);
            }
        }
    }

    ContinuationSamples cs{ctx.u(bounce, kDimTechnique),  ctx.u(bounce, kDimDirectionSelect),
                           ctx.u(bounce, kDimDirectionU), ctx.u(bounce, kDimDirectionV),
                           ctx.u(bounce, kDimBsdfLobe),   ctx.u(bounce, kDimBsdfU),
                           ctx.u(bounce, kDimBsdfV)};
    Continuation c = sample_continuation(strategy, ctx.scene, ctx.lights, v, wo, cs);
    if (!c.valid) return radiance;
    Color weight = c.weight;
    if (bounce + 1 >= ctx.config.rr_depth) {
        float q = survival_probability(beta * weight);
        if (ctx.u(bounce, kDimRoulette) >= q) return radiance;
        weight /= q;
    }
    if (c.transmitted) media.cross(v.interior, dot(c.wi, v.ng) < 0.0f);
    Previous next{v.p, c.pdf_bsdf, c.delta || !lights_ok};
    Ray r{offset_origin(v, c.wi), c.wi};
    return radiance + weight * ray_color(ctx, r, bounce + 1, media, next, beta * weight);
}

// Radiance arriving along `ray` (the seed's ray_color). `bounce` numbers the vertex the ray
// will reach: 0 for camera rays.
Color ray_color(PathContext& ctx, Ray ray, int bounce, MediumStack media, const Previous& prev,
                Color beta) {
    const Scene& scene = ctx.scene;
    const float dir_length = length(ray.d);
    const Vec3 dir = ray.d / dir_length;
    // The free-flight distance is drawn once per segment; boundary crossings use up the
    // distance travelled in each medium (memorylessness keeps this exact).
    float flight = -std::log1p(-ctx.u(bounce, kDimMediumDistance));  // in optical depth units
    for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
        ++ctx.rays;
        Hit hit = ctx.bvh.intersect(ray);
        MediumId m = media.current();
        if (m != kNone) {
            float density = scene.media[m].density;
            float seg = hit.found() ? (hit.t - ray.tmin) * dir_length : kInfinity;
            float s = flight / density;  // world distance to the scattering event
            if (s < seg) {
                Point3 p = ray.o + (ray.tmin + s / dir_length) * ray.d;
                return scatter(ctx, medium_vertex(scene, m, p), -dir, bounce, media, beta);
            }
            flight -= density * seg;
        }
        if (!hit.found()) {
            if (scene.background.is_black()) return {};
            Color le = eval_background(scene, dir);
            return le * weight_for_emitter(ctx, prev, PrimRef{}, dir, kInfinity);
        }
        SurfaceHit s = surface_at(scene, ray, hit);
        const MaterialKind kind = scene.materials[s.material].kind;
        if (kind == MaterialKind::Interface) {
            media.cross(s.interior, s.front_face);
            ray.o = s.p + (2e-5f * (1.0f + max_component(abs(s.p)))) * dir;
            ray.d = dir;
            ray.tmin = 0.0f;
            continue;
        }
        if (kind == MaterialKind::DiffuseLight) {
            Color le = emitted_radiance(scene, s);
            if (max_component(le) <= 0.0f) return {};
            float dist = length(s.p - prev.p);
            return le * weight_for_emitter(ctx, prev, hit.prim, dir, dist);
        }
        return scatter(ctx, surface_vertex(scene, s), -dir, bounce, media, beta);
    }
    return {};
}

}  // namespace

Film render_megakernel(const Scene& scene, const Bvh& bvh, const RenderConfig& config,
                       RenderStats* stats, const ProgressCallback& progress) {
    auto start = std::chrono::steady_clock::now();
    Film film(config.width, config.height);
    LightSet lights(scene);
    CameraRays camera(scene.camera, config.width, config.height);
    const MediumStack camera_media = media_at(scene, bvh, scene.camera.look_from);
    const int tiles_x = (config.width + kTile - 1) / kTile;
    const int tiles_y = (config.height + kTile - 1) / kTile;
    std::atomic<uint64_t> rays{0};
    std::atomic<int> tiles_done{0};

    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& r) {
        for (int tile = r.begin(); tile < r.end(); ++tile) {
            const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
            uint64_t tile_rays = 0;
            for (int y = y0; y < std::min(y0 + kTile, config.height); ++y)
                for (int x = x0; x < std::min(x0 + kTile, config.width); ++x) {
                    const uint32_t pixel = static_cast<uint32_t>(y) * config.width + x;
                    for (int i = 0; i < config.spp; ++i) {
                        PathContext ctx{scene, bvh, lights, config, pixel, static_cast<uint32_t>(i)};
                        auto u = [&](uint32_t dim) { return sample_1d(config.seed, pixel, i, dim); };
                        Ray ray = camera.generate(x + u(kDimPixelX), y + u(kDimPixelY), u(kDimLensU),
                                                  u(kDimLensV));
                        Previous camera_vertex{ray.o, 0.0f, true};
                        Color c = ray_color(ctx, ray, 0, camera_media, camera_vertex, Color(1.0f));
                        film.add(static_cast<int>(pixel), c);
                        tile_rays += ctx.rays;
                    }
                }
            rays.fetch_add(tile_rays, std::memory_order_relaxed);
            int done = tiles_done.fetch_add(1) + 1;
            if (progress) progress(double(done) / (tiles_x * tiles_y));
        }
    });

    if (stats) {
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->paths = static_cast<uint64_t>(config.width) * config.height * config.spp;
        stats->rays = rays.load();
    }
    return film;
}

const char* to_string(Strategy s) {
    switch (s) {
        case Strategy::Bsdf: return "bsdf";
        case Strategy::Light: return "light";
        case Strategy::Mixture: return "mixture";
        case Strategy::Nee: return "nee";
        case Strategy::Mis: return "mis";
    }
    return "?";
}

std::optional<Strategy> parse_strategy(const std::string& name) {
    for (Strategy s : {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis})
        if (name == to_string(s)) return s;
    return std::nullopt;
}

}  // namespace wavetrace
