#include "pbrt/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "scene/tessellate.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

constexpr double kPiD = 3.14159265358979323846;
// The most triangles a subdivided mesh may reach: pbrt's default 3 levels of any mesh, or a
// quarter million, so that the work stays proportional to the file.
size_t max_subdivided_triangles(size_t control) { return 64 * control + (size_t(1) << 18); }

[[noreturn]] void fail(const std::string& place, const std::string& message) {
    throw SceneError(place + ": " + message);
}

Vec3 vertex(const std::vector<double>& v, size_t i) {
    return {static_cast<float>(v[3 * i]), static_cast<float>(v[3 * i + 1]),
            static_cast<float>(v[3 * i + 2])};
}

// Vertices P, N, uv of a mesh shape, and its index list (`arity` per face) checked against them.
struct Vertices {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;
    std::vector<Vec2> uvs;
    std::vector<uint32_t> indices;
};

Vertices vertices(PbrtParams& p, const std::string& place, size_t arity) {
    Vertices out;
    const std::vector<double>* P = p.numbers("P", 3);
    if (!P || P->size() < 3 * arity) fail(place, p.what + ": needs \"P\" with " + std::to_string(arity) + " or more points");
    const size_t n = P->size() / 3;
    if (n > (size_t(1) << 31)) fail(place, p.what + ": too many vertices");
    for (size_t i = 0; i < n; ++i) out.positions.push_back(vertex(*P, i));
    if (const std::vector<double>* N = p.numbers("N", 3)) {
        if (N->size() != P->size()) fail(place, p.what + ": \"N\" needs one normal per point of \"P\"");
        for (size_t i = 0; i < n; ++i) out.normals.push_back(vertex(*N, i));
    }
    const std::vector<double>* uv = p.numbers("uv", 2);
    if (!uv) uv = p.numbers("st", 2);
    if (uv) {
        if (uv->size() != 2 * n) fail(place, p.what + ": \"uv\" needs one pair per point of \"P\"");
        for (size_t i = 0; i < n; ++i)
            out.uvs.push_back({static_cast<float>((*uv)[2 * i]), static_cast<float>((*uv)[2 * i + 1])});
    }
    if (const std::vector<double>* idx = p.numbers("indices", arity)) {
        if (idx->empty()) fail(place, p.what + ": \"indices\" is empty");
        for (double v : *idx) {
            if (!(v >= 0 && v < static_cast<double>(n)) || v != std::floor(v))
                fail(place, p.what + ": index " + std::to_string(v) + " is not a point of \"P\" (0 .. " +
                                std::to_string(n - 1) + ")");
            out.indices.push_back(static_cast<uint32_t>(v));
        }
    } else if (n == arity) {
        for (uint32_t i = 0; i < arity; ++i) out.indices.push_back(i);
    } else {
        fail(place, p.what + ": needs \"indices\" (more than " + std::to_string(arity) + " points)");
    }
    return out;
}

// pbrt's geometric normal is flipped towards the shading normals where they are given: the
// triangle is wound so that its normal agrees.
void orient_by_normals(PbrtMesh* m) {
    if (m->normals.empty()) return;
    for (size_t t = 0; t + 2 < m->indices.size(); t += 3) {
        uint32_t* f = &m->indices[t];
        const Vec3 n = cross(m->positions[f[1]] - m->positions[f[0]],
                             m->positions[f[2]] - m->positions[f[0]]);
        const Vec3 s = m->normals[f[0]] + m->normals[f[1]] + m->normals[f[2]];
        if (dot(n, s) < 0) std::swap(f[1], f[2]);
    }
}

PbrtMesh triangle_mesh(PbrtParams& p, const std::string& place) {
    Vertices v = vertices(p, place, 3);
    p.get("S");
    p.get("faceIndices");
    PbrtMesh m{std::move(v.positions), std::move(v.normals), std::move(v.uvs), std::move(v.indices)};
    orient_by_normals(&m);
    return m;
}

