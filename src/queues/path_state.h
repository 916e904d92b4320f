// What survives a bounce, per live path of a wave. Entries move with their rays (sorting by
// material, compaction), so no index leads from a ray to its path.
#pragma once

#include <cstdint>

#include "queues/packed_media.h"
#include "queues/soa.h"
#include "shading/path_vertex.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

#define WAVETRACE_PATH_FIELDS(F)                                                          \
    F(uint32_t, pixel, "film pixel index")                                                \
    F(uint32_t, sample, "the path's sample index: which of the pixel's samples it is")    \
    F(uint32_t, slot, "where the wave's film holds its radiance (WaveFilm)")              \
    F(uint16_t, bounce, "index of the vertex the current ray will reach (0: camera ray)") \
    F(uint16_t, depth, "that vertex's depth: bounce less the thin sheets passed")         \
    F(uint8_t, crossings, "medium boundaries crossed by the current segment")             \
    F(uint8_t, counts_fully, "previous vertex: camera, or could not sample lights")       \
    F(Color, beta, "path throughput")                                                     \
    F(float, eta_scale, "product of eta^2 over the path's refractions (for roulette)")    \
    F(Color, radiance, "radiance gathered so far")                                        \
    F(Point3, prev_p, "previous vertex: position (MIS density of emission found)")        \
    F(Normal3, prev_n, "previous vertex: geometric normal, zero in a medium (the same)")  \
    F(float, prev_total, "previous vertex: its light choice's importance sum (the same)") \
    F(float, prev_pdf, "previous vertex: BSDF density of the current ray's direction")    \
    F(PackedMedia, media, "media the current ray travels in")                             \
    F(float, flight, "optical depth the current segment may still travel in media")

WAVETRACE_SOA(PathQueue, WAVETRACE_PATH_FIELDS);

inline PreviousVertex previous_vertex(const PathQueue& q, size_t i) {
    return {q.prev_p[i], q.prev_pdf[i], q.counts_fully[i] != 0, q.prev_n[i], q.prev_total[i]};
}
inline void set_previous_vertex(PathQueue& q, size_t i, const PreviousVertex& v) {
    q.prev_p[i] = v.p;
    q.prev_n[i] = v.n;
    q.prev_total[i] = v.select_total;
    q.prev_pdf[i] = v.pdf_bsdf;
    q.counts_fully[i] = v.counts_fully;
}

}  // namespace wavetrace
