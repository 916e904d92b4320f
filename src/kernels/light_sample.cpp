#include "kernels/kernels.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

void light_sample(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end) {
    ShadowQueue& out = q.shadow_candidates;
    for (size_t i = begin; i < end; ++i) {
        q.shadow_keep[i] = 0;
        if (!q.scatter.has_vertex[i]) continue;
        const Vec3 u = q.scatter.light_u[i];
        DirectSample d =
            sample_direct(in.scene, in.lights, q.scatter.vertex[i], q.scatter.wo[i], u.x, u.y, u.z);
        if (!d.valid) continue;
        if (direct_weight(in.config.strategy, in.config.heuristic, d.pdf_light, d.pdf_bsdf) <= 0.0f)
            continue;
        out.ray[i] = d.shadow;
        out.contribution[i] = q.scatter.beta[i] * d.value;
        out.pdf_light[i] = d.pdf_light;
        out.pdf_bsdf[i] = d.pdf_bsdf;
        out.media[i] = q.scatter.media[i];
        out.path[i] = q.rays.path[i];
        q.shadow_keep[i] = 1;
    }
}

}  // namespace wavetrace