// Bilinear patches p00, p10, p01, p11: planar ones as two triangles, others as a grid of them.
PbrtMesh bilinear_mesh(PbrtParams& p, const std::string& place) {
    Vertices v = vertices(p, place, 4);
    p.get("faceIndices");
    PbrtMesh m{v.positions, v.normals, v.uvs, {}};
    const bool has_n = !v.normals.empty(), has_uv = !v.uvs.empty();
    for (size_t f = 0; f < v.indices.size(); f += 4) {
        const uint32_t* q = &v.indices[f];
        const Point3 p00 = v.positions[q[0]], p10 = v.positions[q[1]], p01 = v.positions[q[2]],
                     p11 = v.positions[q[3]];
        const Vec3 n = cross(p10 - p00, p01 - p00);
        const float size = std::max(length(p10 - p00), length(p01 - p00));
        const bool planar = length(n) > 0 &&
                            std::abs(dot(p11 - p00, normalize(n))) <= 1e-5f * size;
        if (planar) {
            m.indices.insert(m.indices.end(), {q[0], q[1], q[3], q[0], q[3], q[2]});
            continue;
        }
        constexpr int kGrid = 8;
        const uint32_t base = static_cast<uint32_t>(m.positions.size());
        for (int j = 0; j <= kGrid; ++j)
            for (int i = 0; i <= kGrid; ++i) {
                const float u = static_cast<float>(i) / kGrid, w = static_cast<float>(j) / kGrid;
                auto lerp2 = [&](auto a00, auto a10, auto a01, auto a11) {
                    return (1 - w) * ((1 - u) * a00 + u * a10) + w * ((1 - u) * a01 + u * a11);
                };
                m.positions.push_back(lerp2(p00, p10, p01, p11));
                if (has_n)
                    m.normals.push_back(lerp2(v.normals[q[0]], v.normals[q[1]], v.normals[q[2]],
                                              v.normals[q[3]]));
                if (has_uv) {
                    const Vec2 a = v.uvs[q[0]], b = v.uvs[q[1]], c = v.uvs[q[2]], d = v.uvs[q[3]];
                    m.uvs.push_back({(1 - w) * ((1 - u) * a.x + u * b.x) + w * ((1 - u) * c.x + u * d.x),
                                     (1 - w) * ((1 - u) * a.y + u * b.y) + w * ((1 - u) * c.y + u * d.y)});
                }
            }
        for (int j = 0; j < kGrid; ++j)
            for (int i = 0; i < kGrid; ++i) {
                const uint32_t a = base + j * (kGrid + 1) + i, b = a + 1, c = a + kGrid + 1, d = c + 1;
                m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
            }
    }
    orient_by_normals(&m);
    return m;
}

// A disk (or an annulus, or a sector of either) at z = height facing +z.
PbrtMesh disk(PbrtParams& p, const std::string& place) {
    const double h = p.number("height", 0), r = p.number("radius", 1);
    const double ri = p.number("innerradius", 0), phimax = p.number("phimax", 360);
    if (!(r > 0) || !(ri >= 0 && ri < r)) fail(place, p.what + ": needs 0 <= innerradius < radius");
    if (!(phimax > 0 && phimax <= 360)) fail(place, p.what + ": phimax must lie in (0, 360]");
    TessellatedShape t = tessellate_disk(r, ri, phimax * kPiD / 180, h);
    PbrtMesh m;
    m.positions = std::move(t.positions);
    m.uvs = std::move(t.uvs);
    m.indices = std::move(t.indices);
    return m;
}

// A cylinder's side about z from zmin to zmax, facing outwards, with the true normals.
PbrtMesh cylinder(PbrtParams& p, const std::string& place) {
    const double r = p.number("radius", 1), zmin = p.number("zmin", -1), zmax = p.number("zmax", 1);
    const double phimax = p.number("phimax", 360);
    if (!(r > 0)) fail(place, p.what + ": needs radius > 0");
    if (!(zmin < zmax) && !(zmax < zmin)) fail(place, p.what + ": needs zmin != zmax");
    if (!(phimax > 0 && phimax <= 360)) fail(place, p.what + ": phimax must lie in (0, 360]");
    // pbrt swaps zmin and zmax where they come reversed.
    TessellatedShape t =
        tessellate_cylinder(r, std::min(zmin, zmax), std::max(zmin, zmax), phimax * kPiD / 180);
    PbrtMesh m;
    m.positions = std::move(t.positions);
    m.normals = std::move(t.normals);
    m.uvs = std::move(t.uvs);
    m.indices = std::move(t.indices);
    return m;
}

