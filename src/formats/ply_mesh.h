// Stanford PLY meshes, read by our own code: Assimp's reader keeps positions, normals, uvs and
// red/green/blue only, and its post-processing reorders vertices, where Mitsuba's mesh
// attributes need every further property in the file's own vertex and face order.
#pragma once

#include <filesystem>

#include "formats/mesh_data.h"

namespace wavetrace {

// Reads an ASCII, binary little-endian or binary big-endian PLY file (Turk 1994; the format
// as the Stanford repository documents it). The `vertex` element gives positions (x, y, z),
// normals (nx, ny, nz) and uvs (u, v; s, t; texture_u, texture_v; or texture_s, texture_t);
// the `face` element its polygons (the list vertex_indices or vertex_index), fanned into
// triangles; other elements are skipped. Further scalar properties of vertices and faces
// become attributes named as Mitsuba 3 names them: r, g, b (or red, green, blue) make
// "vertex_color" / "face_color"; consecutive PREFIX_x, _y, _z (or _r _g _b, _0 _1 _2, _1 _2 _3)
// make "vertex_PREFIX" ("vertex_PREFIX_color" for _r _g _b), and a single PREFIX_x (or _r, _0,
// _1) a one-channel "vertex_PREFIX"; anything else (alpha, two or four components, names
// without such a suffix) is not an attribute. One material, "(none)", covers every triangle.
//
// Every count is checked against what the rest of the file can hold before anything is
// allocated, every index against the vertex count. Throws std::runtime_error with the reason
// and the place (header line, or element and record), without the path.
MeshFile read_ply_mesh(const std::filesystem::path& path);

}  // namespace wavetrace
