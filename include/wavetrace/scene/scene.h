// The scene: plain arrays of shapes, materials, textures and media, with builder helpers.
// Loaded from a file by load_scene() (wavetrace/loaders/load_scene.h) or built in code; the BVH is
// built over it afterwards.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavetrace/math/aabb.h"
#include "wavetrace/math/transform.h"
#include "wavetrace/sampling/sampler.h"
#include "wavetrace/scene/background.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/ids.h"
#include "wavetrace/scene/light.h"
#include "wavetrace/scene/material.h"
#include "wavetrace/scene/medium.h"
#include "wavetrace/scene/shapes.h"
#include "wavetrace/scene/texture.h"
#include "wavetrace/scene/volume_grid.h"

namespace wavetrace {

// Limits on what a scene file or the command line may ask for: beyond them a request is
// taken for a mistake, not a render.
inline constexpr int kMaxImageSide = 32768;
inline constexpr long long kMaxPixels = 1LL << 27;  // 134 M pixels, e.g. 16384 x 8192
inline constexpr int kMaxSpp = 1 << 20;
inline constexpr int kMaxDepth = 1024;

// Defaults for a render of this scene; the command line overrides them.
struct RenderSettings {
    int width = 600;
    int height = 600;
    int spp = 16;
    int max_depth = 50;
    SamplerKind sampler = SamplerKind::Sobol;
};

// Most media a scene may declare: the wavefront packs medium ids into 15 bits.
inline constexpr size_t kMaxMedia = 32000;

struct Scene {
    std::string name;
    Camera camera;
    RenderSettings render;
    Background background;
    MediumBoundaries medium_boundaries = MediumBoundaries::Nested;
    // Whether a direction must also lie on the side of the geometric surface its lobe says
    // (reflection on wo's side, transmission across), else it carries nothing: Veach 1997,
    // §5.3, against light leaking where the shading normal disagrees. False: the shading frame
    // alone decides, as in pbrt-v4 and Mitsuba 3 (their readers set it).
    bool geometric_side_test = true;

    std::vector<Texture> textures;
    std::vector<ImageData> images;
    std::vector<Material> materials;
    std::vector<Medium> media;
    std::vector<VolumeGrid> volume_grids;  // heterogeneous media's extinctions, grid textures

    std::vector<Sphere> spheres;
    std::vector<Frame> sphere_frames;  // the own frames of spheres whose transform rotates them
    std::vector<Quad> quads;
    std::vector<Mesh> meshes;
    std::vector<Triangle> triangles;
    std::vector<Point3> positions;  // mesh vertices, all meshes back to back
    std::vector<Normal3> normals;   // per vertex; zero for meshes without normals
    std::vector<Vec2> uvs;          // per vertex; zero for meshes without uvs
    std::vector<MeshAttribute> mesh_attributes;  // of every mesh, each naming its mesh
    std::vector<Light> lights;      // lights that are not shapes (emissive shapes are lights too)

    // ---- builders (all transforms are baked into the stored shapes) ----
    TextureId add_texture(const Texture& texture);
    TextureId add_solid(Color color);
    ImageId add_image(ImageData image);
    MaterialId add_material(Material material);
    // A medium of extinction sigma_t per world unit (one density for all channels, or one per
    // channel) whose phase function has the given albedo texture.
    MediumId add_medium(std::string medium_name, Color sigma_t, TextureId albedo);
    MediumId add_medium(std::string medium_name, float density, TextureId albedo) {
        return add_medium(std::move(medium_name), Color(density), albedo);
    }
    // The pass-through material of medium boundaries (created on first use).
    MaterialId interface_material();

    // Shapes whose material is the interface material (medium boundaries that are no surface)
    // are moved outwards by a hair, boundary_margin() of their world bounds, so that they are
    // never coplanar with a surface or another boundary they touch (docs/scene-format.md,
    // "Media").
    void add_sphere(Sphere sphere, const Transform& to_world = {});
    void add_quad(Quad quad, const Transform& to_world = {});
    // Six outward-facing quads spanning [lo, hi].
    void add_box(Point3 lo,
                 Point3 hi,
                 MaterialId material,
                 MediumId interior,
                 const Transform& to_world = {});
    // Appends a mesh; normals and uvs may be empty (else one per position). Indices are
    // relative to this mesh's positions. Degenerate triangles (zero area, repeated or
    // out-of-range indices, non-finite vertices) are skipped; returns how many were.
    // `attributes` hold one value per position or per triangle of `indices` (any other count
    // is a SceneError); a skipped triangle's value goes with it.
    size_t add_mesh(Mesh mesh,
                    const std::vector<Point3>& positions,
                    const std::vector<Normal3>& normals,
                    const std::vector<Vec2>& uvs,
                    const std::vector<uint32_t>& indices,
                    const Transform& to_world = {},
                    std::vector<MeshAttribute> attributes = {});
    // The attribute named `attribute` of mesh `mesh`, or nullptr.
    const MeshAttribute* mesh_attribute(uint32_t mesh, const std::string& attribute) const;

    // How far a medium boundary with these world bounds is moved outwards.
    static float boundary_margin(const Aabb& world_bounds);

    // ---- queries ----
    size_t primitive_count() const { return spheres.size() + quads.size() + triangles.size(); }
    Aabb bounds() const;
    Aabb prim_bounds(PrimRef prim) const;
    // Inline: the wavefront's shade asks it of every hit.
    MaterialId prim_material(PrimRef prim) const {
        switch (prim.kind()) {
            case PrimKind::Triangle:
                return meshes[triangles[prim.index()].mesh].material;
            case PrimKind::Quad:
                return quads[prim.index()].material;
            case PrimKind::Sphere:
                return spheres[prim.index()].material;
        }
        return kNone;
    }
    MediumId prim_interior(PrimRef prim) const;
    float prim_area(PrimRef prim) const;
    // Whether `material` (kNone: no) marks a medium boundary, an Interface with no surface.
    bool is_boundary(MaterialId material) const {
        return material < materials.size() && materials[material].kind == MaterialKind::Interface;
    }

  private:
    void add_box_faces(
        Point3 lo, Point3 hi, MaterialId material, MediumId interior, const Transform& to_world);
};

// Throws SceneError if the scene refers to something it does not hold (a material, texture,
// image or medium id out of range; a checker whose cells are not added before it), a material
// lacks a texture its kind reads, or a shape, light or camera is not finite. What load_scene()
// returns passes; a scene built in code should be checked before a BVH is built over it.
void check_scene(const Scene& scene);

// Why mesh `mesh` cannot be rendered with its material: an attribute the material reads that
// the mesh does not have (named, with those it has); "" if none.
std::string missing_attribute(const Scene& scene, uint32_t mesh);
// Every primitive whose material emits: the scene's area lights.
std::vector<PrimRef> collect_emitters(const Scene& scene);

// Bad scene input: the message names the file and the place in it
// ("scenes/x.json: /objects/3/radius: expected a positive number, got -1").
class SceneError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace wavetrace
