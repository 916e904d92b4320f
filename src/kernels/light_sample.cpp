// The light_sample kernel: per chunk of its queue, each vertex's light chosen; the samples
// towards quad lights and towards sphere lights seen from outside taken in SIMD lanes, every
// other in scalar code (sample_direct); the shadow rays appended in queue order.
#include <algorithm>

#include "kernels/kernels.h"
#include "kernels/lane_kernels.h"
#include "shading/path_vertex.h"
#include "util/check.h"

namespace wavetrace {
namespace {

// The vertex of queue entry i, as next_event sees it, but for its frame (only sample_direct
// needs it).
Vertex queued_vertex(const LightSampleQueue& q, size_t i) {
    Vertex v;
    v.p = q.p[i];
    v.ng = q.ng[i];
    v.bsdf.kind = q.kind[i];
    v.bsdf.albedo = q.albedo[i];
    v.bsdf.alpha = q.alpha[i];
    return v;
}

void push_row(const LightSampleQueue& q,
              size_t i,
              int32_t quad,
              int32_t sphere,
              const LightChoice& light,
              LightSampleBlock& b) {
    const size_t k = b.n++;
    for (int a = 0; a < 3; ++a) {
        b.p[a][k] = q.p[i][a];
        b.ng[a][k] = q.ng[i][a];
        b.ns[a][k] = q.ns[i][a];
        b.wo[a][k] = q.wo[i][a];
        b.albedo[a][k] = q.albedo[i][a];
    }
    b.alpha[k] = q.alpha[i];
    b.lobe[k] = int32_t(lane_lobe(q.kind[i]));
    b.quad[k] = quad;
    b.sphere[k] = sphere;
    b.select_prob[k] = light.probability;
    b.u1[k] = q.u1[i];
    b.u2[k] = q.u2[i];
}

DirectSample lane_result(const LightSampleBlock& b, size_t k) {
    DirectSample d;
    if (b.valid[k] == 0) return d;
    d.value = block_row(b.value, k);
    d.pdf_light = b.pdf_light[k];
    d.pdf_bsdf = b.pdf_bsdf[k];
    d.shadow = Ray{block_row(b.origin, k), block_row(b.wi, k), 0.0f, b.tmax[k]};
    d.valid = true;
    return d;
}

}  // namespace

size_t light_sample(const WaveInputs& in,
                    const LightSampleQueue& queue,
                    size_t begin,
                    size_t end,
                    ShadowQueue& shadows,
                    size_t first_shadow) {
    WT_DCHECK_LE(end, queue.capacity);
    LightSampleBlock block;
    DirectSample scalar[kShadeChunk];
    int lane_row[kShadeChunk];  // per chunk row: its row of the block, or -1 (scalar)
    size_t s = first_shadow;
    for (size_t c = begin; c < end; c += kShadeChunk) {
        const size_t chunk_end = std::min(end, c + kShadeChunk);
        block.n = 0;
        for (size_t i = c; i < chunk_end; ++i) {
            const size_t row = i - c;
            const LightChoice light = in.lights.select(queue.u_select[i]);
            Vertex v = queued_vertex(queue, i);
            const int32_t quad = quad_light_sample_at(v, in.lights, light);
            const int32_t sphere = quad < 0 ? sphere_light_sample_at(v, in.lights, light) : -1;
            if (quad >= 0 || sphere >= 0) {
                lane_row[row] = static_cast<int>(block.n);
                push_row(queue, i, quad, sphere, light, block);
                continue;
            }
            lane_row[row] = -1;
            v.frame = Frame::from_normal(queue.ns[i]);
            scalar[row] =
                sample_direct(in.scene, in.lights, v, queue.wo[i], light, queue.u1[i], queue.u2[i]);
        }
        sample_lights_in_lanes(block, in.lights);
        for (size_t i = c; i < chunk_end; ++i) {
            const size_t row = i - c;
            const DirectSample d =
                lane_row[row] >= 0 ? lane_result(block, size_t(lane_row[row])) : scalar[row];
            if (!d.valid) continue;
            WT_DCHECK_LT(s, shadows.capacity);
            shadows.store(s++, {d.shadow.o, d.shadow.d, d.shadow.tmax, queue.beta[i] * d.value,
                                d.pdf_light, d.pdf_bsdf, queue.path[i]});
        }
    }
    return s - first_shadow;
}

}  // namespace wavetrace
