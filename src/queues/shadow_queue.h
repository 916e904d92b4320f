// Vertices where paths scatter (for light sampling), and the shadow rays light sampling makes.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/shading/medium_stack.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

// Indexed like the ray queue entry that reached the vertex; `has_vertex` marks the entries
// that light sampling applies to.
#define WAVETRACE_SCATTER_QUEUE_FIELDS(F)                                    \
    F(uint8_t, has_vertex, "1: a vertex that samples lights is stored here") \
    F(Vertex, vertex, "the scattering vertex")                               \
    F(Vec3, wo, "unit direction back along the incoming segment")            \
    F(Color, beta, "path throughput at the vertex, before the continuation") \
    F(MediumStack, media, "media at the vertex, before the continuation")    \
    F(Vec3, light_u, "the vertex's light-sample numbers: select, u, v")

WAVETRACE_SOA(ScatterQueue, WAVETRACE_SCATTER_QUEUE_FIELDS);

#define WAVETRACE_SHADOW_QUEUE_FIELDS(F)                                                       \
    F(Ray, ray, "shadow ray (unit direction, tmax short of the light)")                        \
    F(Color, contribution, "beta f Le / p_light: unweighted, unoccluded")                      \
    F(float, pdf_light, "light density of the sample (solid angle, selection included)")       \
    F(float, pdf_bsdf, "BSDF density of the same direction")                                   \
    F(MediumStack, media, "media at the ray's origin")                                         \
    F(float, transmittance, "written by the shadow intersection: 0 blocked, else attenuation") \
    F(uint32_t, path, "path slot in the wave")

WAVETRACE_SOA(ShadowQueue, WAVETRACE_SHADOW_QUEUE_FIELDS);

}  // namespace wavetrace
