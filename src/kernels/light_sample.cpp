// The light_sample kernel: per chunk of its queue, each vertex's light chosen; the samples
// towards quad and triangle lights, sphere lights seen from outside, point and directional
// lights and the environment map taken in SIMD lanes at lane vertices, every other in scalar code
// (sample_direct; a direction on the environment map in lanes there too); the chunk's shadow rays
// appended, the lanes' first.
#include <algorithm>

#include "blocks/lane_kernels.h"
#include "kernels/kernels.h"
#include "scene/material_lookup.h"
#include "shading/lane_routes.h"
#include "shading/path_vertex.h"
#include "util/check.h"

namespace wavetrace {
namespace {

// The BSDF of queue entry i, as next_event sees it.
BsdfParams queued_bsdf(const Scene& scene, const LightSampleQueue& q, size_t i) {
    BsdfParams b;
    const MaterialId material = q.material[i];
    if (material == kNone) {
        b.kind = q.kind[i];
        b.albedo = WAVETRACE_XYZ_AT(q, albedo, i);
        b.alpha = q.alpha[i];
        return b;
    }
    const Material& m = scene.materials[material];
    b = material_bsdf(m, WAVETRACE_XYZ_AT(q, albedo, i));
    // As the vertex's textures made them.
    b.alpha = q.alpha[i];
    b.alpha_v = q.alpha_v[i];
    const TexturePoint at{{q.uv_u[i], q.uv_v[i]}, WAVETRACE_XYZ_AT(q, p, i)};
    if (b.kind == MaterialKind::MetallicRoughness) {
        b.metallic = q.metallic[i];
        b.coat_normal = WAVETRACE_XYZ_AT(q, coat_n, i);
        transmission_and_coat_at(scene, m, at, &b);
    }
    if (b.kind == MaterialKind::Principled) principled_at(scene, m, at.uv, at.p, &b);
    return b;
}

// The vertex of queue entry i, as next_event sees it, but for its frame (which only
// sample_direct needs: rotated_frame of the entry's ns and frame_angle, as shade's vertex had).
Vertex queued_vertex(const Scene& scene, const LightSampleQueue& q, size_t i) {
    Vertex v;
    v.p = WAVETRACE_XYZ_AT(q, p, i);
    v.ng = WAVETRACE_XYZ_AT(q, ng, i);
    v.geometric_side_test = scene.geometric_side_test;
    v.unbent = WAVETRACE_XYZ_AT(q, unbent, i);
    v.bump_alpha2 = q.bump_alpha2[i];
    v.material = q.material[i];
    v.bsdf = queued_bsdf(scene, q, i);
    return v;
}

// The lanes' shadow rays [from, to), appended in row order for the rows of b sampled in lanes,
// hold their paths' media at the vertex; a ray that leaves through the surface (from inside a
// rough dielectric) crosses into or out of its interior first, as next_event's (shadow_media).
void cross_in_lane_shadows(const Scene& scene,
                           const LightSampleQueue& q,
                           const LightSampleBlock& b,
                           ShadowQueue& shadows,
                           size_t from,
                           size_t to) {
    size_t j = from;
    for (size_t row = 0; row < b.n && j < to; ++row) {
        const size_t i = b.first + row;
        const bool in_lanes = b.planar[row] >= 0 || b.sphere[row] >= 0 || b.delta[row] >= 0 ||
                              b.environment[row] != 0;
        if (!in_lanes || shadows.path[j] != q.path[i]) continue;  // no contribution
        shadows.media[j] = PackedMedia::pack(
            shadow_media(scene.medium_boundaries, shadows.media[j].unpack(), q.interior[i],
                         WAVETRACE_XYZ_AT(q, ng, i), WAVETRACE_XYZ_AT(q, wo, i),
                         Vec3{shadows.dir_x[j], shadows.dir_y[j], shadows.dir_z[j]}));
        ++j;
    }
}

}  // namespace

size_t light_sample(const WaveInputs& in,
                    const LightSampleQueue& queue,
                    size_t begin,
                    size_t end,
                    ShadowQueue& shadows,
                    size_t first_shadow,
                    PathQueue& paths) {
    WT_DCHECK_LE(end, queue.capacity);
    LightSampleBlock block;
    block.queue = &queue;
    block.geometric_side_test = in.scene.geometric_side_test;
    DirectSample scalar[kShadeChunk];
    // The BSDF of a row of another kind, as far as is_lane_vertex reads it: its kind and alphas,
    // the rest as constructed (set once: a BsdfParams is large).
    BsdfParams plain;
    EnvironmentPointBlock points;
    uint8_t point_row[kShadeChunk];  // the chunk row of each of points' rows
    size_t s = first_shadow;
    for (size_t c = begin; c < end; c += kShadeChunk) {
        const size_t chunk_end = std::min(end, c + kShadeChunk);
        block.first = c;
        block.n = chunk_end - c;
        static_assert(kShadeChunk <= LightSelection::kRowsAtOnce);
        LightChoice choices[kShadeChunk];
        {
            const float* const p[3] = {&queue.p_x[c], &queue.p_y[c], &queue.p_z[c]};
            const float* const ng[3] = {&queue.ng_x[c], &queue.ng_y[c], &queue.ng_z[c]};
            in.lights.selection().select_rows(&queue.u_select[c], p, ng, block.n, choices);
        }
        // Each vertex's light; the SIMD kernel takes the rows whose light is a quad, a triangle,
        // a sphere seen from outside, a point or directional light or the environment map, as
        // next_event chooses, scalar code the others.
        for (size_t i = c; i < chunk_end; ++i) {
            const size_t row = i - c;
            const Normal3 ng = WAVETRACE_XYZ_AT(queue, ng, i);
            const Point3 p = WAVETRACE_XYZ_AT(queue, p, i);
            const LightChoice& light = choices[row];
            if (const uint32_t path = queue.path[i]; paths.prev_p[path] == p)
                paths.prev_total[path] = light.total;
            block.lobe[row] = int32_t(lane_lobe(queue.kind[i]));
            block.select_prob[row] = light.probability;
            block.sphere[row] = -1;
            block.delta[row] = -1;
            block.environment[row] = 0;
            // A conductor's, a dielectric's or a metallic-roughness surface's BSDF comes from
            // its material.
            const bool glossy_row = queue.kind[i] == MaterialKind::Conductor ||
                                    queue.kind[i] == MaterialKind::Dielectric ||
                                    queue.kind[i] == MaterialKind::MetallicRoughness;
            bool lane;
            if (glossy_row) {
                const BsdfParams bsdf = queued_bsdf(in.scene, queue, i);
                lane = is_lane_vertex(ng, bsdf, queue.bump_alpha2[i]);
                if (lane) block.glossy.set(row, bsdf);
            } else {
                plain.kind = queue.kind[i];
                plain.alpha = queue.alpha[i];
                plain.alpha_v = queue.alpha_v[i];
                lane = is_lane_vertex(ng, plain, queue.bump_alpha2[i]);
            }
            block.planar[row] = planar_light_sample_at(lane, in.lights, light);
            if (block.planar[row] >= 0) continue;
            block.sphere[row] =
                sphere_light_sample_at(WAVETRACE_XYZ_AT(queue, p, i), lane, in.lights, light);
            if (block.sphere[row] >= 0) continue;
            block.delta[row] = delta_light_sample_at(lane, in.lights, light);
            if (block.delta[row] >= 0) continue;
            if (environment_light_sample_at(lane, in.lights, light)) {
                block.environment[row] = 1;
                continue;
            }
            if (in.lights.is_environment(light)) {  // its direction in lanes, below
                const size_t k = points.n++;
                point_row[k] = static_cast<uint8_t>(row);
                points.u1[k] = queue.u1[i];
                points.u2[k] = queue.u2[i];
                points.select_prob[k] = light.probability;
                continue;
            }
            Vertex v = queued_vertex(in.scene, queue, i);
            v.frame = rotated_frame(WAVETRACE_XYZ_AT(queue, ns, i), queue.frame_angle[i]);
            scalar[row] = sample_direct(in.scene, in.lights, v, WAVETRACE_XYZ_AT(queue, wo, i),
                                        light, queue.u1[i], queue.u2[i]);
        }
        // Directions on the environment map for the other vertices, in lanes; their BSDFs in
        // scalar code, as sample_direct evaluates them.
        environment_light_points(points, in.lights);
        for (size_t k = 0; k < points.n; ++k) {
            const size_t i = c + point_row[k];
            Vertex v = queued_vertex(in.scene, queue, i);
            v.frame = rotated_frame(WAVETRACE_XYZ_AT(queue, ns, i), queue.frame_angle[i]);
            scalar[point_row[k]] = direct_sample_from(
                v, WAVETRACE_XYZ_AT(queue, wo, i),
                environment_light_sample(block_row(points.wi, k), block_row(points.radiance, k),
                                         points.pdf[k]));
        }
        points.n = 0;
        // The lanes' shadow rays first, then the scalar ones: a fixed order.
        const size_t lane_shadows = sample_lights_in_lanes(block, in.lights, shadows, s);
        if (in.shadows_walk)
            cross_in_lane_shadows(in.scene, queue, block, shadows, s, s + lane_shadows);
        s += lane_shadows;
        for (size_t i = c; i < chunk_end; ++i) {
            const size_t row = i - c;
            if (block.planar[row] >= 0 || block.sphere[row] >= 0 || block.delta[row] >= 0 ||
                block.environment[row] != 0 || !scalar[row].valid)
                continue;
            const DirectSample& d = scalar[row];
            WT_DCHECK_LT(s, shadows.capacity);
            const PackedMedia media = PackedMedia::pack(shadow_media(
                in.scene.medium_boundaries, queue.media[i].unpack(), queue.interior[i],
                WAVETRACE_XYZ_AT(queue, ng, i), WAVETRACE_XYZ_AT(queue, wo, i), d.shadow.d));
            store_shadow_ray(
                shadows, s++,
                {d.shadow.o, d.shadow.d, d.shadow.tmax, WAVETRACE_XYZ_AT(queue, beta, i) * d.value,
                 d.pdf_light, d.pdf_bsdf, queue.path[i], media});
        }
    }
    return s - first_shadow;
}

}  // namespace wavetrace
