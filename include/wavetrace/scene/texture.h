#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

enum class TextureKind : uint8_t {
    Solid,      // a constant colour
    Checker,    // 3-D checkerboard of two sub-textures, cells of size `scale` (RTNW §4.3)
    UvChecker,  // checkerboard over the (u, v) plane, cells of side `scale` in uv units
    Noise,      // Perlin turbulence "marble": 0.5 (1 + sin(scale z + 10 turb(p))) (RTNW §5)
    Image,      // an image mapped by the surface's (u, v): `filter`, `wrap_u`, `wrap_v`
    // The hit mesh's attribute named `attribute` (Scene::mesh_attributes) times `scale`: a
    // per-vertex one interpolated by the hit's barycentrics, a per-face one the triangle's
    // (Mitsuba 3's mesh_attribute). Only meshes have attributes.
    MeshAttribute,
    Product,  // the product of textures `factors` (pbrt-v4's scale texture; glTF's base colour
              // times its vertex colour)
    Grid,     // a volume grid read at the point (VolumeGrid::lookup): a medium's albedo
};

// How an image texture is looked up between texels: interpolated between the four nearest
// texel centres, or the texel the point falls in (Mitsuba's bitmap filter_type, pbrt-v4's
// imagemap filter "point", glTF's NEAREST).
enum class TextureFilter : uint8_t { Bilinear, Nearest };
// What an image texture holds outside [0, 1]^2, applied to texel indices: the image repeated,
// mirrored at every edge (period two images), its edge texels extended (Mitsuba's wrap_mode,
// pbrt-v4's wrap, glTF's wrapS and wrapT: REPEAT, MIRRORED_REPEAT, CLAMP_TO_EDGE), or black
// texels all around (pbrt-v4's wrap "black"; its grid media's samples beyond the grid).
enum class TextureWrap : uint8_t { Repeat, Mirror, Clamp, Black };
// Index i of a row of n texels (or of a volume grid's voxels) brought into [0, n); -1 for a
// black texel beyond the row.
int wrap_index(int64_t i, int n, TextureWrap wrap);

// A texture is a plain record; which fields matter depends on `kind`.
struct Texture {
    TextureKind kind = TextureKind::Solid;
    Color color{0.0f};       // Solid: the colour. Noise: the colour multiplied in.
    float scale = 1.0f;      // Checker: cell size (world units). Noise: frequency.
                             // MeshAttribute: multiplied in.
    std::string attribute;   // MeshAttribute: its name ("vertex_color", "face_weight")
    TextureId even = kNone;  // Checker: the texture of even cells
    TextureId odd = kNone;   // Checker: the texture of odd cells
    TextureId factors[2] = {kNone, kNone};  // Product: the textures multiplied
    ImageId image = kNone;   // Image: index into Scene::images
    VolumeGridId grid = kNone;                       // Grid: index into Scene::volume_grids
    TextureFilter filter = TextureFilter::Bilinear;  // Image
    TextureWrap wrap_u = TextureWrap::Repeat;        // Image: along u
    TextureWrap wrap_v = TextureWrap::Repeat;        // Image: along v
    Color factor{1.0f};      // Image: multiplied into the texels (glTF's colour factors)
    float cutoff = -1.0f;    // Image, Product: if >= 0, the value becomes 1 where its first
                             // channel reaches the cutoff and 0 elsewhere (glTF's alphaMode
                             // MASK)
    // Image, UvChecker: the affine map applied to the surface's (u, v) first,
    // (u', v') = (uv[0][0] u + uv[0][1] v + uv[0][2], uv[1][0] u + uv[1][1] v + uv[1][2]).
    float uv[2][3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};

    Vec2 map_uv(Vec2 st) const {
        return {uv[0][0] * st.x + uv[0][1] * st.y + uv[0][2],
                uv[1][0] * st.x + uv[1][1] * st.y + uv[1][2]};
    }
};

// A decoded image held as linear RGB floats, row 0 at the top.
struct ImageData {
    std::string path;  // where it was read from, for messages
    int width = 0;
    int height = 0;
    std::vector<Color> texels;

    Color texel(int x, int y) const { return texels[static_cast<size_t>(y) * width + x]; }
    // A texel, or black at index -1 (wrap_index's black beyond the image).
    Color texel_or_black(int x, int y) const { return x < 0 || y < 0 ? Color(0.0f) : texel(x, y); }
    // The image at (u, v), u running left to right and v bottom to top (OpenGL convention):
    // texel centres sit at half-integer coordinates of (u W, (1 - v) H).
    Color lookup(float u, float v, TextureFilter filter, TextureWrap wrap_u, TextureWrap wrap_v) const;
    // The gradient in (u, v) of luminance(factor * lookup(u, v)): with the bilinear filter the
    // exact derivative of the interpolation inside the texel cell that holds (u, v) (as
    // Mitsuba's bitmap eval_1_grad), with the nearest filter 0 (a constant inside each texel).
    Vec2 luminance_gradient(float u,
                            float v,
                            Color factor,
                            TextureFilter filter,
                            TextureWrap wrap_u,
                            TextureWrap wrap_v) const;
};

struct Scene;
struct Sphere;
// Whether texture `id` (kNone: no texture) reads the surface's uv: image textures, directly or
// through the textures it combines. The others read the point or nothing.
bool texture_reads_uv(const Scene& scene, TextureId id);
// The mesh attributes texture `id` (kNone: none) reads, directly or through the textures it
// combines, appended to `names`.
void texture_attributes(const Scene& scene, TextureId id, std::vector<std::string>* names);
// Whether texture `id` reads any mesh attribute.
bool texture_reads_attributes(const Scene& scene, TextureId id);

// Where a texture is looked up: the surface's texture coordinates and world point, and on a
// triangle (kNone: elsewhere) the hit's barycentric coordinates of its second and third vertex.
struct TexturePoint {
    Vec2 uv;
    Point3 p;
    uint32_t triangle = kNone;
    float b1 = 0.0f, b2 = 0.0f;
};

// Evaluates texture `id` at `at`.
Color eval_texture(const Scene& scene, TextureId id, const TexturePoint& at);
// At a point of no triangle (a sphere, a quad, a light's own texture).
inline Color eval_texture(const Scene& scene, TextureId id, Vec2 uv, Point3 p) {
    return eval_texture(scene, id, TexturePoint{uv, p});
}
// The gradient in the surface's (u, v) of texture `id`'s luminance at (uv, p), where the
// texture is an image without a cutoff (ImageData::luminance_gradient through its uv map);
// false for other textures, whose gradient the caller approximates.
bool texture_luminance_gradient(const Scene& scene, TextureId id, Vec2 uv, Vec2* gradient);
// The texture's mean over its domain (an image's texels, a checker's two cells; noise: half its
// colour; a product: the product of its factors' means), as Mitsuba's Texture::mean; 0 for
// kNone.
Color texture_mean(const Scene& scene, TextureId id);
// A sphere's texture coordinates at the point of outward unit normal ng: u = phi / 2 pi around
// -x..+z.., v = theta / pi from -y (Ray Tracing: The Next Week's mapping).
Vec2 sphere_uv(Normal3 ng);
// Sphere s's texture coordinates at the point of outward unit normal ng (in world space), in its
// mapping and frame (SphereMapping).
Vec2 sphere_uv(const Scene& scene, const Sphere& s, Normal3 ng);
// Perlin turbulence (RTNW §5.6): the sum of 7 octaves of |noise|, in [0, ~1.5).
float perlin_turbulence(Point3 p, int octaves = 7);
// Perlin gradient noise in [-1, 1].
float perlin_noise(Point3 p);

}  // namespace wavetrace
