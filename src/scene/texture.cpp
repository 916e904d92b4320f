#include "wavetrace/scene/texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

int wrap_index(int64_t i, int n, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::Clamp:
            return static_cast<int>(std::clamp<int64_t>(i, 0, n - 1));
        case TextureWrap::Black:
            return i >= 0 && i < n ? static_cast<int>(i) : -1;
        case TextureWrap::Mirror: {
            const int64_t m = ((i % (2 * int64_t(n))) + 2 * int64_t(n)) % (2 * int64_t(n));
            return static_cast<int>(m < n ? m : 2 * int64_t(n) - 1 - m);
        }
        case TextureWrap::Repeat:
        default:
            return static_cast<int>(((i % n) + n) % n);
    }
}

namespace {

// The four texels about (u, v) and its place between their centres (tx, ty in [0, 1)), as
// the bilinear filter reads them.
struct BilinearCell {
    int x0, x1, y0, y1;
    float tx, ty;
};

BilinearCell bilinear_cell(
    float u, float v, int width, int height, TextureWrap wrap_u, TextureWrap wrap_v, float lim) {
    // A repeated axis goes into the first period first, as floats.
    const float x = wrap_u == TextureWrap::Repeat
                        ? (u - std::floor(u)) * static_cast<float>(width) - 0.5f
                        : std::clamp(u * float(width) - 0.5f, -lim, lim);
    const float y = wrap_v == TextureWrap::Repeat
                        ? std::clamp((1.0f - (v - std::floor(v))) * static_cast<float>(height) -
                                         0.5f,
                                     -0.5f, static_cast<float>(height) - 0.5f)
                        : std::clamp((1.0f - v) * float(height) - 0.5f, -lim, lim);
    const float fx = std::floor(x), fy = std::floor(y);
    return {wrap_index(int64_t(fx), width, wrap_u),
            wrap_index(int64_t(fx) + 1, width, wrap_u),
            wrap_index(int64_t(fy), height, wrap_v),
            wrap_index(int64_t(fy) + 1, height, wrap_v),
            x - fx,
            y - fy};
}

// Far outside the image only the wrap matters, and float coordinates there are too coarse to
// tell texels apart: kept within 2^24 texel widths, which int64 holds.
constexpr float kCoordinateLimit = 0x1p24f;

}  // namespace

Color ImageData::lookup(
    float u, float v, TextureFilter filter, TextureWrap wrap_u, TextureWrap wrap_v) const {
    const float lim = kCoordinateLimit;
    if (filter == TextureFilter::Nearest) {
        const float x = std::clamp(u * float(width), -lim, lim);
        const float y = std::clamp((1.0f - v) * float(height), -lim, lim);
        return texel_or_black(wrap_index(int64_t(std::floor(x)), width, wrap_u),
                              wrap_index(int64_t(std::floor(y)), height, wrap_v));
    }
    const BilinearCell c = bilinear_cell(u, v, width, height, wrap_u, wrap_v, lim);
    const float tx = c.tx, ty = c.ty;
    return (1 - ty) * ((1 - tx) * texel_or_black(c.x0, c.y0) + tx * texel_or_black(c.x1, c.y0)) +
           ty * ((1 - tx) * texel_or_black(c.x0, c.y1) + tx * texel_or_black(c.x1, c.y1));
}

Vec2 ImageData::luminance_gradient(float u,
                                   float v,
                                   Color factor,
                                   TextureFilter filter,
                                   TextureWrap wrap_u,
                                   TextureWrap wrap_v) const {
    if (filter == TextureFilter::Nearest) return {0.0f, 0.0f};
    const BilinearCell c = bilinear_cell(u, v, width, height, wrap_u, wrap_v, kCoordinateLimit);
    auto l = [&](int x, int y) { return luminance(factor * texel_or_black(x, y)); };
    const float l00 = l(c.x0, c.y0), l10 = l(c.x1, c.y0), l01 = l(c.x0, c.y1), l11 = l(c.x1, c.y1);
    // x = u W - 1/2 and y = (1 - v) H - 1/2 inside the cell: d/du = W d/dx, d/dv = -H d/dy.
    const float ddx = (1 - c.ty) * (l10 - l00) + c.ty * (l11 - l01);
    const float ddy = (1 - c.tx) * (l01 - l00) + c.tx * (l11 - l10);
    return {float(width) * ddx, -float(height) * ddy};
}

namespace {

// Ken Perlin's gradient noise with random unit gradients and trilinear Hermite blending, as
// the seed builds it (RTNW §5). Tables come from a fixed splitmix64 stream, so the noise is
// the same on every platform.
class Perlin {
  public:
    Perlin() {
        uint64_t state = 0x5eed5eedULL;
        auto next = [&state] {
            uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            return z ^ (z >> 31);
        };
        auto uniform = [&] { return static_cast<float>(next() >> 40) * 0x1p-24f; };
        for (Vec3& g : gradients_) {
            do {
                g = {2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1};
            } while (length_squared(g) > 1.0f || length_squared(g) < 1e-4f);
            g = normalize(g);
        }
        for (auto& perm : perm_) {
            for (int i = 0; i < kCount; ++i) perm[i] = i;
            for (int i = kCount - 1; i > 0; --i) std::swap(perm[i], perm[next() % (i + 1)]);
        }
    }

