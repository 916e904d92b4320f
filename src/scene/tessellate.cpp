#include "scene/tessellate.h"

#include <algorithm>
#include <cmath>

namespace wavetrace {
namespace {

constexpr double kTwoPiD = 6.28318530717958647692;

// A full turn given in degrees and converted may exceed 2π by an ulp: not a 129th segment.
int segments_for(double phimax) {
    return std::max(4, static_cast<int>(std::ceil(kSegmentsPerTurn * phimax / kTwoPiD - 1e-9)));
}

}  // namespace

TessellatedShape tessellate_disk(double radius, double inner, double phimax, double height) {
    const int segments = segments_for(phimax);
    TessellatedShape m;
    const float z = static_cast<float>(height);
    // Rings of radius `radius` (v = 0) and `inner` (v = 1).
    for (int ring = 0; ring < 2; ++ring) {
        const double rho = ring == 0 ? radius : inner;
        for (int i = 0; i <= segments; ++i) {
            const double u = static_cast<double>(i) / segments, phi = u * phimax;
            m.positions.push_back({static_cast<float>(rho * std::cos(phi)),
                                   static_cast<float>(rho * std::sin(phi)), z});
            m.uvs.push_back({static_cast<float>(u), static_cast<float>(ring)});
        }
    }
    const uint32_t in = static_cast<uint32_t>(segments + 1);
    for (uint32_t i = 0; i < static_cast<uint32_t>(segments); ++i) {
        m.indices.insert(m.indices.end(), {i, i + 1, in + i + 1});
        if (inner > 0) m.indices.insert(m.indices.end(), {i, in + i + 1, in + i});
    }
    return m;
}

TessellatedShape tessellate_cylinder(double radius, double zmin, double zmax, double phimax) {
    const int segments = segments_for(phimax);
    TessellatedShape m;
    // Rings at zmin (v = 0) and zmax (v = 1).
    for (int ring = 0; ring < 2; ++ring) {
        const float z = static_cast<float>(ring == 0 ? zmin : zmax);
        for (int i = 0; i <= segments; ++i) {
            const double u = static_cast<double>(i) / segments, phi = u * phimax;
            const float c = static_cast<float>(std::cos(phi)), s = static_cast<float>(std::sin(phi));
            m.positions.push_back({static_cast<float>(radius) * c, static_cast<float>(radius) * s, z});
            m.normals.push_back({c, s, 0.0f});
            m.uvs.push_back({static_cast<float>(u), static_cast<float>(ring)});
        }
    }
    // Each segment a quad (bottom i, i + 1; top i + 1, i), counter-clockwise seen from outside.
    const uint32_t top = static_cast<uint32_t>(segments + 1);
    for (uint32_t i = 0; i < static_cast<uint32_t>(segments); ++i) {
        m.indices.insert(m.indices.end(), {i, i + 1, top + i + 1});
        m.indices.insert(m.indices.end(), {i, top + i + 1, top + i});
    }
    return m;
}

}  // namespace wavetrace
