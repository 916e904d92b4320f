#include <algorithm>

#include "kernels/kernels.h"
#include "kernels/shade_lanes.h"
#include "shading/path_vertex.h"

namespace wavetrace {

size_t shade(const WaveInputs& in,
             uint32_t sample,
             const HitQueue& hits,
             size_t begin,
             size_t end,
             PathQueue& paths,
             RayQueue& rays,
             std::span<uint8_t> keep,
             ShadowQueue& shadows,
             size_t first_shadow) {
    const RenderConfig& cfg = in.config;
    size_t s = first_shadow;
    // Chunk by chunk: the vertices' uniform numbers in SIMD lanes, then each entry's segment
    // and light sample in scalar code, with the Lambertian continuations gathered for one
    // SIMD pass at the end of the chunk.
    SampleBlock samples;
    LambertianBlock lambertian;
    for (size_t c = begin; c < end; c += kShadeChunk) {
        const size_t chunk_end = std::min(end, c + kShadeChunk);
        draw_vertex_samples(cfg.seed, sample, &paths.pixel[c], &paths.bounce[c], chunk_end - c,
                            samples);
        lambertian.n = 0;
        for (size_t i = c; i < chunk_end; ++i) {
            keep[i] = 0;

            // ---- the segment: medium, emission, boundary or surface ----
            MediumStack media = paths.media[i].unpack();
            float flight = paths.flight[i];
            const SegmentResult seg =
                resolve_segment(in.scene, in.lights, cfg, ray_at(rays, i), hit_at(hits, i), media,
                                flight, previous_vertex(paths, i));
            if (seg.event == SegmentEvent::Cross) {
                if (++paths.crossings[i] >= kMaxBoundaryCrossings) continue;
                paths.media[i] = PackedMedia::pack(media);
                paths.flight[i] = flight;
                set_ray(rays, i, seg.next);
                keep[i] = 1;
                continue;
            }
            // Emission found; at an emitter that also reflects, the path scatters on from it.
            if (seg.event == SegmentEvent::Emission || seg.event == SegmentEvent::Scatter)
                paths.radiance[i] += paths.beta[i] * seg.emission;
            if (seg.event != SegmentEvent::Scatter) continue;

            // ---- a scattering vertex: a light sample, then the continuation ----
            const int bounce = paths.bounce[i];
            if (!may_scatter(cfg, bounce)) continue;
            const uint32_t pixel = paths.pixel[i];
            const Color beta = paths.beta[i];
            const VertexSamples u = samples.at(i - c);
            const WeightedDirect d = next_event(in.scene, in.lights, cfg, seg.vertex, seg.wo, u);
            if (d.weight > 0.0f) {
                shadows.origin[s] = d.sample.shadow.o;
                shadows.dir[s] = d.sample.shadow.d;
                shadows.tmax[s] = d.sample.shadow.tmax;
                shadows.contribution[s] = beta * (d.sample.value * d.weight);
                shadows.path[s] = static_cast<uint32_t>(i);
                ++s;
            }
            if (takes_lambertian_step(cfg, seg.vertex, in.lights)) {
                lambertian.push(i, seg.vertex, seg.wo, beta, u.continuation, u.roulette,
                                bounce + 1 >= cfg.rr_depth);
                continue;
            }
            // Vertices that sample lights never transmit, so `media` stays what the shadow ray
            // (which reads its path's media) needs.
            const PathStep step = continue_path(in.scene, in.lights, cfg, seg.vertex, seg.wo,
                                                bounce, beta, media, u.continuation, u.roulette);
            if (!step.alive) continue;
            paths.beta[i] = beta * step.weight;
            set_previous_vertex(paths, i, step.prev);
            paths.media[i] = PackedMedia::pack(media);
            paths.bounce[i] = static_cast<uint16_t>(bounce + 1);
            paths.flight[i] = segment_flight(in.scene, cfg.seed, pixel, sample, bounce + 1);
            paths.crossings[i] = 0;
            set_ray(rays, i, step.next);
            keep[i] = 1;
        }
        lambertian_steps(lambertian);
        const bool counts_fully = in.lights.empty();  // Lambertian vertices sample lights if any
        for (size_t k = 0; k < lambertian.n; ++k) {
            if (lambertian.alive[k] == 0.0f) continue;
            const size_t i = lambertian.entry[k];
            auto row = [&](const float(*rows)[kShadeChunk]) {
                return Vec3{rows[0][k], rows[1][k], rows[2][k]};
            };
            const int bounce = paths.bounce[i];
            paths.beta[i] = paths.beta[i] * row(lambertian.weight);
            set_previous_vertex(paths, i, {row(lambertian.p), lambertian.pdf[k], counts_fully});
            paths.bounce[i] = static_cast<uint16_t>(bounce + 1);
            paths.flight[i] =
                segment_flight(in.scene, cfg.seed, paths.pixel[i], sample, bounce + 1);
            paths.crossings[i] = 0;
            set_ray(rays, i, Ray{row(lambertian.origin), row(lambertian.wi)});
            keep[i] = 1;
        }
    }
    return s - first_shadow;
}

}  // namespace wavetrace
