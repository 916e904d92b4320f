#include "kernels/kernels.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

void shade(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end) {
    const RenderConfig& cfg = in.config;
    PathState& ps = q.paths;
    for (size_t k = begin; k < end; ++k) {
        const uint32_t i = q.order[k];
        const uint32_t p = q.rays.path[i];
        q.keep[i] = 0;
        q.scatter.has_vertex[i] = 0;

        // ---- the segment: medium, emission, boundary or surface ----
        const Ray ray{q.rays.origin[i], q.rays.dir[i], q.rays.tmin[i]};
        const Hit hit{q.hits.t[i], q.hits.prim[i], q.hits.u[i], q.hits.v[i]};
        MediumStack media = ps.media[p];
        float flight = ps.flight[p];
        SegmentResult seg =
            resolve_segment(in.scene, in.lights, cfg, ray, hit, media, flight, ps.prev[p]);
        if (seg.event == SegmentEvent::Cross) {
            if (++ps.crossings[p] >= kMaxBoundaryCrossings) continue;
            ps.media[p] = media;
            ps.flight[p] = flight;
            q.rays.origin[i] = seg.next.o;
            q.rays.dir[i] = seg.next.d;
            q.rays.tmin[i] = seg.next.tmin;
            q.keep[i] = 1;
            continue;
        }
        if (seg.event == SegmentEvent::Emission) ps.radiance[p] += ps.beta[p] * seg.emission;
        if (seg.event != SegmentEvent::Scatter) continue;

        // ---- a scattering vertex: keep it for light sampling, then continue the path ----
        const int bounce = ps.bounce[p];
        if (!may_scatter(cfg, bounce)) continue;
        const uint32_t pixel = ps.pixel[p], sample = ps.sample[p];
        VertexSamples u = vertex_samples(cfg.seed, pixel, sample, bounce);
        if ((cfg.strategy == Strategy::Nee || cfg.strategy == Strategy::Mis) &&
            can_sample_lights(seg.vertex, in.lights)) {
            q.scatter.has_vertex[i] = 1;
            q.scatter.vertex[i] = seg.vertex;
            q.scatter.wo[i] = seg.wo;
            q.scatter.beta[i] = ps.beta[p];
            q.scatter.media[i] = media;
            q.scatter.light_u[i] = Vec3{u.light_select, u.light_u, u.light_v};
        }
        PathStep step = continue_path(in.scene, in.lights, cfg, seg.vertex, seg.wo, bounce,
                                      ps.beta[p], media, u.continuation, u.roulette);
        if (!step.alive) continue;
        ps.beta[p] *= step.weight;
        ps.prev[p] = step.prev;
        ps.media[p] = media;
        ps.bounce[p] = bounce + 1;
        ps.flight[p] = segment_flight(cfg.seed, pixel, sample, bounce + 1);
        ps.crossings[p] = 0;
        q.rays.origin[i] = step.next.o;
        q.rays.dir[i] = step.next.d;
        q.rays.tmin[i] = step.next.tmin;
        q.keep[i] = 1;
    }
}

}  // namespace wavetrace
