#include "wavetrace/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bsdfs/plastic.h"

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
        case MaterialKind::Conductor:
            return "conductor";
        case MaterialKind::Plastic:
            return "plastic";
        case MaterialKind::ThinDielectric:
            return "thin_dielectric";
        case MaterialKind::MetallicRoughness:
            return "metallic_roughness";
        case MaterialKind::Principled:
            return "principled";
        case MaterialKind::Blend:
            return "blend";
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
    if (material.kind == MaterialKind::Plastic) {
        const float s = mean(material.specular), d = mean(texture_mean(*this, material.albedo));
        material.specular_weight = s + d > 0.0f ? s / (s + d) : 0.5f;
        if (material.alpha_u > 0.0f) {
            // The table depends on the coating alone: computed once per coating.
            auto same = std::find_if(materials.begin(), materials.end(), [&](const Material& m) {
                return m.kind == MaterialKind::Plastic && m.alpha_u == material.alpha_u &&
                       m.distribution == material.distribution && m.ior == material.ior;
            });
            material.coating =
                same != materials.end()
                    ? same->coating
                    : rough_coating_table(material.distribution, material.alpha_u, material.ior);
        }
    }
    materials.push_back(std::move(material));
    return static_cast<MaterialId>(materials.size() - 1);
}

MediumId Scene::add_medium(std::string medium_name, Color sigma_t, TextureId albedo) {
    if (media.size() >= kMaxMedia)
        throw std::length_error("a scene holds at most " + std::to_string(kMaxMedia) + " media");
    Material phase;
    phase.name = medium_name + ".phase";
    phase.kind = MaterialKind::Isotropic;
    phase.albedo = albedo;
    media.push_back({std::move(medium_name), sigma_t, add_material(std::move(phase))});
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

// Medium boundaries that are no surface (interface material) are moved outwards by a hair, so
// that they are never coplanar with anything they touch: a surface coincident with a boundary
// (a smoke box standing on a floor, fog filling a room to its walls) is then met first from
// inside and last from outside, as if the boundary lay a hair beyond it; of two coincident
// boundaries (a medium box inside a medium box, both on the floor) the larger one, moved
// further, is entered first and left last. The hair is the ray offset at the shape's farthest
// corner (so that rounding never reorders the crossings; it grows with the shape, as the outer
// of two nested shapes contains the inner one's corners) plus 1e-5 of the shape's size.
float Scene::boundary_margin(const Aabb& world_bounds) {
    const Point3 corner = max(abs(world_bounds.lo), abs(world_bounds.hi));
    return origin_offset(corner) + 1e-5f * length(world_bounds.hi - world_bounds.lo);
}

void Scene::add_sphere(Sphere sphere, const Transform& to_world) {
    float s = 1.0f;
    if (!to_world.preserves_shape(&s))
        throw std::invalid_argument("a sphere's transform must not scale non-uniformly or shear");
    sphere.center = to_world.point(sphere.center);
    sphere.radius *= s;
    // Its own frame (for its texture coordinates): the transform's rotation, possibly mirrored,
    // after any frame it had; none while that is the identity.
    Frame f = sphere.frame == kNone ? Frame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}
                                    : sphere_frames.at(sphere.frame);
    f = {to_world.vector(f.s) / s, to_world.vector(f.t) / s, to_world.vector(f.n) / s};
    const Frame identity{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const float change =
        length(f.s - identity.s) + length(f.t - identity.t) + length(f.n - identity.n);
    if (change > 1e-6f) {
        sphere.frame = static_cast<uint32_t>(sphere_frames.size());
        sphere_frames.push_back(f);
    } else {
        sphere.frame = kNone;
    }
    if (is_boundary(sphere.material)) {
        const Vec3 r(sphere.radius);
        sphere.radius += boundary_margin(Aabb{sphere.center - r, sphere.center + r});
    }
    spheres.push_back(sphere);
}

void Scene::add_quad(Quad quad, const Transform& to_world) {
    quad.q = to_world.point(quad.q);
    quad.u = to_world.vector(quad.u);
    quad.v = to_world.vector(quad.v);
    // cross(M u, M v) = det(M) M^-T (u x v): a mirroring transform turns the normal inwards
    // unless v is reversed, from the far edge; flip_v keeps each point's texture coordinates.
    if (to_world.flips_handedness()) {
        quad.q += quad.v;
        quad.v = -quad.v;
        quad.flip_v = !quad.flip_v;
    }
    if (is_boundary(quad.material)) {  // outwards: along u x v
        Aabb b{min(quad.q, quad.q + quad.u + quad.v), max(quad.q, quad.q + quad.u + quad.v)};
        b.lo = min(b.lo, min(quad.q + quad.u, quad.q + quad.v));
        b.hi = max(b.hi, max(quad.q + quad.u, quad.q + quad.v));
        quad.q += boundary_margin(b) * normalize(cross(quad.u, quad.v));
    }
    quads.push_back(quad);
}

void Scene::add_box(
    Point3 lo, Point3 hi, MaterialId material, MediumId interior, const Transform& to_world) {
    if (is_boundary(material)) {
        // The whole box grows (its faces moved one by one would open gaps at its edges): each
        // local axis by the world margin over that axis's world length per unit.
        Aabb world;
        for (int c = 0; c < 8; ++c)
            world.grow(
                to_world.point({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z}));
        const float m = boundary_margin(world);
        const Vec3 grow{m / length(to_world.vector({1, 0, 0})),
                        m / length(to_world.vector({0, 1, 0})),
                        m / length(to_world.vector({0, 0, 1}))};
        lo -= grow;
        hi += grow;
    }
    add_box_faces(lo, hi, material, interior, to_world);  // not moved again face by face
}

void Scene::add_box_faces(
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
    for (Quad f : faces) {
        f.q = to_world.point(f.q);
        f.u = to_world.vector(f.u);
        f.v = to_world.vector(f.v);
        if (to_world.flips_handedness()) std::swap(f.u, f.v);
        quads.push_back(f);
    }
}

size_t Scene::add_mesh(Mesh mesh,
                       const std::vector<Point3>& pos,
                       const std::vector<Normal3>& nrm,
                       const std::vector<Vec2>& uv,
                       const std::vector<uint32_t>& indices,
                       const Transform& to_world,
                       std::vector<MeshAttribute> attributes) {
    const size_t faces = indices.size() / 3;
    for (const MeshAttribute& a : attributes)
        if (a.values.size() != (a.per_face ? faces : pos.size()) ||
            !(a.channels == 1 || a.channels == 3))
            throw SceneError("mesh '" + mesh.name + "': attribute '" + a.name + "' has " +
                             std::to_string(a.values.size()) + " values of " +
                             std::to_string(a.channels) + " channels for " +
                             std::to_string(a.per_face ? faces : pos.size()) +
                             (a.per_face ? " triangles" : " vertices"));
    mesh.first_vertex = static_cast<uint32_t>(positions.size());
    mesh.first_triangle = static_cast<uint32_t>(triangles.size());
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
    if (is_boundary(mesh.material) && !pos.empty()) {
        // A (convex, closed) boundary mesh: every vertex away from the centroid by the margin,
        // which moves every face outwards and keeps the mesh closed.
        Aabb b;
        Vec3 sum{0.0f};
        for (uint32_t i = mesh.first_vertex; i < positions.size(); ++i) {
            b.grow(positions[i]);
            sum += positions[i];
        }
        const Point3 centroid = sum / float(pos.size());
        const float m = boundary_margin(b);
        for (uint32_t i = mesh.first_vertex; i < positions.size(); ++i) {
            const Vec3 out = positions[i] - centroid;
            const float len = length(out);
            if (len > 0.0f && std::isfinite(len)) positions[i] += (m / len) * out;
        }
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
        for (MeshAttribute& x : attributes)  // kept triangles' values move down over skipped ones
            if (x.per_face) x.values[i / 3 - skipped] = x.values[i / 3];
    }
    for (MeshAttribute& x : attributes) {
        if (x.per_face) x.values.resize(faces - skipped);
        x.mesh = mesh_id;
        mesh_attributes.push_back(std::move(x));
    }
    return skipped;
}

const MeshAttribute* Scene::mesh_attribute(uint32_t mesh, const std::string& attribute) const {
    for (const MeshAttribute& a : mesh_attributes)
        if (a.mesh == mesh && a.name == attribute) return &a;
    return nullptr;
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