    float noise(Point3 p) const {
        float u = p.x - std::floor(p.x), v = p.y - std::floor(p.y), w = p.z - std::floor(p.z);
        int i = static_cast<int>(std::floor(p.x)), j = static_cast<int>(std::floor(p.y)),
            k = static_cast<int>(std::floor(p.z));
        float uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
        float accum = 0;
        for (int di = 0; di < 2; ++di)
            for (int dj = 0; dj < 2; ++dj)
                for (int dk = 0; dk < 2; ++dk) {
                    const Vec3& g = gradients_[perm_[0][(i + di) & 255] ^ perm_[1][(j + dj) & 255] ^
                                               perm_[2][(k + dk) & 255]];
                    Vec3 weight{u - di, v - dj, w - dk};
                    accum += (di * uu + (1 - di) * (1 - uu)) * (dj * vv + (1 - dj) * (1 - vv)) *
                             (dk * ww + (1 - dk) * (1 - ww)) * dot(g, weight);
                }
        return accum;
    }

  private:
    static constexpr int kCount = 256;
    std::array<Vec3, kCount> gradients_;
    std::array<std::array<int, kCount>, 3> perm_;
};

const Perlin& perlin() {
    static const Perlin instance;
    return instance;
}

}  // namespace

float perlin_noise(Point3 p) {
    return perlin().noise(p);
}

float perlin_turbulence(Point3 p, int octaves) {
    float accum = 0, weight = 1;
    for (int i = 0; i < octaves; ++i) {
        accum += weight * perlin().noise(p);
        weight *= 0.5f;
        p *= 2.0f;
    }
    return std::fabs(accum);
}

bool texture_reads_uv(const Scene& scene, TextureId id) {
    if (id == kNone) return false;
    const Texture& t = scene.textures[id];
    switch (t.kind) {
        case TextureKind::Image:
        case TextureKind::UvChecker:
            return true;
        case TextureKind::Checker:
            return texture_reads_uv(scene, t.even) || texture_reads_uv(scene, t.odd);
        case TextureKind::Product:
            return texture_reads_uv(scene, t.factors[0]) || texture_reads_uv(scene, t.factors[1]);
        case TextureKind::Solid:
        case TextureKind::Noise:
        case TextureKind::MeshAttribute:
        case TextureKind::Grid:
            return false;
    }
    return false;
}

void texture_attributes(const Scene& scene, TextureId id, std::vector<std::string>* names) {
    if (id == kNone || id >= scene.textures.size()) return;
    const Texture& t = scene.textures[id];
    if (t.kind == TextureKind::MeshAttribute) names->push_back(t.attribute);
    // A checker's cells and a product's factors come before it (check_scene), so this ends.
    const bool checker = t.kind == TextureKind::Checker || t.kind == TextureKind::UvChecker;
    const bool product = t.kind == TextureKind::Product;
    if (!checker && !product) return;
    for (const TextureId sub :
         checker ? std::array{t.even, t.odd} : std::array{t.factors[0], t.factors[1]})
        if (sub < id) texture_attributes(scene, sub, names);
}

bool texture_reads_attributes(const Scene& scene, TextureId id) {
    std::vector<std::string> names;
    texture_attributes(scene, id, &names);
    return !names.empty();
}

namespace {

// Value c of texture t after its cutoff (Texture::cutoff), where it has one.
Color after_cutoff(const Texture& t, Color c) {
    return t.cutoff >= 0.0f ? Color(c.x >= t.cutoff ? 1.0f : 0.0f) : c;
}

}  // namespace

