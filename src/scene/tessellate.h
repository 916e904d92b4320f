// Analytic shapes that wavetrace renders as triangle meshes: disks (and annuli, and sectors of
// either) and open cylinders, as pbrt-v4 and Mitsuba 3 define them. One tessellation for the
// JSON loader's `disk` and `cylinder` and for pbrt's `Shape "disk"`.
#pragma once

#include <cstdint>
#include <vector>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

struct TessellatedShape {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;  // empty (flat), or one per position
    std::vector<Vec2> uvs;         // one per position
    std::vector<uint32_t> indices;
};

// Segments of a full turn: a disk's tessellated area is n sin(2π/n) / (2π) of the true one
// (0.99960), a cylinder's n sin(π/n) / π (0.99990).
inline constexpr int kSegmentsPerTurn = 128;

// The part of the plane z = `height` between radii `inner` and `radius` (0 <= inner < radius)
// and angles 0 .. `phimax` (radians, in (0, 2π]), its triangles counter-clockwise seen from +z
// (facing +z). uv as pbrt-v4's disk: (φ / phimax, (radius − ρ) / (radius − inner)).
TessellatedShape tessellate_disk(double radius, double inner, double phimax, double height);

// The side of the cylinder of `radius` about the z axis between z = zmin and zmax (zmin <
// zmax), angles 0 .. `phimax` (radians, in (0, 2π]), open at both ends, facing outwards, with
// vertex normals of the true surface (so that it shades round). uv as pbrt-v4's cylinder:
// (φ / phimax, (z − zmin) / (zmax − zmin)).
TessellatedShape tessellate_cylinder(double radius, double zmin, double zmax, double phimax);

}  // namespace wavetrace
