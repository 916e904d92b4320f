// The scattering vertices of a bounce that sample a light, appended by shade in a fixed order
// for the light_sample kernel: what sampling a light and evaluating the BSDF towards it needs,
// the vertex resolved (textures evaluated), and nothing of the hit it came from.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/material.h"

namespace wavetrace {

// Every vertex that samples lights is Lambertian, a rough metal or a medium's isotropic phase
// function (can_sample_lights): an albedo and a roughness describe its BSDF.
#define WAVETRACE_LIGHT_SAMPLE_FIELDS(F)                          \
    F(uint32_t, path, "entry of the path queue it belongs to")    \
    F(Point3, p, "vertex position")                               \
    F(Normal3, ng, "geometric normal, outward; zero in a medium") \
    F(Normal3, ns, "shading normal, the frame's z")               \
    F(Vec3, wo, "unit direction back along the ray that arrived") \
    F(Color, albedo, "the BSDF's albedo at the vertex")           \
    F(float, alpha, "rough metal: GGX alpha")                     \
    F(MaterialKind, kind, "Lambertian, Metal or Isotropic")       \
    F(Color, beta, "path throughput arriving at the vertex")      \
    F(float, u_select, "uniform number that picks the light")     \
    F(float, u1, "uniform numbers of the point on the light")     \
    F(float, u2, "")

WAVETRACE_SOA(LightSampleQueue, WAVETRACE_LIGHT_SAMPLE_FIELDS);

}  // namespace wavetrace