Color eval_texture(const Scene& scene, TextureId id, const TexturePoint& at) {
    const Vec2 uv = at.uv;
    const Point3 p = at.p;
    for (;;) {
        const Texture& t = scene.textures[id];
        switch (t.kind) {
            case TextureKind::Solid:
                return t.color;
            case TextureKind::Checker: {
                // Cells of side `scale`: the parity of the sum of the cell indices.
                float inv = 1.0f / t.scale;
                long sum = static_cast<long>(std::floor(inv * p.x)) +
                           static_cast<long>(std::floor(inv * p.y)) +
                           static_cast<long>(std::floor(inv * p.z));
                id = (sum % 2 == 0) ? t.even : t.odd;
                continue;
            }
            case TextureKind::UvChecker: {
                // Cells of side `scale` in (u', v'): the parity of the sum of the cell indices
                // (Mitsuba's checkerboard is scale 0.5, even = its color0).
                const Vec2 st = t.map_uv(uv);
                const float inv = 1.0f / t.scale;
                const long sum = static_cast<long>(std::floor(inv * st.x)) +
                                 static_cast<long>(std::floor(inv * st.y));
                id = (sum % 2 == 0) ? t.even : t.odd;
                continue;
            }
            case TextureKind::Noise:
                return t.color *
                       (0.5f * (1.0f + std::sin(t.scale * p.z + 10.0f * perlin_turbulence(p))));
            case TextureKind::Grid:
                return scene.volume_grids[t.grid].lookup(p);
            case TextureKind::Image: {
                const Vec2 st = t.map_uv(uv);
                const Color c =
                    t.factor * scene.images[t.image].lookup(st.x, st.y, t.filter, t.wrap_u,
                                                                  t.wrap_v);
                return after_cutoff(t, c);
            }
            case TextureKind::Product:
                return after_cutoff(t, eval_texture(scene, t.factors[0], at) *
                                           eval_texture(scene, t.factors[1], at));
            case TextureKind::MeshAttribute: {
                // check_scene has made sure that only meshes holding the attribute read it.
                if (at.triangle == kNone) return {};
                const Triangle& tri = scene.triangles[at.triangle];
                const MeshAttribute* a = scene.mesh_attribute(tri.mesh, t.attribute);
                if (!a) return {};
                const Mesh& m = scene.meshes[tri.mesh];
                if (a->per_face) return t.scale * a->values[at.triangle - m.first_triangle];
                const auto v = [&](int k) { return a->values[tri.v[k] - m.first_vertex]; };
                return t.scale * ((1.0f - at.b1 - at.b2) * v(0) + at.b1 * v(1) + at.b2 * v(2));
            }
        }
        return {};
    }
}

bool texture_luminance_gradient(const Scene& scene, TextureId id, Vec2 uv, Vec2* gradient) {
    const Texture& t = scene.textures[id];
    if (t.kind != TextureKind::Image || t.cutoff >= 0.0f) return false;
    const Vec2 st = t.map_uv(uv);
    const Vec2 g = scene.images[t.image].luminance_gradient(st.x, st.y, t.factor, t.filter,
                                                            t.wrap_u, t.wrap_v);
    // Through the affine uv map st = A uv + b: the gradient in uv is A^T g.
    *gradient = {t.uv[0][0] * g.x + t.uv[1][0] * g.y, t.uv[0][1] * g.x + t.uv[1][1] * g.y};
    return true;
}

Vec2 sphere_uv(Normal3 ng) {
    const float theta = std::acos(std::fmax(-1.0f, std::fmin(1.0f, -ng.y)));
    const float phi = std::atan2(-ng.z, ng.x) + kPi;
    return {phi * (0.5f * kInvPi), theta * kInvPi};
}

Vec2 sphere_uv(const Scene& scene, const Sphere& s, Normal3 ng) {
    const Vec3 n = s.frame == kNone ? ng : scene.sphere_frames[s.frame].to_local(ng);
    if (s.mapping == SphereMapping::YUp) return sphere_uv(n);
    float phi = std::atan2(n.y, n.x);
    if (phi < 0.0f) phi += 2.0f * kPi;
    const float theta = std::acos(std::fmax(-1.0f, std::fmin(1.0f, n.z)));
    return {phi * (0.5f * kInvPi), 1.0f - theta * kInvPi};
}

Color texture_mean(const Scene& scene, TextureId id) {
    // A checker's cells name textures added before it (the loader's rule), so this ends; the
    // depth bound guards scenes built by hand.
    std::function<Color(TextureId, int)> mean_of = [&](TextureId t_id, int depth) -> Color {
        if (t_id == kNone || t_id >= scene.textures.size() || depth > 64) return {};
        const Texture& t = scene.textures[t_id];
        switch (t.kind) {
            case TextureKind::Solid:
                return t.color;
            case TextureKind::Checker:
            case TextureKind::UvChecker:
                return 0.5f * (mean_of(t.even, depth + 1) + mean_of(t.odd, depth + 1));
            case TextureKind::Noise:
                return 0.5f * t.color;
            case TextureKind::Product:
                return mean_of(t.factors[0], depth + 1) * mean_of(t.factors[1], depth + 1);
            case TextureKind::Image: {
                const ImageData& image = scene.images[t.image];
                Color sum{0.0f};
                for (const Color& c : image.texels) sum += c;
                return image.texels.empty() ? Color(0.0f)
                                            : t.factor * sum / float(image.texels.size());
            }
            case TextureKind::Grid: {  // over the voxels
                const VolumeGrid& g = scene.volume_grids[t.grid];
                Color sum{0.0f};
                const int res = g.res[0] * g.res[1] * g.res[2];
                for (int i = 0; i < res; ++i)
                    sum += g.voxel(i % g.res[0], i / g.res[0] % g.res[1], i / g.res[0] / g.res[1]);
                return res > 0 ? sum / float(res) : Color(0.0f);
            }
            case TextureKind::MeshAttribute: {  // over every mesh's values of that name
                Color sum{0.0f};
                size_t n = 0;
                for (const MeshAttribute& a : scene.mesh_attributes)
                    if (a.name == t.attribute) {
                        for (const Color& c : a.values) sum += c;
                        n += a.values.size();
                    }
                return n == 0 ? Color(0.0f) : t.scale * sum / float(n);
            }
        }
        return {};
    };
    return mean_of(id, 0);
}

}  // namespace wavetrace
