#include <algorithm>

#include "kernels/kernels.h"
#include "kernels/lane_kernels.h"
#include "shading/path_vertex.h"
#include "util/check.h"

namespace wavetrace {
namespace {

void append_shadow(
    const Ray& ray, Color contribution, size_t path, ShadowQueue& shadows, size_t& s) {
    WT_DCHECK_LT(s, shadows.capacity);
    shadows.origin[s] = ray.o;
    shadows.dir[s] = ray.d;
    shadows.tmax[s] = ray.tmax;
    shadows.contribution[s] = contribution;
    shadows.path[s] = static_cast<uint32_t>(path);
    ++s;
}

// Entry i goes on from its scattering vertex: throughput, the record for weighting emission the
// next segment finds, the next ray and the optical depth it may travel in media (`flight`: the
// SampleBlock's). Vertices that sample lights never transmit, so the entry's media stay what its
// shadow ray (which reads its path's media) needs.
void advance(size_t i,
             Color weight,
             const PreviousVertex& prev,
             const Ray& next,
             float flight,
             PathQueue& paths,
             RayQueue& rays,
             std::span<uint8_t> keep) {
    paths.beta[i] = paths.beta[i] * weight;
    set_previous_vertex(paths, i, prev);
    paths.bounce[i] = static_cast<uint16_t>(paths.bounce[i] + 1);
    paths.flight[i] = flight;
    paths.crossings[i] = 0;
    set_ray(rays, i, next);
    keep[i] = 1;
}

// The BSDF surface_vertex gives material m, if it is Lambertian or a rough metal: the materials
// whose surface vertices shade needs nothing of but the hit's point and normals, and, where the
// albedo is a texture other than a Solid one (an image, a noise, a checker; *textured), its
// texture coordinates: that albedo is looked up once the block has resolved the hit
// (textured_albedo), and *bsdf holds albedo 0 until then.
bool lane_material(const Scene& scene, MaterialId m, BsdfParams* bsdf, bool* textured) {
    if (m == kNone) return false;
    const Material& mat = scene.materials[m];
    if (!(mat.kind == MaterialKind::Lambertian || mat.kind == MaterialKind::Metal) ||
        mat.albedo == kNone)
        return false;
    const Texture& albedo = scene.textures[mat.albedo];
    *textured = albedo.kind != TextureKind::Solid;
    *bsdf = material_bsdf(mat, *textured ? Color(0.0f) : albedo.color);
    return mat.kind == MaterialKind::Lambertian || bsdf->alpha > 0.0f;  // not a mirror
}

// A block row of material m resolved from a hit on a sphere or a quad: surface_vertex's BSDF,
// from surface_at's texture coordinates (the sphere's from its outward normal, the quad's the
// hit's (u, v)) and the resolved point.
struct TexturedRow {
    size_t row;
    MaterialId material;
    bool sphere;
};
void textured_albedo(const Scene& scene, const TexturedRow& t, SurfaceBlock& block) {
    const size_t k = t.row;
    const Point3 p = block_row(block.p, k);
    const Vec2 uv =
        t.sphere ? sphere_uv(block_row(block.ng, k)) : Vec2{block.hit_u[k], block.hit_v[k]};
    const Material& mat = scene.materials[t.material];
    const BsdfParams bsdf = material_bsdf(mat, eval_texture(scene, mat.albedo, uv, p));
    for (int a = 0; a < 3; ++a) block.albedo[a][k] = bsdf.albedo[a];
    block.alpha[k] = bsdf.alpha;
}

// A chunk's mesh hits read a triangle record and then its vertices' positions and normals, from
// arrays that outgrow the L2 on a large mesh (the dragon's: 3 MiB). Read entry by entry, among
// each entry's branchy shading, those loads wait one after the other: prefetched a few entries
// ahead (records at the chunk's start, vertices four entries ahead) they still held 45% of
// `shade`'s samples on the dragon (`perf annotate -l`), and prefetching further ahead did not
// help. So where the mesh data outgrows the L1, a chunk first reads its triangle records in a
// tight loop of loads that do not depend on one another, so that the core has many in flight
// at once, then asks for all their vertices; the entries find them arrived. (`shade`'s samples
// on the dragon 1,474 -> 1,085, the wavefront 1.29 -> 1.34 Mpaths/s; the bunny 956 -> 829 and
// 2.02 -> 2.04: `perf record -F 4000` of `wavetrace render scenes/S.json --width 320 --height
// 320 --spp 32 --threads 1 --engine wavefront`, medians of five interleaved runs. Copying the
// vertices into a chunk array instead: 1,187 and 1.33 on the dragon.) Below that size the data
// stays in the L1, and the loop over the chunk's hits would cost more than it saves.
constexpr size_t kPrefetchMeshBytes = 64 * 1024;

bool prefetches_meshes(const Scene& scene) {
    return scene.triangles.size() * sizeof(Triangle) +
               scene.positions.size() * (sizeof(Point3) + sizeof(Normal3)) >
           kPrefetchMeshBytes;
}

// The triangle records of a chunk's mesh hits. `shade` owns them for all its chunks: the same
// array on the function's own stack took `shade`'s samples on the dragon from ~900 to ~1,170
// (medians of five, the command above; not understood).
struct ChunkTriangles {
    Triangle tri[kShadeChunk];
};

void prefetch_chunk_vertices(
    const Scene& scene, const HitQueue& hits, size_t begin, size_t end, ChunkTriangles& records) {
    size_t count = 0;
    for (size_t i = begin; i < end; ++i)
        if (const PrimRef p = hits.prim[i]; p.valid() && p.kind() == PrimKind::Triangle)
            records.tri[count++] = scene.triangles[p.index()];
    const Normal3* normals = scene.normals.empty() ? nullptr : scene.normals.data();
    for (size_t j = 0; j < count; ++j)
        for (int v = 0; v < 3; ++v) {
            __builtin_prefetch(&scene.positions[records.tri[j].v[v]]);
            if (normals) __builtin_prefetch(normals + records.tri[j].v[v]);
        }
}

// A light sample of a row resolved in lanes towards a light other than a quad: once the row's
// vertex is known, a sphere seen from outside goes back to the block, anything else is taken in
// scalar code.
struct DeferredLightSample {
    size_t row;
    LightChoice light;
    float u1, u2;
};

// Entry i goes straight on past a medium boundary: `media` and `flight` after it, the next ray;
// or ends, after too many crossings in one segment.
void cross(size_t i,
           const MediumStack& media,
           float flight,
           const Ray& next,
           PathQueue& paths,
           RayQueue& rays,
           std::span<uint8_t> keep) {
    if (++paths.crossings[i] >= kMaxBoundaryCrossings) return;
    paths.media[i] = PackedMedia::pack(media);
    paths.flight[i] = flight;
    set_ray(rays, i, next);
    keep[i] = 1;
}

// Shades entry i without resolve_segment where its segment needs none of it: where the path
// scatters in a medium of isotropic phase function, or reaches a hit on a Lambertian or rough
// metal quad, triangle or sphere (lane_material; of textured albedo only a quad or a sphere),
// the vertex becomes a row of
// the block (or nothing, at the last bounce: there resolve_segment finds no emission, and the
// vertex takes the lane step) when `lanes`; where it escapes into a black background it ends;
// where it reaches a medium boundary it crosses. False for the scalar path.
bool shade_quickly(const WaveInputs& in,
                   size_t i,
                   size_t chunk_row,
                   const SampleBlock& samples,
                   const MediumSegmentBlock& segments,
                   const HitQueue& hits,
                   bool lanes,
                   bool nee,
                   RayQueue& rays,
                   PathQueue& paths,
                   std::span<uint8_t> keep,
                   SurfaceBlock& block,
                   DeferredLightSample* deferred,
                   size_t& deferred_count,
                   TexturedRow* textured,
                   size_t& textured_count) {
    const Scene& scene = in.scene;
    const PrimRef prim = hits.prim[i];
    const int bounce = paths.bounce[i];
    // The light sample (towards a quad light in the block, other lights deferred) and the
    // continuation of the row just pushed.
    auto sample_and_step = [&](size_t row) {
        const VertexSamples u = samples.at(chunk_row);
        if (nee && !in.lights.empty()) {
            const LightChoice light = in.lights.select(u.light_select);
            if (const int32_t quad = in.lights.quad_emitter_index(light); quad >= 0)
                block.set_light_sample(row, quad, light.probability, u.light_u, u.light_v);
            else
                deferred[deferred_count++] = {row, light, u.light_u, u.light_v};
        }
        block.set_step(row, u.continuation, u.roulette, bounce + 1 >= in.estimator.rr_depth);
    };
    // In a medium, the path scatters on the way to the hit (resolve_segment's first event:
    // `segments`, drawn for the chunk in lanes), or reaches it with `flight` left; the optical
    // depth left is not needed past a scattering vertex.
    float flight = paths.flight[i];
    if (!scene.media.empty()) {
        if (!lanes) return false;
        flight = segments.flight[chunk_row];
        if (segments.scatters[chunk_row] != 0.0f) {
            if (!may_scatter(in.estimator, bounce)) return true;  // the path ends here
            const Ray ray{rays.origin[i], rays.dir[i]};
            const float dir_length = segments.dir_length[chunk_row];
            const Vertex v =
                medium_vertex(scene, paths.media[i].current(),
                              scattering_point(ray, segments.dist[chunk_row], dir_length));
            sample_and_step(block.push(i, v, -(ray.d / dir_length), paths.beta[i]));
            return true;
        }
    }
    if (!prim.valid()) return scene.background.is_black();  // nothing found: the path ends
    const uint32_t index = prim.index();
    const Triangle* tri = nullptr;
    MaterialId m = kNone;
    switch (prim.kind()) {
        case PrimKind::Quad:
            m = scene.quads[index].material;
            break;
        case PrimKind::Triangle:
            tri = &scene.triangles[index];
            m = scene.meshes[tri->mesh].material;
            break;
        case PrimKind::Sphere:
            m = scene.spheres[index].material;
            break;
    }
    if (scene.is_boundary(m)) {
        const Ray ray = ray_at(rays, i);
        MediumStack media = paths.media[i].unpack();
        const Ray next =
            cross_boundary(surface_at(scene, ray, hit_at(hits, i)), ray.d / length(ray.d), media);
        cross(i, media, flight, next, paths, rays, keep);
        return true;
    }
    BsdfParams bsdf;
    bool texture = false;
    // Textured meshes stay scalar: their texture coordinates come from the mesh's vertices.
    if (!lanes || !lane_material(scene, m, &bsdf, &texture) || (texture && tri)) return false;
    if (!may_scatter(in.estimator, bounce)) return true;  // the path ends here, with nothing found
    size_t row;
    if (tri) {
        const Mesh& mesh = scene.meshes[tri->mesh];
        Point3 p[3];
        Normal3 n[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = scene.positions[tri->v[k]];
            if (mesh.has_normals) n[k] = scene.normals[tri->v[k]];
        }
        row = block.push_triangle_hit(i, rays.dir[i], hits.u[i], hits.v[i], p,
                                      mesh.has_normals ? n : nullptr, bsdf, paths.beta[i]);
    } else if (prim.kind() == PrimKind::Quad) {
        row = block.push_quad_hit(i, rays.dir[i], hits.u[i], hits.v[i], scene.quads[index], bsdf,
                                  paths.beta[i]);
    } else {
        // surface_at's point of a sphere hit: ray.at(t).
        const Ray ray{rays.origin[i], rays.dir[i]};
        row = block.push_sphere_hit(i, ray.d, ray.at(hits.t[i]), scene.spheres[index], bsdf,
                                    paths.beta[i]);
    }
    if (texture) textured[textured_count++] = {row, m, prim.kind() == PrimKind::Sphere};
    sample_and_step(row);
    return true;
}

}  // namespace

// Chunk by chunk: the vertices' uniform numbers and the free flights through media in SIMD
// lanes; hits on Lambertian and rough metal surfaces and scatterings in media gathered into a
// block whose vertices, light samples towards quad and sphere lights and continuations run in
// SIMD lanes at the end of the chunk (light samples towards other lights in scalar code from
// the resolved vertices); escapes and boundary crossings directly; every other segment in
// scalar code. Shadow rays are appended in a fixed order (scalar ones, then the deferred ones,
// then the block's), so the queue, and the image, do not depend on the target.
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
    const Estimator& cfg = in.estimator;
    size_t s = first_shadow;
    SampleBlock samples;
    SurfaceBlock block;
    DeferredLightSample deferred[kShadeChunk];
    TexturedRow textured[kShadeChunk];
    const bool prefetch = prefetches_meshes(in.scene);
    ChunkTriangles records;
    MediumSegmentBlock segments;
    const bool flights = !in.scene.media.empty();  // else segment_flight() is 0
    if (!flights) std::fill(std::begin(samples.next_flight), std::end(samples.next_flight), 0.0f);
    // Hits on Lambertian and rough metal surfaces of constant albedo, and scattering in media,
    // skip resolve_segment: their vertex is resolved in lanes with the block. That takes a
    // strategy whose continuation there is the lane step (not the one-sample light/mixture
    // choice).
    const bool nee = cfg.strategy == Strategy::Nee || cfg.strategy == Strategy::Mis;
    const bool resolve_in_lanes =
        (cfg.strategy != Strategy::Light && cfg.strategy != Strategy::Mixture) || in.lights.empty();
    const bool segments_in_lanes = resolve_in_lanes && !in.scene.media.empty();
    for (size_t c = begin; c < end; c += kShadeChunk) {
        const size_t chunk_end = std::min(end, c + kShadeChunk);
        draw_vertex_samples(in.seed, sample, &paths.pixel[c], &paths.bounce[c], chunk_end - c,
                            flights, samples);
        if (segments_in_lanes) {
            for (size_t i = c; i < chunk_end; ++i) {
                const size_t k = i - c;
                const Vec3 d = rays.dir[i];
                for (int a = 0; a < 3; ++a) segments.dir[a][k] = d[a];
                segments.t[k] = hits.prim[i].valid() ? hits.t[i] : kInfinity;
                const MediumId m = paths.media[i].current();
                segments.medium[k] = m != kNone ? 1.0f : 0.0f;
                segments.density[k] = m != kNone ? in.scene.media[m].density : 0.0f;
                segments.flight[k] = paths.flight[i];
            }
            medium_segments(segments, chunk_end - c);
        }
        block.n = 0;
        size_t deferred_count = 0, textured_count = 0;
        if (prefetch) prefetch_chunk_vertices(in.scene, hits, c, chunk_end, records);
        for (size_t i = c; i < chunk_end; ++i) {
            keep[i] = 0;

            // ---- a vertex in lanes, a boundary crossed, an escape into the dark ----
            if (shade_quickly(in, i, i - c, samples, segments, hits, resolve_in_lanes, nee, rays,
                              paths, keep, block, deferred, deferred_count, textured,
                              textured_count))
                continue;

            // ---- the segment: medium, emission, boundary or surface ----
            MediumStack media = paths.media[i].unpack();
            float flight = paths.flight[i];
            const SegmentResult seg =
                resolve_segment(in.scene, in.lights, cfg, ray_at(rays, i), hit_at(hits, i), media,
                                flight, previous_vertex(paths, i));
            if (seg.event == SegmentEvent::Cross) {
                cross(i, media, flight, seg.next, paths, rays, keep);
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
            // Lane vertices go to the block for their light samples towards quad lights and their
            // continuations; the rest is taken here.
            const bool sampled = samples_lights(cfg, v, in.lights);
            const LightChoice light = sampled ? in.lights.select(u.light_select) : LightChoice{};
            const int32_t quad_index = sampled ? quad_light_sample_at(v, in.lights, light) : -1;
            const bool quad = quad_index >= 0;
            const bool surface_step = takes_lane_step(cfg, v, in.lights);
            if (quad || surface_step) {
                const size_t row = block.push(i, v, seg.wo, beta);
                if (quad)
                    block.set_light_sample(row, quad_index, light.probability, u.light_u,
                                           u.light_v);
                if (surface_step)
                    block.set_step(row, u.continuation, u.roulette, bounce + 1 >= cfg.rr_depth);
            }
            if (sampled && !quad) {
                const WeightedDirect d = next_event(in.scene, in.lights, cfg, v, seg.wo, u, light);
                if (d.weight > 0.0f)
                    append_shadow(d.sample.shadow, beta * (d.sample.value * d.weight), i, shadows,
                                  s);
            }
            if (surface_step) continue;
            const PathStep step = continue_path(in.scene, in.lights, cfg, v, seg.wo, bounce, beta,
                                                media, u.continuation, u.roulette);
            if (!step.alive) continue;
            paths.media[i] = PackedMedia::pack(media);
            advance(i, step.weight, step.prev, step.next, samples.next_flight[i - c], paths, rays,
                    keep);
        }

        resolve_surface_hits(block);
        for (size_t j = 0; j < textured_count; ++j) textured_albedo(in.scene, textured[j], block);
        for (size_t j = 0; j < deferred_count; ++j) {
            const DeferredLightSample& l = deferred[j];
            const size_t k = l.row;
            Vertex v;
            v.p = block_row(block.p, k);
            v.ng = block_row(block.ng, k);
            v.bsdf.kind = block.metal[k] != 0.0f   ? MaterialKind::Metal
                          : block.phase[k] != 0.0f ? MaterialKind::Isotropic
                                                   : MaterialKind::Lambertian;
            v.bsdf.alpha = block.alpha[k];
            // A sphere light seen from outside: back to the block, in lanes.
            if (const int32_t sphere = sphere_light_sample_at(v, in.lights, l.light); sphere >= 0) {
                block.set_sphere_light_sample(k, sphere, l.light.probability, l.u1, l.u2);
                continue;
            }
            v.frame = Frame::from_normal(block_row(block.ns, k));
            v.bsdf.albedo = block_row(block.albedo, k);
            VertexSamples u{};
            u.light_u = l.u1;
            u.light_v = l.u2;
            const WeightedDirect d =
                next_event(in.scene, in.lights, cfg, v, block_row(block.wo, k), u, l.light);
            if (d.weight > 0.0f)
                append_shadow(d.sample.shadow,
                              block_row(block.beta, k) * (d.sample.value * d.weight),
                              block.entry[k], shadows, s);
        }
        surface_vertices(block, in.lights, cfg.strategy == Strategy::Mis, cfg.heuristic);
        const bool counts_fully = in.lights.empty();  // the block's vertices sample lights if any
        for (size_t k = 0; k < block.n; ++k) {
            if (block.shadow[k] != 0.0f)
                append_shadow(Ray{block_row(block.shadow_origin, k), block_row(block.shadow_dir, k),
                                  0.0f, block.tmax[k]},
                              block_row(block.contribution, k), block.entry[k], shadows, s);
            if (block.alive[k] != 0.0f)
                advance(block.entry[k], block_row(block.weight, k),
                        {block_row(block.p, k), block.pdf[k], counts_fully},
                        Ray{block_row(block.origin, k), block_row(block.wi, k)},
                        samples.next_flight[block.entry[k] - c], paths, rays, keep);
        }
    }
    return s - first_shadow;
}

}  // namespace wavetrace
