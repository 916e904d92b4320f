#include <algorithm>

#include "kernels/kernels.h"
#include "kernels/lane_kernels.h"
#include "shading/path_vertex.h"

namespace wavetrace {
namespace {

void append_shadow(
    const Ray& ray, Color contribution, size_t path, ShadowQueue& shadows, size_t& s) {
    shadows.origin[s] = ray.o;
    shadows.dir[s] = ray.d;
    shadows.tmax[s] = ray.tmax;
    shadows.contribution[s] = contribution;
    shadows.path[s] = static_cast<uint32_t>(path);
    ++s;
}

// Entry i goes on from its scattering vertex: throughput, the record for weighting emission the
// next segment finds, the next ray. Vertices that sample lights never transmit, so the entry's
// media stay what its shadow ray (which reads its path's media) needs.
void advance(const WaveInputs& in,
             uint32_t sample,
             size_t i,
             Color weight,
             const PreviousVertex& prev,
             const Ray& next,
             PathQueue& paths,
             RayQueue& rays,
             std::span<uint8_t> keep) {
    const int bounce = paths.bounce[i];
    paths.beta[i] = paths.beta[i] * weight;
    set_previous_vertex(paths, i, prev);
    paths.bounce[i] = static_cast<uint16_t>(bounce + 1);
    paths.flight[i] = segment_flight(in.scene, in.config.seed, paths.pixel[i], sample, bounce + 1);
    paths.crossings[i] = 0;
    set_ray(rays, i, next);
    keep[i] = 1;
}

Vec3 row(const float (*rows)[kShadeChunk], size_t k) {
    return {rows[0][k], rows[1][k], rows[2][k]};
}

}  // namespace

// Chunk by chunk: the vertices' uniform numbers in SIMD lanes; each entry's segment in scalar
// code; the light samples towards quad lights and the continuations of Lambertian vertices
// gathered into blocks and run in SIMD lanes at the end of the chunk, the rest in scalar code.
// Shadow rays are appended in a fixed order (scalar ones, then the block's), so the queue, and
// the image, do not depend on the target.
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
            const Vertex& v = seg.vertex;
            const Color beta = paths.beta[i];
            const VertexSamples u = samples.at(i - c);
            // Lambertian surface vertices go to the block for their light samples towards quad
            // lights and their continuations; the rest is taken here.
            const bool nee = samples_lights(cfg, v, in.lights);
            const LightChoice light = nee ? in.lights.select(u.light_select) : LightChoice{};
            const int32_t quad_index = nee ? quad_light_sample_at(v, in.lights, light) : -1;
            const bool quad = quad_index >= 0;
            const bool diffuse_step = takes_lambertian_step(cfg, v, in.lights);
            if (quad || diffuse_step) {
                const size_t row = lambertian.push(i, v, seg.wo, beta);
                if (quad)
                    lambertian.set_light_sample(row, quad_index, light.probability, u.light_u,
                                                u.light_v);
                if (diffuse_step)
                    lambertian.set_step(row, u.continuation, u.roulette,
                                        bounce + 1 >= cfg.rr_depth);
            }
            if (nee && !quad) {
                const WeightedDirect d = next_event(in.scene, in.lights, cfg, v, seg.wo, u, light);
                if (d.weight > 0.0f)
                    append_shadow(d.sample.shadow, beta * (d.sample.value * d.weight), i, shadows,
                                  s);
            }
            if (diffuse_step) continue;
            const PathStep step = continue_path(in.scene, in.lights, cfg, v, seg.wo, bounce, beta,
                                                media, u.continuation, u.roulette);
            if (!step.alive) continue;
            paths.media[i] = PackedMedia::pack(media);
            advance(in, sample, i, step.weight, step.prev, step.next, paths, rays, keep);
        }

        lambertian_vertices(lambertian, in.lights.quad_emitter_columns(),
                            cfg.strategy == Strategy::Mis, cfg.heuristic);
        const bool counts_fully = in.lights.empty();  // Lambertian vertices sample lights if any
        for (size_t k = 0; k < lambertian.n; ++k) {
            if (lambertian.shadow[k] != 0.0f)
                append_shadow(Ray{row(lambertian.shadow_origin, k), row(lambertian.shadow_dir, k),
                                  0.0f, lambertian.tmax[k]},
                              row(lambertian.contribution, k), lambertian.entry[k], shadows, s);
            if (lambertian.alive[k] != 0.0f)
                advance(in, sample, lambertian.entry[k], row(lambertian.weight, k),
                        {row(lambertian.p, k), lambertian.pdf[k], counts_fully},
                        Ray{row(lambertian.origin, k), row(lambertian.wi, k)}, paths, rays, keep);
        }
    }
    return s - first_shadow;
}

}  // namespace wavetrace
