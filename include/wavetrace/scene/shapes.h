#pragma once

#include <cstdint>
#include <string>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// Every shape carries the material of its surface and the medium inside it (kNone: none).
// Geometric normals point outwards; emitters emit on that side unless two-sided.

struct Sphere {
    Point3 center;
    float radius = 1.0f;
    MaterialId material = kNone;
    MediumId interior = kNone;
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
    bool has_normals = false;  // Scene::normals holds per-vertex shading normals for it
    bool has_uvs = false;      // Scene::uvs holds per-vertex texture coordinates for it
    MaterialId material = kNone;
    MediumId interior = kNone;
};

// Counter-clockwise winding seen from the front: normal along (v1 - v0) x (v2 - v0).
struct Triangle {
    uint32_t v[3];
    uint32_t mesh;
};

}  // namespace wavetrace
