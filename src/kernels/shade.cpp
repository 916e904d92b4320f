// The shade kernel, chunk by chunk: one pass classifies each entry's segment into a route,
// each route is one function over its entries, and the lane vertices are resolved, stepped
// and written back at the end of the chunk (see kernels.h for what shade does).
#include <algorithm>

#include "blocks/lane_kernels.h"
#include "kernels/kernels.h"
#include "shading/lane_routes.h"
#include "shading/path_vertex.h"
#include "util/check.h"

namespace wavetrace {
namespace {

// The routes an entry takes through shade.
enum class ShadeRoute : uint8_t {
    End,           // the path ends: a black background, or a vertex past the last bounce
    Cross,         // a medium boundary: straight on past it
    MediumVertex,  // scatters in a medium on the way to its hit: a lane vertex
    SurfaceHit,    // a hit on a Lambertian or rough metal surface: a lane vertex, from the hit
    Escape,        // leaves the scene under an environment map: its radiance found in lanes
    Resolve,       // anything else: resolve_segment, in scalar code
};
constexpr size_t kRoutes = 6;

// A chunk's entries per route, as rows of the chunk (entry = chunk begin + row), in order.
class ChunkRoutes {
  public:
    void clear() { std::fill(std::begin(count_), std::end(count_), size_t(0)); }
    void add(ShadeRoute r, size_t row) {
        rows_[size_t(r)][count_[size_t(r)]++] = static_cast<uint8_t>(row);
    }
    std::span<const uint8_t> operator[](ShadeRoute r) const {
        return {rows_[size_t(r)], count_[size_t(r)]};
    }