// Loop's subdivision (C. Loop, "Smooth Subdivision Surfaces Based on Triangles", 1987), with
// the boundary rules of Hoppe et al. 1994, `levels` times, then every vertex moved to its
// limit position, as pbrt does.
PbrtMesh loop_subdivision(PbrtParams& p, const std::string& place) {
    const int levels = p.integer("levels", 3, 0, 16);
    Vertices v = vertices(p, place, 3);
    std::vector<Vec3> pos = v.positions;
    std::vector<uint32_t> tri = v.indices;
    auto key = [](uint32_t a, uint32_t b) {
        return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
    };
    // Each vertex's neighbours and whether it lies on a boundary (an edge of one face).
    auto rings = [&](std::vector<std::vector<uint32_t>>* nb, std::vector<char>* boundary,
                     std::map<uint64_t, std::vector<uint32_t>>* edges) {
        edges->clear();
        for (size_t t = 0; t < tri.size(); t += 3)
            for (int e = 0; e < 3; ++e)
                (*edges)[key(tri[t + e], tri[t + (e + 1) % 3])].push_back(tri[t + (e + 2) % 3]);
        nb->assign(pos.size(), {});
        boundary->assign(pos.size(), 0);
        for (const auto& [k, opposite] : *edges) {
            const uint32_t a = static_cast<uint32_t>(k >> 32), b = static_cast<uint32_t>(k);
            (*nb)[a].push_back(b);
            (*nb)[b].push_back(a);
            if (opposite.size() != 2) (*boundary)[a] = (*boundary)[b] = 1;
        }
    };
    // The neighbours along boundary edges of a boundary vertex.
    auto boundary_neighbours = [&](uint32_t a, const std::vector<uint32_t>& ring,
                                   const std::map<uint64_t, std::vector<uint32_t>>& edges) {
        std::vector<uint32_t> out;
        for (uint32_t b : ring)
            if (edges.at(key(a, b)).size() != 2) out.push_back(b);
        return out;
    };
    auto beta = [](size_t n) {
        const double c = 3.0 / 8 + std::cos(2 * kPiD / static_cast<double>(n)) / 4;
        return (5.0 / 8 - c * c) / static_cast<double>(n);
    };
    std::vector<std::vector<uint32_t>> nb;
    std::vector<char> boundary;
    std::map<uint64_t, std::vector<uint32_t>> edges;
    // Every vertex moved by its one ring: an interior one of valence n to (1 - n w(n)) v +
    // w(n) (its neighbours' sum), a boundary one to c v + (1 - c) / 2 (b0 + b1), b0 and b1
    // its neighbours along the boundary (a vertex on no face, or where the boundary branches,
    // stays).
    auto smoothed = [&](const auto& w, float c) {
        std::vector<Vec3> out(pos.size());
        for (uint32_t a = 0; a < pos.size(); ++a) {
            const std::vector<uint32_t>& ring = nb[a];
            out[a] = pos[a];
            if (ring.empty()) continue;
            if (!boundary[a]) {
                const double k = w(ring.size());
                Vec3 sum(0.0f);
                for (uint32_t n : ring) sum = sum + pos[n];
                out[a] = static_cast<float>(1 - ring.size() * k) * pos[a] + static_cast<float>(k) * sum;
            } else if (const std::vector<uint32_t> bn = boundary_neighbours(a, ring, edges);
                       bn.size() == 2) {
                out[a] = c * pos[a] + 0.5f * (1 - c) * (pos[bn[0]] + pos[bn[1]]);
            }
        }
        return out;
    };
    for (int level = 0; level < levels; ++level) {
        const size_t limit = max_subdivided_triangles(v.indices.size() / 3);
        if (tri.size() / 3 * 4 > limit)
            fail(place, p.what + ": " + std::to_string(levels) + " levels give more than " +
                            std::to_string(limit) + " triangles (the limit: 64 times the control "
                            "mesh's, plus 262144)");
        rings(&nb, &boundary, &edges);
        std::vector<Vec3> next = smoothed(beta, 0.75f);
        std::map<uint64_t, uint32_t> edge_vertex;
        for (const auto& [k, opposite] : edges) {
            const uint32_t a = static_cast<uint32_t>(k >> 32), b = static_cast<uint32_t>(k);
            edge_vertex[k] = static_cast<uint32_t>(next.size());
            if (opposite.size() == 2)
                next.push_back(0.375f * (pos[a] + pos[b]) + 0.125f * (pos[opposite[0]] + pos[opposite[1]]));
            else
                next.push_back(0.5f * (pos[a] + pos[b]));
        }
        std::vector<uint32_t> finer;
        finer.reserve(tri.size() * 4);
        for (size_t t = 0; t < tri.size(); t += 3) {
            const uint32_t a = tri[t], b = tri[t + 1], c = tri[t + 2];
            const uint32_t ab = edge_vertex[key(a, b)], bc = edge_vertex[key(b, c)],
                           ca = edge_vertex[key(c, a)];
            finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        pos = std::move(next);
        tri = std::move(finer);
    }
    // The limit surface: interior vertices by Loop's gamma = 1 / (n + 3 / (8 beta)), boundary
    // ones as 3/5 v + 1/5 (b0 + b1).
    rings(&nb, &boundary, &edges);
    std::vector<Vec3> limit = smoothed(
        [&](size_t n) { return 1 / (static_cast<double>(n) + 3 / (8 * beta(n))); }, 0.6f);
    PbrtMesh m;
    m.positions = std::move(limit);
    m.indices = std::move(tri);
    return m;
}

}  // namespace

PbrtMesh pbrt_shape_mesh(const std::string& type, PbrtParams& p, const std::string& place) {
    if (type == "trianglemesh") return triangle_mesh(p, place);
    if (type == "bilinearmesh") return bilinear_mesh(p, place);
    if (type == "disk") return disk(p, place);
    if (type == "cylinder") return cylinder(p, place);
    return loop_subdivision(p, place);
}

void reverse_winding(PbrtMesh* mesh) {
    for (size_t t = 0; t + 2 < mesh->indices.size(); t += 3)
        std::swap(mesh->indices[t + 1], mesh->indices[t + 2]);
}

}  // namespace wavetrace
