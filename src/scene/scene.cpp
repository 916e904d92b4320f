#include "wavetrace/scene/scene.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavetrace {

const char* to_string(MaterialKind kind) {
    switch (kind) {
        case MaterialKind::Lambertian:
            return "lambertian";
        case MaterialKind::Metal:
            return "metal";
        case MaterialKind::Mirror:
            return "mirror";
        case MaterialKind::Dielectric:
            return "dielectric";
        case MaterialKind::DiffuseLight:
            return "diffuse_light";
        case MaterialKind::Isotropic:
            return "isotropic";
        case MaterialKind::Interface:
            return "interface";
    }
    return "?";
}

TextureId Scene::add_texture(const Texture& texture) {
    textures.push_back(texture);
    return static_cast<TextureId>(textures.size() - 1);
}

TextureId Scene::add_solid(Color color) {
    Texture t;
    t.kind = TextureKind::Solid;
    t.color = color;
    return add_texture(t);
}

ImageId Scene::add_image(ImageData image) {
    images.push_back(std::move(image));
    return static_cast<ImageId>(images.size() - 1);
}

MaterialId Scene::add_material(Material material) {
    materials.push_back(std::move(material));
    return static_cast<MaterialId>(materials.size() - 1);
}

MediumId Scene::add_medium(std::string medium_name, float density, TextureId albedo) {
    if (media.size() >= kMaxMedia)
        throw std::length_error("a scene holds at most " + std::to_string(kMaxMedia) + " media");
    Material phase;
    phase.name = medium_name + ".phase";
    phase.kind = MaterialKind::Isotropic;
    phase.albedo = albedo;
    media.push_back({std::move(medium_name), density, add_material(std::move(phase))});
    return static_cast<MediumId>(media.size() - 1);
}

MaterialId Scene::interface_material() {
    for (size_t i = 0; i < materials.size(); ++i)
        if (materials[i].kind == MaterialKind::Interface) return static_cast<MaterialId>(i);
    Material m;
    m.name = "interface";
    m.kind = MaterialKind::Interface;
    return add_material(std::move(m));
}

void Scene::add_sphere(Sphere sphere, const Transform& to_world) {
    float s = 1.0f;
    if (!to_world.preserves_shape(&s))
        throw std::invalid_argument("a sphere's transform must not scale non-uniformly or shear");
    sphere.center = to_world.point(sphere.center);
    sphere.radius *= s;
    spheres.push_back(sphere);
}

void Scene::add_quad(Quad quad, const Transform& to_world) {
    quad.q = to_world.point(quad.q);
    quad.u = to_world.vector(quad.u);
    quad.v = to_world.vector(quad.v);
    // cross(M u, M v) = det(M) M^-T (u x v): a mirroring transform turns the normal inwards
    // unless u and v trade places.
    if (to_world.flips_handedness()) std::swap(quad.u, quad.v);
    quads.push_back(quad);
}

void Scene::add_box(
    Point3 lo, Point3 hi, MaterialId material, MediumId interior, const Transform& to_world) {
    Vec3 dx{hi.x - lo.x, 0, 0}, dy{0, hi.y - lo.y, 0}, dz{0, 0, hi.z - lo.z};
    // Each face's u x v points out of the box.
    const Quad faces[6] = {
        {{lo.x, lo.y, hi.z}, dx, dy, material, interior},   // front (+z)
        {{hi.x, lo.y, lo.z}, -dx, dy, material, interior},  // back (-z)
        {{hi.x, lo.y, hi.z}, -dz, dy, material, interior},  // right (+x)
        {{lo.x, lo.y, lo.z}, dz, dy, material, interior},   // left (-x)
        {{lo.x, hi.y, hi.z}, dx, -dz, material, interior},  // top (+y)
        {{lo.x, lo.y, lo.z}, dx, dz, material, interior},   // bottom (-y)
    };
    for (const Quad& f : faces) add_quad(f, to_world);
}

