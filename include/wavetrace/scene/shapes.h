#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// Every shape carries the material of its surface and the medium inside it (kNone: none).
// Geometric normals point outwards; emitters emit on that side unless two-sided.

// How a sphere's texture coordinates follow its outward normal n, taken into the sphere's own
// frame (its transform's rotation, Scene::sphere_frames; none: the world's):
// - YUp (the default): Ray Tracing: The Next Week's, u = (atan2(-n.z, n.x) + pi) / 2 pi,
//   v = acos(-n.y) / pi.
// - ZUp: pbrt-v4's, u = phi / 2 pi with phi = atan2(n.y, n.x) in [0, 2 pi), v = 1 - acos(n.z) / pi;
//   Mitsuba 3's (u, 1 - v).
enum class SphereMapping : uint8_t { YUp, ZUp };

struct Sphere {
    Point3 center;
    float radius = 1.0f;
    MaterialId material = kNone;
    MediumId interior = kNone;
    SphereMapping mapping = SphereMapping::YUp;
    uint32_t frame = kNone;  // index into Scene::sphere_frames; kNone: the world's axes
};

// Parallelogram q + a u + b v, a, b in [0, 1]; normal along u x v (the quad of Ray Tracing: The
// Next Week). Its texture coordinates are (a, b), or (a, 1 - b) with flip_v (Mitsuba's
// rectangle, whose v runs the other way about its normal).
struct Quad {
    Point3 q;
    Vec3 u, v;
    MaterialId material = kNone;
    MediumId interior = kNone;
    bool flip_v = false;
};

// A triangle mesh's shared attributes; its vertices live in the scene's vertex arrays from
// first_vertex on, and its triangles index them with absolute indices.
struct Mesh {
    std::string name;
    uint32_t first_vertex = 0;
    uint32_t vertex_count = 0;
    uint32_t first_triangle = 0;  // its triangles are Scene::triangles[first_triangle, ...)
    bool has_normals = false;  // Scene::normals holds per-vertex shading normals for it
    bool has_uvs = false;      // Scene::uvs holds per-vertex texture coordinates for it
    MaterialId material = kNone;
    MediumId interior = kNone;
};

// Values a mesh gives each vertex or each triangle beyond its geometry, read by
// TextureKind::MeshAttribute (Mitsuba 3's mesh attributes, a PLY's further properties). The
// name starts with "vertex_" or "face_"; values holds one entry per vertex or per triangle of
// the mesh in order, a one-channel attribute's value in all three channels.
struct MeshAttribute {
    std::string name;
    bool per_face = false;
    uint8_t channels = 3;  // 1 or 3
    std::vector<Color> values;
    uint32_t mesh = 0;  // in Scene::mesh_attributes: the mesh it belongs to
};

// Counter-clockwise winding seen from the front: normal along (v1 - v0) x (v2 - v0).
struct Triangle {
    uint32_t v[3];
    uint32_t mesh;
};

}  // namespace wavetrace
