#include <cmath>
#include <string>

#include "scene/material_lookup.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

[[noreturn]] void fail(const std::string& what, size_t index, const std::string& problem) {
    throw SceneError("scene: " + what + " " + std::to_string(index) + ": " + problem);
}

bool finite(Vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Whether a material of this kind reads its albedo texture.
bool reads_albedo(MaterialKind kind) {
    switch (kind) {
        case MaterialKind::Lambertian:
        case MaterialKind::Metal:
        case MaterialKind::Mirror:
        case MaterialKind::Isotropic:
        case MaterialKind::Conductor:
        case MaterialKind::Plastic:
        case MaterialKind::MetallicRoughness:
        case MaterialKind::Principled:
            return true;
        default:
            return false;
    }
}

}  // namespace

std::string missing_attribute(const Scene& scene, uint32_t mesh) {
    const Mesh& m = scene.meshes[mesh];
    for (const std::string& name : material_attributes(scene, m.material)) {
        if (scene.mesh_attribute(mesh, name)) continue;
        std::string has;
        for (const MeshAttribute& a : scene.mesh_attributes)
            if (a.mesh == mesh) has += (has.empty() ? "" : ", ") + ("\"" + a.name + "\"");
        return "its material reads the mesh attribute \"" + name + "\", which mesh '" + m.name +
               "' does not have (" + (has.empty() ? "it has none" : "it has " + has) + ")";
    }
    return "";
}

