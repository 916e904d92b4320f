// The scattering vertices of a bounce that sample a light, appended by shade in a fixed order
// for the light_sample kernel: what sampling a light and evaluating the BSDF towards it needs,
// the vertex resolved (textures evaluated), and nothing of the hit it came from.
#pragma once

#include <cstdint>

#include "queues/packed_media.h"
#include "queues/soa.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/material.h"

namespace wavetrace {

// A Lambertian or rough metal vertex, or a medium's isotropic phase function, is described by
// its albedo and roughness (the light_sample kernel's lanes read them); any other BSDF by its
// material besides (a conductor's index of refraction comes from there), with its roughness
// and a metallic-roughness one's metallic at the vertex (textures may vary them); a principled
// one's weights are looked up again at its texture coordinates.
#define WAVETRACE_LIGHT_SAMPLE_FIELDS(F)                                                \
    F(uint32_t, path, "entry of the path queue it belongs to")                          \
    WAVETRACE_XYZ_FIELD(F, p, "vertex position")                                        \
    WAVETRACE_XYZ_FIELD(F, ng, "geometric normal, outward; zero in a medium")           \
    WAVETRACE_XYZ_FIELD(F, ns, "shading normal, the frame's z")                         \
    F(float, frame_angle, "anisotropic BSDFs: the frame's turn about ns (Vertex)")      \
    WAVETRACE_XYZ_FIELD(F, unbent, "a mapped normal's shadowing: unperturbed normal")   \
    F(float, bump_alpha2, "... and its alpha^2; 0: none (Vertex)")                      \
    WAVETRACE_XYZ_FIELD(F, wo, "unit direction back along the ray that arrived")        \
    WAVETRACE_XYZ_FIELD(F, albedo, "the BSDF's albedo at the vertex")                   \
    F(float, alpha, "the BSDF's roughness (alpha_u) at the vertex")                     \
    F(float, alpha_v, "... across dp/du (textures may vary both)")                      \
    F(float, metallic, "metallic-roughness: metallic (a texture may vary both)")        \
    WAVETRACE_XYZ_FIELD(F, coat_n, "... and its coat's normal in the shading frame")    \
    F(float, uv_u, "principled: texture coordinates, where its weights are looked up")  \
    F(float, uv_v, "")                                                                  \
    F(MaterialKind, kind, "the BSDF's kind")                                            \
    F(MaterialId, material, "the material, or kNone where kind, albedo, alpha say all") \
    WAVETRACE_XYZ_FIELD(F, beta, "path throughput arriving at the vertex")              \
    F(float, u_select, "uniform number that picks the light")                           \
    F(float, u1, "uniform numbers of the point on the light")                           \
    F(float, u2, "")                                                                    \
    F(PackedMedia, media, "the path's media at the vertex, on wo's side")               \
    F(MediumId, interior, "the surface's interior medium (shadow_media)")

WAVETRACE_SOA(LightSampleQueue, WAVETRACE_LIGHT_SAMPLE_FIELDS);

// One entry, with its vectors whole.
struct QueuedVertex {
    uint32_t path;
    Point3 p;
    Normal3 ng, ns;
    float frame_angle;
    Normal3 unbent;
    float bump_alpha2;
    Vec3 wo;
    Color albedo;
    float alpha, alpha_v;
    float metallic;
    Vec3 coat_n;
    Vec2 uv;
    MaterialKind kind;
    MaterialId material;
    Color beta;
    float u_select, u1, u2;
    PackedMedia media;
    MediumId interior;
};

inline void store_queued_vertex(LightSampleQueue& q, size_t i, const QueuedVertex& v) {
    q.store(
        i, {v.path,        v.p.x,     v.p.y,      v.p.z,         v.ng.x,     v.ng.y,     v.ng.z,
            v.ns.x,        v.ns.y,    v.ns.z,     v.frame_angle, v.unbent.x, v.unbent.y, v.unbent.z,
            v.bump_alpha2, v.wo.x,    v.wo.y,     v.wo.z,        v.albedo.x, v.albedo.y, v.albedo.z,
            v.alpha,       v.alpha_v, v.metallic, v.coat_n.x,    v.coat_n.y, v.coat_n.z, v.uv.x,
            v.uv.y,        v.kind,    v.material, v.beta.x,      v.beta.y,   v.beta.z,   v.u_select,
            v.u1,          v.u2,      v.media,    v.interior});
}

}  // namespace wavetrace
