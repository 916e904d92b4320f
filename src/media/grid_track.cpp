#include "media/grid_track.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace {

// p[0] + p[1] x + p[2] x^2 + p[3] x^3 per channel.
struct Cubic {
    Color p[4];
    Color at(float x) const { return p[0] + x * (p[1] + x * (p[2] + x * p[3])); }
    // The integral from 0 to x.
    Color integral(float x) const {
        return x * (p[0] + x * (0.5f * p[1] + x * ((1.0f / 3.0f) * p[2] + x * (0.25f * p[3]))));
    }
};

// The extinction along x in [0, L) inside one cell, whose lower corner voxel is (i, j, k)
// (indices wrapped by VolumeGrid::voxel: with clamping, a cell beyond the outer centres is
// constant along that axis), where the fractions within the cell are f + df x. Trilinear
// interpolation as nested lerps, each multiplying in one linear factor: along z, then y, then
// x; a nearest-filtered grid's cell is its voxel's constant.
Cubic cell_cubic(const VolumeGrid& g, const int idx[3], const float f[3], const float df[3]) {
    if (g.nearest)
        return {{g.voxel(idx[0], idx[1], idx[2]), Color(0.0f), Color(0.0f), Color(0.0f)}};
    Color lz[2][2][2];  // [dx][dy] -> linear in x: {constant, slope}
    for (int dx = 0; dx < 2; ++dx)
        for (int dy = 0; dy < 2; ++dy) {
            const Color v0 = g.voxel(idx[0] + dx, idx[1] + dy, idx[2]);
            const Color d = g.voxel(idx[0] + dx, idx[1] + dy, idx[2] + 1) - v0;
            lz[dx][dy][0] = v0 + f[2] * d;
            lz[dx][dy][1] = df[2] * d;
        }
    Color qy[2][3];  // [dx] -> quadratic in x
    for (int dx = 0; dx < 2; ++dx) {
        const Color* a = lz[dx][0];
        const Color e0 = lz[dx][1][0] - a[0], e1 = lz[dx][1][1] - a[1];
        qy[dx][0] = a[0] + f[1] * e0;
        qy[dx][1] = a[1] + df[1] * e0 + f[1] * e1;
        qy[dx][2] = df[1] * e1;
    }
    const Color d0 = qy[1][0] - qy[0][0], d1 = qy[1][1] - qy[0][1], d2 = qy[1][2] - qy[0][2];
    Cubic c;
    c.p[0] = qy[0][0] + f[0] * d0;
    c.p[1] = qy[0][1] + df[0] * d0 + f[0] * d1;
    c.p[2] = qy[0][2] + df[0] * d1 + f[0] * d2;
    c.p[3] = df[0] * d2;
    return c;
}

// The x in [0, L] where channel c's integral reaches r (0 <= r <= integral(L)): Newton's method
// on the monotone integral, bisecting where a step would leave the bracket.
float solve_depth(const Cubic& q, int c, float r, float L, float total) {
    float lo = 0.0f, hi = L;
    float x = total > 0.0f ? L * (r / total) : 0.0f;
    for (int it = 0; it < 64; ++it) {
        const float f = q.integral(x)[c] - r;
        if (f == 0.0f) break;
        (f > 0.0f ? hi : lo) = x;
        const float slope = q.at(x)[c];
        float next = slope > 0.0f ? x - f / slope : 0.5f * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5f * (lo + hi);
        if (next == x || hi - lo <= 1e-7f * L) break;
        x = next;
    }
    return x;
}

}  // namespace

GridReach grid_reach(
    const VolumeGrid& g, Color scale, Point3 o, Vec3 dir, float length, int c, float target) {
    GridReach r;
    r.dist = length;
    // The part of the ray inside the grid's unit cube (the medium is empty outside it).
    const Point3 ol = g.to_local.point(o);
    const Vec3 dl = g.to_local.vector(dir);
    float s0 = 0.0f, s1 = length;
    for (int a = 0; a < 3; ++a) {
        if (dl[a] == 0.0f) {
            if (!(ol[a] >= 0.0f && ol[a] <= 1.0f)) return r;
            continue;
        }
        float ta = -ol[a] / dl[a], tb = (1.0f - ol[a]) / dl[a];
        if (ta > tb) std::swap(ta, tb);
        s0 = std::max(s0, ta);
        s1 = std::min(s1, tb);
    }
    if (!(s0 < s1)) return r;
    // Index space, voxel centres at integers (nearest: voxel i spans [i, i + 1)): u(s) = u0 +
    // du s. The walk visits the cells between consecutive integers of each axis in the order
    // the ray crosses them.
    float u0[3], du[3], next[3];
    int idx[3], step[3];
    for (int a = 0; a < 3; ++a) {
        u0[a] = ol[a] * g.res[a] - (g.nearest ? 0.0f : 0.5f);
        du[a] = dl[a] * g.res[a];
        const float u = std::fmin(std::fmax(u0[a] + du[a] * s0, -1.0f), float(g.res[a]));
        if (du[a] > 0.0f) {
            idx[a] = static_cast<int>(std::floor(u));
            step[a] = 1;
            next[a] = (float(idx[a] + 1) - u0[a]) / du[a];
        } else if (du[a] < 0.0f) {
            idx[a] = static_cast<int>(std::ceil(u)) - 1;
            step[a] = -1;
            next[a] = (float(idx[a]) - u0[a]) / du[a];
        } else {
            idx[a] = static_cast<int>(std::floor(u));
            step[a] = 0;
            next[a] = kInfinity;
        }
    }
    // A cell per crossing of an integer plane: at most res + 1 along each axis.
    const int max_cells = g.res[0] + g.res[1] + g.res[2] + 6;
    float s = s0;
    for (int cell = 0; cell < max_cells && s < s1; ++cell) {
        const int a =
            next[0] <= next[1] ? (next[0] <= next[2] ? 0 : 2) : (next[1] <= next[2] ? 1 : 2);
        const float end = std::min(next[a], s1);
        const float L = end - s;
        if (L > 0.0f) {
            float f[3];
            for (int b = 0; b < 3; ++b)
                f[b] = std::clamp(u0[b] + du[b] * s - float(idx[b]), 0.0f, 1.0f);
            Cubic q = cell_cubic(g, idx, f, du);
            for (Color& p : q.p) p = p * scale;
            const Color total = q.integral(L);
            const float remaining = target - r.depth[c];
            if (total[c] >= remaining) {
                const float x = solve_depth(q, c, std::max(remaining, 0.0f), L, total[c]);
                r.reached = true;
                r.dist = s + x;
                r.depth += q.integral(x);
                r.sigma = q.at(x);
                return r;
            }
            r.depth += total;
        }
        s = end;
        idx[a] += step[a];
        next[a] = (float(step[a] > 0 ? idx[a] + 1 : idx[a]) - u0[a]) / du[a];
    }
    return r;
}

}  // namespace wavetrace