void check_scene(const Scene& scene) {
    const size_t textures = scene.textures.size(), materials = scene.materials.size(),
                 media = scene.media.size();
    for (size_t i = 0; i < textures; ++i) {
        const Texture& t = scene.textures[i];
        // Sub-textures come first: a checker refers only to textures before it, so that
        // evaluating one ends.
        if (t.kind == TextureKind::Checker || t.kind == TextureKind::UvChecker) {
            if (t.even >= i || t.odd >= i)
                fail("texture", i, "a checker's cells must be textures added before it");
            if (!(t.scale > 0) || !std::isfinite(t.scale))
                fail("texture", i, "a checker's scale must be a positive number");
        }
        if (t.kind == TextureKind::Product && (t.factors[0] >= i || t.factors[1] >= i))
            fail("texture", i, "a product's factors must be textures added before it");
        if (t.kind == TextureKind::Grid && t.grid >= scene.volume_grids.size())
            fail("texture", i, "names no volume grid of the scene");
        if (t.kind == TextureKind::Image &&
            (t.image >= scene.images.size() || scene.images[t.image].texels.empty()))
            fail("texture", i, "names no image of the scene");
        if (!finite(t.color) || !finite(t.factor)) fail("texture", i, "a colour is not finite");
        if (t.kind == TextureKind::MeshAttribute && !std::isfinite(t.scale))
            fail("texture", i, "a mesh attribute's scale is not finite");
    }
    // Only what surface_at and surface_vertex look up at a triangle's hit knows the triangle.
    auto reads_attributes = [&](TextureId id) { return texture_reads_attributes(scene, id); };
    auto check_texture = [&](size_t m, TextureId id, const char* field, bool required) {
        if (id == kNone && !required) return;
        if (id >= textures)
            fail("material", m,
                 std::string(field) + (id == kNone ? " is needed" : " names no texture"));
    };
    for (size_t i = 0; i < materials; ++i) {
        const Material& m = scene.materials[i];
        check_texture(i, m.albedo, "albedo", reads_albedo(m.kind));
        check_texture(i, m.emission, "emission", m.kind == MaterialKind::DiffuseLight);
        check_texture(i, m.metallic_roughness, "metallic_roughness", false);
        check_texture(i, m.transmission_map, "transmission_texture", false);
        check_texture(i, m.clearcoat_map, "clearcoat_texture", false);
        check_texture(i, m.clearcoat_roughness_map, "clearcoat_roughness_texture", false);
        check_texture(i, m.opacity, "opacity", false);
        check_texture(i, m.normal_map, "normal_map", false);
        check_texture(i, m.bump_map, "bump_map", false);
        check_texture(i, m.clearcoat_normal_map, "clearcoat_normal_map", false);
        check_texture(i, m.alpha_u_texture, "alpha_u_texture", false);
        check_texture(i, m.alpha_v_texture, "alpha_v_texture", false);
        m.principled.for_each([&](const char* name, const TexturedNumber& w) {
            check_texture(i, w.texture, name, false);
            const float top = PrincipledWeights::max_of(name);
            if (!(w.value >= 0 && w.value <= top))
                fail("material", i,
                     std::string(name) + (top > 1 ? " must be in [0, 2]" : " must be in [0, 1]"));
        });
        if (m.kind == MaterialKind::Blend) {
            check_texture(i, m.blend_weight.texture, "a blend's weight", false);
            if (!(m.blend_weight.value >= 0 && m.blend_weight.value <= 1))
                fail("material", i, "a blend's weight must be in [0, 1]");
            for (const MaterialId b : m.blend) {
                // Materials come first, as sub-textures do: choosing one ends.
                if (b >= i) fail("material", i, "a blend's materials must be added before it");
                const Material& c = scene.materials[b];
                if (!c.can_be_blended())
                    fail("material", i,
                         "a blend's materials cannot emit, be cut away, be a thin dielectric, a "
                         "medium's interface or a phase function (blend " +
                             std::string(to_string(c.kind)) + " \"" + c.name + "\")");
            }
        }
        if (const char* field = attribute_misuse(scene, m))
            fail("material", i, std::string("its ") + field + " reads a mesh attribute");
        if (m.is_emissive() && m.kind == MaterialKind::Blend)
            fail("material", i, "a blend cannot emit; its materials are chosen at each hit");
        if (!(m.ior > 0) || !std::isfinite(m.ior)) fail("material", i, "ior must be positive");
        if (!(m.alpha_u >= 0 && m.alpha_v >= 0 && m.alpha_u <= 64 && m.alpha_v <= 64))
            fail("material", i, "alpha_u and alpha_v must be in [0, 64]");
    }
    for (size_t i = 0; i < scene.volume_grids.size(); ++i) {
        const VolumeGrid& g = scene.volume_grids[i];
        uint64_t voxels = 1;
        for (int a = 0; a < 3; ++a) {
            if (g.res[a] < 1) fail("volume grid", i, "needs a resolution of at least 1 per axis");
            voxels *= static_cast<uint64_t>(g.res[a]);
        }
        if ((g.channels != 1 && g.channels != 3) || g.values.size() != voxels * g.channels)
            fail("volume grid", i, "needs 1 or 3 channels and a value per channel and voxel");
        for (const float x : g.values)
            if (!(x >= 0.0f) || !std::isfinite(x))
                fail("volume grid", i, "values must be finite and non-negative");
    }
    for (size_t i = 0; i < media; ++i) {
        const Medium& m = scene.media[i];
        if (m.phase >= materials || scene.materials[m.phase].kind != MaterialKind::Isotropic)
            fail("medium", i, "its phase must be an isotropic material of the scene");
        if (reads_attributes(scene.materials[m.phase].albedo))
            fail("medium", i, "its phase's albedo reads a mesh attribute");
        for (int c = 0; c < 3; ++c)
            if (!(m.sigma_t[c] >= 0) || !std::isfinite(m.sigma_t[c]))
                fail("medium", i, "sigma_t must be non-negative numbers");
        if (m.heterogeneous() && m.density_grid >= scene.volume_grids.size())
            fail("medium", i, "its density grid names no volume grid of the scene");
    }
    auto check_refs = [&](const char* what, size_t i, MaterialId material, MediumId interior) {
        if (material >= materials) fail(what, i, "names no material of the scene");
        if (interior != kNone && interior >= media) fail(what, i, "names no medium of the scene");
    };
    for (size_t i = 0; i < scene.spheres.size(); ++i) {
        const Sphere& s = scene.spheres[i];
        check_refs("sphere", i, s.material, s.interior);
        if (!finite(s.center) || !(s.radius > 0) || !std::isfinite(s.radius))
            fail("sphere", i, "needs a finite centre and a positive radius");
        if (!material_attributes(scene, s.material).empty())
            fail("sphere", i, "its material reads a mesh attribute");
        if (s.mapping != SphereMapping::YUp && s.mapping != SphereMapping::ZUp)
            fail("sphere", i, "has no known texture mapping");
        if (s.frame != kNone && (s.frame >= scene.sphere_frames.size() ||
                                 !scene.sphere_frames[s.frame].is_orthonormal(1e-4f)))
            fail("sphere", i, "names no orthonormal frame of the scene's sphere_frames");
    }
    for (size_t i = 0; i < scene.quads.size(); ++i) {
        const Quad& q = scene.quads[i];
        check_refs("quad", i, q.material, q.interior);
        if (!finite(q.q) || !finite(q.u) || !finite(q.v) || length(cross(q.u, q.v)) == 0)
            fail("quad", i, "needs finite, non-parallel edges");
        if (!material_attributes(scene, q.material).empty())
            fail("quad", i, "its material reads a mesh attribute");
    }
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        check_refs("mesh", i, m.material, m.interior);
        if (size_t(m.first_vertex) + m.vertex_count > scene.positions.size())
            fail("mesh", i, "its vertices lie beyond the scene's positions");
        if (const std::string missing = missing_attribute(scene, uint32_t(i)); !missing.empty())
            fail("mesh", i, missing);
    }
    for (size_t i = 0; i < scene.mesh_attributes.size(); ++i) {
        const MeshAttribute& a = scene.mesh_attributes[i];
        if (a.mesh >= scene.meshes.size()) fail("mesh attribute", i, "names no mesh of the scene");
        const Mesh& m = scene.meshes[a.mesh];
        const size_t next = a.mesh + 1 < scene.meshes.size()
                                ? scene.meshes[a.mesh + 1].first_triangle
                                : scene.triangles.size();
        if (a.values.size() != (a.per_face ? next - m.first_triangle : m.vertex_count))
            fail("mesh attribute", i, "needs one value per vertex or per triangle of its mesh");
    }
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        if (t.mesh >= scene.meshes.size()) fail("triangle", i, "names no mesh of the scene");
        const Mesh& m = scene.meshes[t.mesh];
        for (uint32_t v : t.v)
            if (v < m.first_vertex || v - m.first_vertex >= m.vertex_count)
                fail("triangle", i, "a vertex lies outside its mesh");
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (!finite(l.position) || !finite(l.intensity) || !finite(l.direction) ||
            length(l.direction) == 0)
            fail("light", i, "needs a finite position, intensity and non-zero direction");
        if (reads_attributes(l.texture)) fail("light", i, "its texture reads a mesh attribute");
        if (l.texture != kNone) {
            if (l.kind != Light::Kind::Spot && l.kind != Light::Kind::Projector)
                fail("light", i, "only a spot or a projector projects a texture");
            if (l.texture >= textures) fail("light", i, "its texture names no texture");
            if (!finite(l.up) || std::abs(length(l.up) - 1) > 1e-4f ||
                std::abs(dot(l.up, l.direction)) > 1e-4f * length(l.direction))
                fail("light", i, "a projected texture needs a unit up orthogonal to the axis");
        }
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.kind == Light::Kind::Projector &&
            (!(l.half_width > 0 && l.half_height > 0) || !std::isfinite(l.half_width) ||
             !std::isfinite(l.half_height) || !finite(l.up) || std::abs(length(l.up) - 1) > 1e-4f ||
             std::abs(dot(l.up, l.direction)) > 1e-4f * length(l.direction)))
            fail("light", i,
                 "a projector needs a finite frustum and a unit up orthogonal to its axis");
    }
    const Background& bg = scene.background;
    if (!finite(bg.radiance)) throw SceneError("scene: the background radiance is not finite");
    if (bg.kind == Background::Kind::Environment &&
        (bg.image >= scene.images.size() || scene.images[bg.image].texels.empty()))
        throw SceneError("scene: the environment map names no image of the scene");
    if (bg.kind == Background::Kind::Environment &&
        bg.mapping == Background::Mapping::EqualArea &&
        scene.images[bg.image].width != scene.images[bg.image].height)
        throw SceneError("scene: an equal-area environment map must be square");
    if (bg.frame && !bg.frame->is_orthonormal(1e-4f))
        throw SceneError("scene: the environment's frame is not a rotation");
    const Camera& c = scene.camera;
    if (!finite(c.look_from) || !finite(c.look_at) || !finite(c.up) ||
        length(c.look_at - c.look_from) == 0 || length(cross(c.up, c.look_at - c.look_from)) == 0)
        throw SceneError(
            "scene: the camera needs distinct look_from and look_at and an up not along them");
    if (!(c.vfov > 0 && c.vfov < 180)) throw SceneError("scene: the camera's vfov must be in (0, 180)");
    if (c.orthographic && !(c.view_height > 0 && c.view_height <= 1e7f && c.view_width >= 0 &&
                            c.view_width <= 1e7f && c.aperture == 0))
        throw SceneError(
            "scene: an orthographic camera needs view_height in (0, 1e7], view_width "
            "in [0, 1e7] and no aperture");
}

}  // namespace wavetrace