size_t Scene::add_mesh(Mesh mesh,
                       const std::vector<Point3>& pos,
                       const std::vector<Normal3>& nrm,
                       const std::vector<Vec2>& uv,
                       const std::vector<uint32_t>& indices,
                       const Transform& to_world) {
    mesh.first_vertex = static_cast<uint32_t>(positions.size());
    mesh.vertex_count = static_cast<uint32_t>(pos.size());
    mesh.has_normals = !nrm.empty() && nrm.size() == pos.size();
    mesh.has_uvs = !uv.empty() && uv.size() == pos.size();
    for (size_t i = 0; i < pos.size(); ++i) {
        positions.push_back(to_world.point(pos[i]));
        Normal3 n = mesh.has_normals ? to_world.normal(nrm[i]) : Normal3{};
        float len = length(n);
        normals.push_back(len > 0 && std::isfinite(len) ? n / len : Normal3{});
        uvs.push_back(mesh.has_uvs ? uv[i] : Vec2{});
    }
    uint32_t mesh_id = static_cast<uint32_t>(meshes.size());
    meshes.push_back(std::move(mesh));

    size_t skipped = 0;
    const uint32_t base = meshes.back().first_vertex;
    const bool flip = to_world.flips_handedness();  // keep the winding's outside outside
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
        if (flip) std::swap(b, c);
        bool bad =
            a >= pos.size() || b >= pos.size() || c >= pos.size() || a == b || b == c || a == c;
        if (!bad) {
            Point3 p0 = positions[base + a], p1 = positions[base + b], p2 = positions[base + c];
            float area2 = length_squared(cross(p1 - p0, p2 - p0));
            bad = !(area2 > 0.0f) || !std::isfinite(area2) || !is_finite(p0) || !is_finite(p1) ||
                  !is_finite(p2);
        }
        if (bad) {
            ++skipped;
            continue;
        }
        triangles.push_back({{base + a, base + b, base + c}, mesh_id});
    }
    return skipped;
}

Aabb Scene::prim_bounds(PrimRef prim) const {
    Aabb box;
    uint32_t i = prim.index();
    switch (prim.kind()) {
        case PrimKind::Triangle:
            for (uint32_t v : triangles[i].v) box.grow(positions[v]);
            break;
        case PrimKind::Quad: {
            const Quad& q = quads[i];
            box.grow(q.q);
            box.grow(q.q + q.u);
            box.grow(q.q + q.v);
            box.grow(q.q + q.u + q.v);
            break;
        }
        case PrimKind::Sphere: {
            const Sphere& s = spheres[i];
            box.grow(s.center - Vec3(s.radius));
            box.grow(s.center + Vec3(s.radius));
            break;
        }
    }
    return box;
}

Aabb Scene::bounds() const {
    Aabb box;
    for (size_t i = 0; i < triangles.size(); ++i)
        box.grow(prim_bounds(PrimRef::make(PrimKind::Triangle, static_cast<uint32_t>(i))));
    for (size_t i = 0; i < quads.size(); ++i)
        box.grow(prim_bounds(PrimRef::make(PrimKind::Quad, static_cast<uint32_t>(i))));
    for (size_t i = 0; i < spheres.size(); ++i)
        box.grow(prim_bounds(PrimRef::make(PrimKind::Sphere, static_cast<uint32_t>(i))));
    return box;
}

MaterialId Scene::prim_material(PrimRef prim) const {
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

MediumId Scene::prim_interior(PrimRef prim) const {
    switch (prim.kind()) {
        case PrimKind::Triangle:
            return meshes[triangles[prim.index()].mesh].interior;
        case PrimKind::Quad:
            return quads[prim.index()].interior;
        case PrimKind::Sphere:
            return spheres[prim.index()].interior;
    }
    return kNone;
}

float Scene::prim_area(PrimRef prim) const {
    uint32_t i = prim.index();
    switch (prim.kind()) {
        case PrimKind::Triangle: {
            const Triangle& t = triangles[i];
            Point3 p0 = positions[t.v[0]], p1 = positions[t.v[1]], p2 = positions[t.v[2]];
            return 0.5f * length(cross(p1 - p0, p2 - p0));
        }
        case PrimKind::Quad:
            return length(cross(quads[i].u, quads[i].v));
        case PrimKind::Sphere:
            return 4.0f * kPi * spheres[i].radius * spheres[i].radius;
    }
    return 0.0f;
}

std::vector<PrimRef> collect_emitters(const Scene& scene) {
    std::vector<PrimRef> emitters;
    auto add = [&](PrimKind kind, size_t n) {
        for (size_t i = 0; i < n; ++i) {
            PrimRef ref = PrimRef::make(kind, static_cast<uint32_t>(i));
            MaterialId m = scene.prim_material(ref);
            if (m != kNone && scene.materials[m].is_emissive()) emitters.push_back(ref);
        }
    };
    add(PrimKind::Triangle, scene.triangles.size());
    add(PrimKind::Quad, scene.quads.size());
    add(PrimKind::Sphere, scene.spheres.size());
    return emitters;
}

}  // namespace wavetrace