  private:
    static_assert(kShadeChunk <= 256, "rows are bytes");
    uint8_t rows_[kRoutes][kShadeChunk];
    size_t count_[kRoutes] = {};
};

// What a SurfaceHit row's vertex needs of its material: the BSDF surface_vertex gives it, with
// albedo 0 where the albedo is a texture other than a Solid one (an image, a noise, a checker),
// which is looked up once the row's hit is resolved.
struct LaneSurface {
    BsdfParams bsdf;
    MaterialId material = kNone;
    bool textured = false;
};

// The SurfaceHit material of m: one the lane formulas take (is_lane_bsdf) whose albedo may be a
// texture but nothing else varies over the surface. False for every other material (thin
// sheets, plastics, emitters, boundaries, none).
bool lane_material(const Scene& scene, MaterialId m, LaneSurface* out) {
    if (m == kNone) return false;
    const Material& mat = scene.materials[m];
    // One-sided materials go the scalar route, where the hit's side is known before the BSDF,
    // and so do normal and bump maps, which need the hit's tangents.
    if (!(mat.kind == MaterialKind::Lambertian || mat.kind == MaterialKind::Mirror ||
          mat.kind == MaterialKind::Metal || mat.kind == MaterialKind::Conductor ||
          mat.kind == MaterialKind::Dielectric || mat.kind == MaterialKind::MetallicRoughness) ||
        (mat.albedo == kNone && mat.kind != MaterialKind::Dielectric) || mat.one_sided ||
        mat.has_normal_maps() || mat.alpha_u_texture != kNone || mat.alpha_v_texture != kNone ||
        mat.metallic_roughness != kNone || mat.transmission_map != kNone ||
        mat.clearcoat_map != kNone || mat.clearcoat_roughness_map != kNone || mat.emission != kNone)
        return false;
    // A dielectric has no albedo.
    const Texture* albedo = mat.albedo != kNone ? &scene.textures[mat.albedo] : nullptr;
    out->material = m;
    out->textured = albedo && albedo->kind != TextureKind::Solid;
    out->bsdf = material_bsdf(mat, albedo && !out->textured ? albedo->color : Color(0.0f));
    return is_lane_bsdf(out->bsdf);
}

// A chunk's mesh hits read a triangle record and then its vertices' positions and normals, from
// arrays that outgrow the L2 on a large mesh (the dragon's: 3 MiB). Read entry by entry, among
// each entry's branchy shading, those loads wait one after the other. So where the mesh data
// outgrows the L1, a chunk first reads its triangle records in a tight loop of loads that do
// not depend on one another, so that the core has many in flight at once, then asks for all
// their vertices; the entries find them arrived (docs/benchmarks.md has the measurements).
// Below that size the data stays in the L1, and the loop would cost more than it saves.
constexpr size_t kPrefetchMeshBytes = 64 * 1024;

bool prefetches_meshes(const Scene& scene) {
    return scene.triangles.size() * sizeof(Triangle) +
               scene.positions.size() * (sizeof(Point3) + sizeof(Normal3)) >
           kPrefetchMeshBytes;
}

// The triangle records of a chunk's mesh hits (`shade` owns them for all its chunks).
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

// What shade writes: the paths that go on (their state, their next ray, keep) and the two
// queues it appends to.
struct ShadeOutputs {
    PathQueue& paths;
    RayQueue& rays;
    std::span<uint8_t> keep;
    LightSampleQueue& light_samples;
    size_t light_sample_end;  // next free entry
    EmissionQueue& emissions;
    size_t emission_end;
};

// One chunk's working state.
struct Chunk {
    size_t begin = 0, end = 0;
    SampleBlock samples;          // the vertices' uniform numbers
    EscapeBlock escapes;          // the rays of route Escape
    MediumSegmentBlock segments;  // where the paths scatter in media, drawn in lanes
    ChunkRoutes routes;
    LaneSurface surface[kShadeChunk];  // per SurfaceHit entry, by row of the chunk
    VertexBlock block;                 // the lane vertices
    MaterialId textured[kShadeChunk];  // per row of the block: its material where the
                                       // albedo is a texture, else kNone
    uint32_t sphere[kShadeChunk];      // per textured row on a sphere: which one
};

// Whether the lanes resolve the chunk's medium segments and lane vertices: a strategy whose
// continuation there is the lane step (not the one-sample light/mixture choice), in grey
// homogeneous media (chromatic ones weight their flights, heterogeneous ones walk a grid:
// grid_flight).
bool resolves_in_lanes(const WaveInputs& in) {
    const Strategy s = in.estimator.strategy;
    for (const Medium& m : in.scene.media)
        if (m.chromatic() || m.heterogeneous()) return false;
    return (s != Strategy::Light && s != Strategy::Mixture) || in.lights.empty();
}

// Whether the strategy takes a light sample at each lane vertex.
bool lane_vertices_sample_lights(const WaveInputs& in) {
    const Strategy s = in.estimator.strategy;
    return (s == Strategy::Nee || s == Strategy::Mis) && !in.lights.empty();
}

// The route of each of the chunk's entries.
void classify(const WaveInputs& in, const HitQueue& hits, const PathQueue& paths, Chunk& c) {
    const Scene& scene = in.scene;
    const bool lanes = resolves_in_lanes(in);
    c.routes.clear();
    for (size_t i = c.begin; i < c.end; ++i) {
        const size_t row = i - c.begin;
        const int depth = paths.depth[i];
        auto route = [&]() {
            if (!scene.media.empty()) {
                if (!lanes) return ShadeRoute::Resolve;
                if (c.segments.scatters[row] != 0.0f)
                    return may_scatter(in.estimator, depth) ? ShadeRoute::MediumVertex
                                                             : ShadeRoute::End;
            }
            const PrimRef prim = hits.prim[i];
            if (!prim.valid())
                return in.lights.has_environment()    ? ShadeRoute::Escape
                       : scene.background.is_black() ? ShadeRoute::End
                                                     : ShadeRoute::Resolve;
            const MaterialId m = scene.prim_material(prim);
            if (scene.is_boundary(m)) return ShadeRoute::Cross;
            // Textured meshes stay scalar: their texture coordinates come from the mesh's
            // vertices.
            if (!lanes || !lane_material(scene, m, &c.surface[row]) ||
                (c.surface[row].textured && prim.kind() == PrimKind::Triangle))
                return ShadeRoute::Resolve;
            // A vertex past the last bounce: resolve_segment would find no emission there.
            return may_scatter(in.estimator, depth) ? ShadeRoute::SurfaceHit : ShadeRoute::End;
        };
        c.routes.add(route(), row);
    }
}

// Entry i goes on from its scattering vertex to one of depth `depth`: throughput, the record for
// weighting emission the next segment finds, the next ray and the optical depth it may travel
// in media.
void advance(size_t i,
             int depth,
             float eta_scale,
             Color weight,
             const PreviousVertex& prev,
             const Ray& next,
             float flight,
             ShadeOutputs& out) {
    out.paths.beta[i] = out.paths.beta[i] * weight;
    set_previous_vertex(out.paths, i, prev);
    out.paths.bounce[i] = static_cast<uint16_t>(out.paths.bounce[i] + 1);
    out.paths.depth[i] = static_cast<uint16_t>(depth);
    out.paths.eta_scale[i] = eta_scale;
    out.paths.flight[i] = flight;
    out.paths.crossings[i] = 0;
    set_ray(out.rays, i, next);
    out.keep[i] = 1;
}

// Entry i goes straight on past a medium boundary: `media` and `flight` after it, the next ray;
// or ends, after too many crossings in one segment.
void cross(size_t i, const MediumStack& media, float flight, const Ray& next, ShadeOutputs& out) {
    if (++out.paths.crossings[i] >= kMaxBoundaryCrossings) return;
    out.paths.media[i] = PackedMedia::pack(media);
    out.paths.flight[i] = flight;
    set_ray(out.rays, i, next);
    out.keep[i] = 1;
}

void append_light_sample(size_t path,
                         Point3 p,
                         Normal3 ng,
                         Normal3 ns,
                         float frame_angle,
                         Normal3 unbent,
                         float bump_alpha2,
                         Vec3 wo,
                         const BsdfParams& bsdf,
                         Vec2 uv,
                         MaterialId material,
                         Color beta,
                         const VertexSamples& u,
                         PackedMedia media,
                         MediumId interior,
                         ShadeOutputs& out) {
    WT_DCHECK_LT(out.light_sample_end, out.light_samples.capacity);
    store_queued_vertex(out.light_samples, out.light_sample_end++,
                        {static_cast<uint32_t>(path),
                         p,
                         ng,
                         ns,
                         frame_angle,
                         unbent,
                         bump_alpha2,
                         wo,
                         bsdf.albedo,
                         bsdf.alpha,
                         bsdf.alpha_v,
                         bsdf.metallic,
                         bsdf.coat_normal,
                         uv,
                         bsdf.kind,
                         material,
                         beta,
                         u.light_select,
                         u.light_u,
                         u.light_v,
                         media,
                         interior});
}

// Route Cross: the ray goes on past the boundary, with the optical depth left after the segment.
void cross_boundaries(const WaveInputs& in, const HitQueue& hits, Chunk& c, ShadeOutputs& out) {
    for (const uint8_t row : c.routes[ShadeRoute::Cross]) {
        const size_t i = c.begin + row;
        const Ray ray = ray_at(out.rays, i);
        MediumStack media = out.paths.media[i].unpack();
        const Ray next = cross_boundary(in.scene, surface_at(in.scene, ray, hit_at(hits, i)),
                                        ray.d / length(ray.d), media);
        const float flight = in.scene.media.empty() ? out.paths.flight[i] : c.segments.flight[row];
        cross(i, media, flight, next, out);
    }
}

// The continuation samples of a lane row of wave entry i.
void set_lane_step(const WaveInputs& in,
                   const Chunk& c,
                   const PathQueue& paths,
                   size_t row,
                   size_t i,
                   VertexBlock& block) {
    const int depth = paths.depth[i];
    const VertexSamples u = c.samples.at(i - c.begin);
    block.set_step(row, u.continuation, u.roulette, depth + 1 >= in.estimator.rr_depth,
                   paths.eta_scale[i]);
}

// Route MediumVertex: the point where the path scatters, a row of the block.
void push_medium_vertices(const WaveInputs& in, Chunk& c, const ShadeOutputs& out) {
    for (const uint8_t row : c.routes[ShadeRoute::MediumVertex]) {
        const size_t i = c.begin + row;
        const Ray ray{out.rays.origin[i], out.rays.dir[i]};
        const float dir_length = c.segments.dir_length[row];
        const Vertex v = medium_vertex(in.scene, out.paths.media[i].current(),
                                       scattering_point(ray, c.segments.dist[row], dir_length));
        const size_t k = c.block.push(i, v, -(ray.d / dir_length), out.paths.beta[i]);
        set_lane_step(in, c, out.paths, k, i, c.block);
    }
}

// Route SurfaceHit: the hit, a row of the block, resolved there in lanes. The rows go in grouped
// by lobe, in the order of the route within each, so that the block's vectors (and the light
// samples queued from them) mostly hold one lobe: a vector that mixes lobes runs each lobe's
// formulas over all its lanes. The delta lobes' rows come last (LaneLobe::Specular): they take
// no light sample. Returns the rows before them.
size_t push_surface_hits(const WaveInputs& in,
                         const HitQueue& hits,
                         Chunk& c,
                         const ShadeOutputs& out) {
    const Scene& scene = in.scene;
    const std::span<const uint8_t> route = c.routes[ShadeRoute::SurfaceHit];
    constexpr size_t kLobes = size_t(LaneLobe::Specular) + 1;
    size_t start[kLobes + 1] = {};
    for (const uint8_t row : route) ++start[size_t(lane_lobe(c.surface[row].bsdf)) + 1];
    for (size_t l = 0; l < kLobes; ++l) start[l + 1] += start[l];
    const size_t sampling_rows = c.block.n + start[size_t(LaneLobe::Specular)];
    uint8_t grouped[kShadeChunk];
    for (const uint8_t row : route) grouped[start[size_t(lane_lobe(c.surface[row].bsdf))]++] = row;
    for (const uint8_t row : std::span<const uint8_t>(grouped, route.size())) {
        const size_t i = c.begin + row;
        const PrimRef prim = hits.prim[i];
        const BsdfParams& bsdf = c.surface[row].bsdf;
        const MaterialId material = c.surface[row].material;
        const Color beta = out.paths.beta[i];
        size_t k;
        switch (prim.kind()) {
            case PrimKind::Triangle: {
                const Triangle& tri = scene.triangles[prim.index()];
                const Mesh& mesh = scene.meshes[tri.mesh];
                Point3 p[3];
                Normal3 n[3];
                for (int j = 0; j < 3; ++j) {
                    p[j] = scene.positions[tri.v[j]];
                    if (mesh.has_normals) n[j] = scene.normals[tri.v[j]];
                }
                k = c.block.push_triangle_hit(i, out.rays.dir[i], hits.u[i], hits.v[i], p,
                                              mesh.has_normals ? n : nullptr, material, bsdf, beta);
                c.block.interior[k] = mesh.interior;
                break;
            }
            case PrimKind::Quad:
                k = c.block.push_quad_hit(i, out.rays.dir[i], hits.u[i], hits.v[i],
                                          scene.quads[prim.index()], material, bsdf, beta);
                c.block.interior[k] = scene.quads[prim.index()].interior;
                break;
            case PrimKind::Sphere:
            default: {
                // surface_at's point of a sphere hit: ray.at(t).
                const Ray ray{out.rays.origin[i], out.rays.dir[i]};
                k = c.block.push_sphere_hit(i, ray.d, ray.at(hits.t[i]),
                                            scene.spheres[prim.index()], material, bsdf, beta);
                c.block.interior[k] = scene.spheres[prim.index()].interior;
                break;
            }
        }
        c.textured[k] = c.surface[row].textured ? c.surface[row].material : kNone;
        c.sphere[k] = prim.kind() == PrimKind::Sphere ? prim.index() : kNone;
        set_lane_step(in, c, out.paths, k, i, c.block);
    }
    return sampling_rows;
}

// Route Resolve, in scalar code: resolve_segment (media, emission found, boundaries, the
// vertex), then at a scattering vertex its light sample queued and its continuation: a lane
// step as a row of the block, or continue_path's.
void resolve_in_scalar(const WaveInputs& in, const HitQueue& hits, Chunk& c, ShadeOutputs& out) {
    const Estimator& cfg = in.estimator;
    for (const uint8_t row : c.routes[ShadeRoute::Resolve]) {
        const size_t i = c.begin + row;
        MediumStack media = out.paths.media[i].unpack();
        float flight = out.paths.flight[i];
        const PreviousVertex prev = previous_vertex(out.paths, i);
        const SegmentResult seg = resolve_segment(in.scene, in.lights, cfg, ray_at(out.rays, i),
                                                  hit_at(hits, i), media, flight, prev);
        out.paths.beta[i] = out.paths.beta[i] * seg.weight;
        if (seg.event == SegmentEvent::Cross) {
            cross(i, media, flight, seg.next, out);
            continue;
        }
        // Emission found, for mis_combine to weight; at an emitter that also reflects, the
        // path scatters on from it.
        const Color beta = out.paths.beta[i];
        if (max_component(seg.emission) > 0.0f) {
            WT_DCHECK_LT(out.emission_end, out.emissions.capacity);
            out.emissions.store(out.emission_end++,
                                {static_cast<uint32_t>(i), beta * seg.emission, prev.pdf_bsdf,
                                 seg.emission_pdf_light,
                                 uint8_t((prev.counts_fully ? kCountsFully : 0) |
                                         (seg.at_infinity ? kAtInfinity : 0))});
        }
        if (seg.event != SegmentEvent::Scatter) continue;

        const int bounce = out.paths.bounce[i], depth = out.paths.depth[i];
        const Vertex& v = seg.vertex;
        if (!may_continue(cfg, v, depth)) continue;
        const VertexSamples u = c.samples.at(row);
        if (samples_lights(cfg, v, in.lights))
            append_light_sample(i, v.p, v.ng, v.frame.n, v.frame_angle, v.unbent, v.bump_alpha2,
                                seg.wo, v.bsdf, v.uv, v.material, beta, u, PackedMedia::pack(media),
                                v.interior, out);
        if (takes_lane_step(cfg, v, in.lights)) {
            const size_t k = c.block.push(i, v, seg.wo, beta);
            c.block.set_step(k, u.continuation, u.roulette, depth + 1 >= cfg.rr_depth,
                             out.paths.eta_scale[i]);
            continue;
        }
        const PathStep step = continue_path(in.scene, in.lights, cfg, v, seg.wo, prev, depth, beta,
                                            out.paths.eta_scale[i], media, u.continuation,
                                            u.roulette);
        const int next_depth = wavetrace::next_depth(bounce, depth, step);
        if (!step.alive || !ray_may_bring_light(cfg, in.lights, next_depth)) continue;
        out.paths.media[i] = PackedMedia::pack(media);
        advance(i, next_depth, step.eta_scale, step.weight, step.prev, step.next,
                c.samples.next_flight[row], out);
    }
}

// Route Escape, in lanes: what each ray finds on the environment map, queued as emission for
// mis_combine to weight (resolve_segment's miss, bit for bit). The paths end.
void escape_in_lanes(const WaveInputs& in, Chunk& c, ShadeOutputs& out) {
    const std::span<const uint8_t> rows = c.routes[ShadeRoute::Escape];
    if (rows.empty()) return;
    EscapeBlock& b = c.escapes;
    b.n = rows.size();
    const bool mis = in.estimator.strategy == Strategy::Mis;
    for (size_t k = 0; k < b.n; ++k) {
        const size_t i = c.begin + rows[k];
        for (int a = 0; a < 3; ++a) b.dir[a][k] = out.rays.dir[i][a];
        // Its MIS weight needs the density only where the previous vertex sampled lights.
        b.select_prob[k] =
            mis && !out.paths.counts_fully[i]
                ? in.lights.background_selection_probability(
                      out.paths.prev_p[i], out.paths.prev_n[i], out.paths.prev_total[i])
                : 0.0f;
    }
    escape_rays(b, in.lights, mis);
    for (size_t k = 0; k < b.n; ++k) {
        const size_t i = c.begin + rows[k];
        const Color radiance = block_row(b.radiance, k);
        if (!(max_component(radiance) > 0.0f)) continue;
        const PreviousVertex prev = previous_vertex(out.paths, i);
        WT_DCHECK_LT(out.emission_end, out.emissions.capacity);
        out.emissions.store(out.emission_end++,
                            {static_cast<uint32_t>(i), out.paths.beta[i] * radiance, prev.pdf_bsdf,
                             mis && !prev.counts_fully ? b.pdf_light[k] : 0.0f,
                             uint8_t((prev.counts_fully ? kCountsFully : 0) | kAtInfinity)});
    }
}

// The textured albedo of SurfaceHit rows [0, rows) once their hits are resolved: surface_at's
// texture coordinates (the sphere's from its outward normal, the quad's the hit's (u, v) or
// (u, 1 - v)).
void look_up_textures(const Scene& scene, size_t rows, Chunk& c) {
    VertexBlock& b = c.block;
    for (size_t k = 0; k < rows; ++k) {
        if (c.textured[k] == kNone) continue;
        const Point3 p = block_row(b.p, k);
        const Vec2 uv = b.shape[k] == int32_t(HitShape::Sphere)
                            ? sphere_uv(scene, scene.spheres[c.sphere[k]], block_row(b.ng, k))
                            : Vec2{b.hit_u[k], b.flip_v[k] ? 1.0f - b.hit_v[k] : b.hit_v[k]};
        const Material& mat = scene.materials[c.textured[k]];
        const BsdfParams bsdf = material_bsdf(mat, eval_texture(scene, mat.albedo, uv, p));
        for (int a = 0; a < 3; ++a) b.albedo[a][k] = bsdf.albedo[a];
        b.alpha[k] = bsdf.alpha;
    }
}

// The light samples of the block's rows [first, last), once their vertices are resolved: the
// block's rows copied to the queue's as they are.
void queue_lane_light_samples(size_t first, size_t last, const Chunk& c, ShadeOutputs& out) {
    const VertexBlock& b = c.block;
    LightSampleQueue& q = out.light_samples;
    const size_t at = out.light_sample_end, n = last - first;
    WT_DCHECK_LE(at + n, q.capacity);
    // Rows of a chunk at most: plain loops, which the compiler vectorizes in place, rather than
    // a call to memmove per row.
    auto row = [&](const float* from, float* __restrict to) {
        for (size_t k = 0; k < n; ++k) to[k] = from[first + k];
    };
    auto rows = [&](const float(*block)[kShadeChunk], std::vector<float>& x, std::vector<float>& y,
                    std::vector<float>& z) {
        row(block[0], x.data() + at);
        row(block[1], y.data() + at);
        row(block[2], z.data() + at);
    };
    rows(b.p, q.p_x, q.p_y, q.p_z);
    rows(b.ng, q.ng_x, q.ng_y, q.ng_z);
    rows(b.ns, q.ns_x, q.ns_y, q.ns_z);
    rows(b.wo, q.wo_x, q.wo_y, q.wo_z);
    rows(b.albedo, q.albedo_x, q.albedo_y, q.albedo_z);
    rows(b.beta, q.beta_x, q.beta_y, q.beta_z);
    row(b.alpha, q.alpha.data() + at);
    row(b.alpha, q.alpha_v.data() + at);  // lane BSDFs are isotropic
    row(b.glossy.metallic, q.metallic.data() + at);  // read for metallic-roughness rows only
    for (size_t k = first; k < last; ++k) {
        const size_t j = at + (k - first);
        q.path[j] = b.entry[k];
        q.media[j] = out.paths.media[b.entry[k]];  // before the step's crossing, if any
        q.interior[j] = b.interior[k];
        q.frame_angle[j] = 0.0f;  // lane BSDFs are isotropic
        q.unbent_x[j] = q.unbent_y[j] = q.unbent_z[j] = 0.0f;
        q.bump_alpha2[j] = 0.0f;  // lane vertices have no mapped normal's shadowing
        // nor a coat apart from the shading normal
        q.coat_n_x[j] = q.coat_n_y[j] = q.coat_n_z[j] = 0.0f;
        q.kind[j] = material_kind(LaneLobe(b.lobe[k]));
        q.material[j] = b.material[k];  // as append_light_sample queues it
        const VertexSamples u = c.samples.at(b.entry[k] - c.begin);
        q.u_select[j] = u.light_select;
        q.u1[j] = u.light_u;
        q.u2[j] = u.light_v;
    }
    out.light_sample_end += n;
}

// The block's continuations, back to their entries; a refraction crosses into or out of the
// surface's interior, as continue_path does.
void write_back_steps(const WaveInputs& in, const Chunk& c, ShadeOutputs& out) {
    const VertexBlock& b = c.block;
    // Lane vertices sample lights if any, but for delta lobes, after which emission counts fully.
    const bool no_lights = in.lights.empty();
    for (size_t k = 0; k < b.n; ++k) {
        if (b.alive[k] == 0) continue;
        const size_t i = b.entry[k];
        if (!ray_may_bring_light(in.estimator, in.lights, out.paths.depth[i] + 1)) continue;
        const Vec3 wi = block_row(b.wi, k);
        if (b.transmitted[k] != 0) {
            MediumStack media = out.paths.media[i].unpack();
            media.cross(b.interior[k], dot(wi, block_row(b.ng, k)) < 0.0f,
                        in.scene.medium_boundaries);
            out.paths.media[i] = PackedMedia::pack(media);
        }
        advance(i, out.paths.depth[i] + 1, b.next_eta_scale[k], block_row(b.weight, k),
                {block_row(b.p, k), b.pdf[k], no_lights || b.delta[k] != 0, block_row(b.ng, k)},
                Ray{block_row(b.origin, k), wi}, c.samples.next_flight[i - c.begin], out);
    }
}

// The chunk's medium segments in lanes: where each path scatters on the way to its hit.
void trace_media(const WaveInputs& in,
                 const HitQueue& hits,
                 const PathQueue& paths,
                 const RayQueue& rays,
                 Chunk& c) {
    MediumSegmentBlock& s = c.segments;
    for (size_t i = c.begin; i < c.end; ++i) {
        const size_t k = i - c.begin;
        for (int a = 0; a < 3; ++a) s.dir[a][k] = rays.dir[i][a];
        const MediumId m = paths.media[i].current();
        s.t[k] = hits.prim[i].valid() ? hits.t[i] : kInfinity;
        s.medium[k] = m != kNone ? 1.0f : 0.0f;
        s.density[k] = m != kNone ? in.scene.media[m].sigma_t.x : 0.0f;  // grey (resolves_in_lanes)
        s.flight[k] = paths.flight[i];
    }
    medium_segments(s, c.end - c.begin);
}

}  // namespace

ShadeCounts shade(const WaveInputs& in,
                  const HitQueue& hits,
                  size_t begin,
                  size_t end,
                  PathQueue& paths,
                  RayQueue& rays,
                  std::span<uint8_t> keep,
                  LightSampleQueue& light_samples,
                  size_t first_light_sample,
                  EmissionQueue& emissions,
                  size_t first_emission) {
    ShadeOutputs out{paths,     rays,          keep, light_samples, first_light_sample,
                     emissions, first_emission};
    Chunk c;
    ChunkTriangles records;
    const bool prefetch = prefetches_meshes(in.scene);
    const bool flights = !in.scene.media.empty();  // else segment_flight() is 0
    const bool media_in_lanes = flights && resolves_in_lanes(in);
    const bool lane_light_samples = lane_vertices_sample_lights(in);
    if (!flights)
        std::fill(std::begin(c.samples.next_flight), std::end(c.samples.next_flight), 0.0f);
    for (c.begin = begin; c.begin < end; c.begin += kShadeChunk) {
        c.end = std::min(end, c.begin + kShadeChunk);
        std::fill(keep.begin() + c.begin, keep.begin() + c.end, uint8_t(0));
        draw_vertex_samples(in.sampler, &paths.sample[c.begin], &paths.pixel[c.begin],
                            &paths.bounce[c.begin], c.end - c.begin,
                            reads_one_sample_pairs(in.estimator.strategy), flights, c.samples);
        if (media_in_lanes) trace_media(in, hits, paths, rays, c);
        if (prefetch) prefetch_chunk_vertices(in.scene, hits, c.begin, c.end, records);
        classify(in, hits, paths, c);

        c.block.n = 0;
        c.block.geometric_side_test = in.scene.geometric_side_test;
        cross_boundaries(in, hits, c, out);
        const size_t sampling_rows = push_surface_hits(in, hits, c, out);
        const size_t surface_rows = c.block.n;
        push_medium_vertices(in, c, out);
        const size_t lane_rows = c.block.n;
        resolve_in_scalar(in, hits, c, out);  // queues its own light samples
        escape_in_lanes(in, c, out);

        resolve_surface_hits(c.block);
        look_up_textures(in.scene, surface_rows, c);
        if (lane_light_samples) {
            queue_lane_light_samples(0, sampling_rows, c, out);
            queue_lane_light_samples(surface_rows, lane_rows, c, out);
        }
        step_vertices(c.block);
        write_back_steps(in, c, out);
    }
    return {out.light_sample_end - first_light_sample, out.emission_end - first_emission};
}

}  // namespace wavetrace
