// Scenes: loading any format the loaders read, and building one with the Scene's builders.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>

#include "casters.h"
#include "py_scene.h"
#include "wavetrace/film/film_file.h"
#include "wavetrace/loaders/load_scene.h"

namespace wavetrace::python {
namespace {

// Warnings of a load, gathered while it runs (LoadOptions::warn is a plain function pointer,
// which may be called from any thread) and then issued as Python warnings: one load at a time.
std::mutex g_load_mutex;
std::vector<std::string>* g_warnings = nullptr;

std::shared_ptr<PyScene> load(const std::filesystem::path& path,
                              const std::string& camera,
                              const std::map<std::string, std::string>& params,
                              const std::optional<std::filesystem::path>& asset_root) {
    auto s = std::make_shared<PyScene>();
    std::vector<std::string> warnings;
    {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(g_load_mutex);
        LoadOptions options;
        options.camera = camera;
        options.params = params;
        if (asset_root) options.asset_root = *asset_root;
        g_warnings = &warnings;
        options.warn = [](const std::string& message) {
            static std::mutex mutex;
            std::lock_guard<std::mutex> guard(mutex);
            g_warnings->push_back(message);
        };
        try {
            s->scene = load_scene(path, options);
        } catch (...) {
            g_warnings = nullptr;
            throw;
        }
        g_warnings = nullptr;
        std::ifstream in(path, std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        s->fingerprint = fnv1a_64(text.data(), text.size());
    }
    s->path = path.string();
    py::module_ warn = py::module_::import("warnings");
    for (const std::string& w : warnings)
        warn.attr("warn")(w, py::module_::import("builtins").attr("UserWarning"), 2);
    return s;
}

ImageData image_data(const py::array_t<float, py::array::c_style | py::array::forcecast>& a,
                     const std::string& name) {
    Image image = to_image(a, "image");
    return ImageData{name, image.width, image.height, std::move(image.pixels)};
}

template <class T>
std::vector<T> rows(const py::handle& h, size_t columns, const char* what) {
    if (h.is_none()) return {};
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(h);
    if (!a || a.ndim() != 2 || size_t(a.shape(1)) != columns)
        throw py::value_error(std::string(what) + ": expected an array of shape (n, " +
                              std::to_string(columns) + ")");
    std::vector<T> out(a.shape(0));
    const float* p = a.data();
    for (size_t i = 0; i < out.size(); ++i) {
        if constexpr (sizeof(T) == 3 * sizeof(float))
            out[i] = T(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
        else
            out[i] = T{p[2 * i], p[2 * i + 1]};
    }
    return out;
}

}  // namespace

void bind_scene(py::module_& m) {
    m.attr("NONE") = kNone;

    py::enum_<TextureKind>(m, "TextureKind")
        .value("Solid", TextureKind::Solid)
        .value("Checker", TextureKind::Checker)
        .value("UvChecker", TextureKind::UvChecker)
        .value("Noise", TextureKind::Noise)
        .value("Image", TextureKind::Image)
        .value("MeshAttribute", TextureKind::MeshAttribute)
        .value("Product", TextureKind::Product)
        .value("Grid", TextureKind::Grid);
    py::enum_<TextureFilter>(m, "TextureFilter")
        .value("Bilinear", TextureFilter::Bilinear)
        .value("Nearest", TextureFilter::Nearest);
    py::enum_<TextureWrap>(m, "TextureWrap")
        .value("Repeat", TextureWrap::Repeat)
        .value("Mirror", TextureWrap::Mirror)
        .value("Clamp", TextureWrap::Clamp)
        .value("Black", TextureWrap::Black);
    py::class_<Texture> texture(m, "Texture", "A texture record; which fields matter depends on kind.");
    keyword_init(texture);
    texture.def_readwrite("kind", &Texture::kind)
        .def_readwrite("color", &Texture::color)
        .def_readwrite("scale", &Texture::scale)
        .def_readwrite("even", &Texture::even)
        .def_readwrite("odd", &Texture::odd)
        .def_readwrite("image", &Texture::image)
        .def_readwrite("factor", &Texture::factor)
        .def_readwrite("cutoff", &Texture::cutoff)
        .def_readwrite("filter", &Texture::filter)
        .def_readwrite("wrap_u", &Texture::wrap_u)
        .def_readwrite("wrap_v", &Texture::wrap_v)
        .def_readwrite("attribute", &Texture::attribute)
        .def_property(
            "factors", [](const Texture& t) { return std::pair(t.factors[0], t.factors[1]); },
            [](Texture& t, std::pair<TextureId, TextureId> f) {
                t.factors[0] = f.first;
                t.factors[1] = f.second;
            });

    py::enum_<MaterialKind>(m, "MaterialKind")
        .value("Lambertian", MaterialKind::Lambertian)
        .value("Metal", MaterialKind::Metal)
        .value("Mirror", MaterialKind::Mirror)
        .value("Dielectric", MaterialKind::Dielectric)
        .value("DiffuseLight", MaterialKind::DiffuseLight)
        .value("Isotropic", MaterialKind::Isotropic)
        .value("Interface", MaterialKind::Interface)
        .value("Conductor", MaterialKind::Conductor)
        .value("Plastic", MaterialKind::Plastic)
        .value("ThinDielectric", MaterialKind::ThinDielectric)
        .value("MetallicRoughness", MaterialKind::MetallicRoughness)
        .value("Principled", MaterialKind::Principled)
        .value("Blend", MaterialKind::Blend);
    py::enum_<Microfacet>(m, "Microfacet")
        .value("Ggx", Microfacet::Ggx)
        .value("Beckmann", Microfacet::Beckmann);
    py::class_<Material> material(
        m, "Material",
        "A material record (docs/scene-format.md); textures are ids from Scene.add_texture.");
    keyword_init(material);
    material.def_readwrite("name", &Material::name)
        .def_readwrite("kind", &Material::kind)
        .def_readwrite("albedo", &Material::albedo)
        .def_readwrite("roughness", &Material::roughness)
        .def_readwrite("ior", &Material::ior)
        .def_readwrite("emission", &Material::emission)
        .def_readwrite("two_sided", &Material::two_sided)
        .def_readwrite("one_sided", &Material::one_sided)
        .def_readwrite("eta", &Material::eta)
        .def_readwrite("k", &Material::k)
        .def_readwrite("distribution", &Material::distribution)
        .def_readwrite("alpha_u", &Material::alpha_u)
        .def_readwrite("alpha_v", &Material::alpha_v)
        .def_readwrite("alpha_u_texture", &Material::alpha_u_texture)
        .def_readwrite("alpha_v_texture", &Material::alpha_v_texture)
        .def_readwrite("specular", &Material::specular)
        .def_readwrite("nonlinear", &Material::nonlinear)
        .def_readwrite("metallic", &Material::metallic)
        .def_readwrite("transmission", &Material::transmission)
        .def_readwrite("clearcoat", &Material::clearcoat)
        .def_readwrite("clearcoat_roughness", &Material::clearcoat_roughness)
        .def_readwrite("metallic_roughness", &Material::metallic_roughness)
        .def_readwrite("opacity", &Material::opacity)
        .def_readwrite("normal_map", &Material::normal_map)
        .def_readwrite("bump_map", &Material::bump_map)
        .def_readwrite("bump_scale", &Material::bump_scale)
        .def_readwrite("flip_invalid_normals", &Material::flip_invalid_normals)
        .def_readwrite("bump_shadowing", &Material::bump_shadowing)
        // Blend: (first, second) material ids, and the second's weight, a number or a texture.
        .def_property(
            "blend_materials",
            [](const Material& x) { return std::make_pair(x.blend[0], x.blend[1]); },
            [](Material& x, std::pair<MaterialId, MaterialId> b) {
                x.blend[0] = b.first;
                x.blend[1] = b.second;
            })
        .def_property(
            "blend_weight", [](const Material& x) { return x.blend_weight.value; },
            [](Material& x, float w) { x.blend_weight.value = w; })
        .def_property(
            "blend_weight_texture", [](const Material& x) { return x.blend_weight.texture; },
            [](Material& x, TextureId t) { x.blend_weight.texture = t; });

    py::enum_<SphereMapping>(m, "SphereMapping", "How a sphere's texture coordinates follow it.")
        .value("YUp", SphereMapping::YUp)
        .value("ZUp", SphereMapping::ZUp);
    py::class_<Sphere> sphere(m, "Sphere");
    keyword_init(sphere);
    sphere.def_readwrite("center", &Sphere::center)
        .def_readwrite("radius", &Sphere::radius)
        .def_readwrite("material", &Sphere::material)
        .def_readwrite("mapping", &Sphere::mapping)
        .def_readwrite("interior", &Sphere::interior);
    py::class_<Quad> quad(m, "Quad", "The parallelogram q + a u + b v, a, b in [0, 1].");
    keyword_init(quad);
    quad.def_readwrite("q", &Quad::q)
        .def_readwrite("u", &Quad::u)
        .def_readwrite("v", &Quad::v)
        .def_readwrite("material", &Quad::material)
        .def_readwrite("flip_v", &Quad::flip_v)
        .def_readwrite("interior", &Quad::interior);

    py::class_<Light> light(m, "Light", "A point, spot, directional or projector light.");
    py::enum_<Light::Kind>(light, "Kind")
        .value("Point", Light::Kind::Point)
        .value("Spot", Light::Kind::Spot)
        .value("Directional", Light::Kind::Directional)
        .value("Projector", Light::Kind::Projector);
    py::enum_<Light::Falloff>(light, "Falloff")
        .value("Linear", Light::Falloff::Linear)
        .value("Smoothstep", Light::Falloff::Smoothstep);
    keyword_init(light);
    light.def_readwrite("kind", &Light::kind)
        .def_readwrite("position", &Light::position)
        .def_readwrite("direction", &Light::direction)
        .def_readwrite("intensity", &Light::intensity)
        .def_readwrite("cutoff_degrees", &Light::cutoff_degrees)
        .def_readwrite("falloff_start_degrees", &Light::falloff_start_degrees)
        .def_readwrite("falloff", &Light::falloff)
        .def_readwrite("texture", &Light::texture,
                       "spot, projector: the id of a texture it projects (NONE: none)")
        .def_readwrite("up", &Light::up,
                       "spot with a texture, projector: the image's top, unit, across the axis")
        .def_readwrite("half_width", &Light::half_width,
                       "projector: the frustum's half width at unit distance (a tangent)")
        .def_readwrite("half_height", &Light::half_height, "projector: ... and half height")
        .def_readwrite("projects_intensity", &Light::projects_intensity,
                       "projector: intensity x texture is the intensity (pbrt-v4's projection "
                       "light), not Mitsuba's irradiance at unit distance");

    py::class_<PixelFilter> filter(m, "PixelFilter");
    py::enum_<PixelFilter::Kind>(filter, "Kind")
        .value("Box", PixelFilter::Kind::Box)
        .value("Tent", PixelFilter::Kind::Tent)
        .value("Gaussian", PixelFilter::Kind::Gaussian);
    keyword_init(filter);
    filter.def_readwrite("kind", &PixelFilter::kind)
        .def_readwrite("radius", &PixelFilter::radius)
        .def_readwrite("sigma", &PixelFilter::sigma);
    py::class_<Camera> camera(m, "Camera",
                              "A thin-lens camera (aperture 0: a pinhole), or with orthographic "
                              "parallel rays from a view_width x view_height film at look_from.");
    keyword_init(camera);
    camera.def_readwrite("look_from", &Camera::look_from)
        .def_readwrite("look_at", &Camera::look_at)
        .def_readwrite("up", &Camera::up)
        .def_readwrite("vfov", &Camera::vfov)
        .def_readwrite("aperture", &Camera::aperture)
        .def_readwrite("focus_distance", &Camera::focus_distance)
        .def_readwrite("mirror", &Camera::mirror)
        .def_readwrite("orthographic", &Camera::orthographic)
        .def_readwrite("view_height", &Camera::view_height)
        .def_readwrite("view_width", &Camera::view_width)
        .def_readwrite("filter", &Camera::filter);

    py::class_<Background> background(
        m, "Background", "A constant radiance, or an environment image scaled by it.");
    py::enum_<Background::Kind>(background, "Kind")
        .value("Constant", Background::Kind::Constant)
        .value("Environment", Background::Kind::Environment);
    py::enum_<Background::Mapping>(background, "Mapping")
        .value("LatLong", Background::Mapping::LatLong)
        .value("EqualArea", Background::Mapping::EqualArea);
    keyword_init(background);
    using Rows = std::array<Vec3, 3>;
    background.def_readwrite("kind", &Background::kind)
        .def_readwrite("radiance", &Background::radiance)
        .def_readwrite("image", &Background::image)
        .def_readwrite("mapping", &Background::mapping)
        .def_readwrite("rotation", &Background::rotation)
        .def_readwrite("rows_at_poles", &Background::rows_at_poles)
        .def_property(
            "to_world",
            [](const Background& b) -> std::optional<Rows> {
                if (!b.frame) return std::nullopt;
                const Frame& f = *b.frame;
                return Rows{Vec3{f.s.x, f.t.x, f.n.x}, Vec3{f.s.y, f.t.y, f.n.y},
                            Vec3{f.s.z, f.t.z, f.n.z}};
            },
            [](Background& b, const std::optional<Rows>& rows) {
                if (!rows) {
                    b.frame.reset();
                    return;
                }
                const Rows& r = *rows;
                b.frame = Frame{{r[0].x, r[1].x, r[2].x}, {r[0].y, r[1].y, r[2].y},
                                {r[0].z, r[1].z, r[2].z}};
            },
            "The map's frame as a 3 x 3 rotation (rows; its columns the map's axes in world "
            "space), or None for the world's own axes.");

    py::class_<RenderSettings> settings(m, "RenderSettings",
                                        "A scene's default size, samples and depth.");
    keyword_init(settings);
    settings.def_readwrite("width", &RenderSettings::width)
        .def_readwrite("height", &RenderSettings::height)
        .def_readwrite("spp", &RenderSettings::spp)
        .def_readwrite("max_depth", &RenderSettings::max_depth)
        .def_property(
            "sampler", [](const RenderSettings& r) { return std::string(to_string(r.sampler)); },
            [](RenderSettings& r, const std::string& name) {
                const std::optional<SamplerKind> kind = parse_sampler(name);
                if (!kind)
                    throw py::value_error("sampler: expected 'independent' or 'sobol', got '" +
                                          name + "'");
                r.sampler = *kind;
            },
            "'independent' or 'sobol': where a render's random numbers come from");

    py::enum_<MediumBoundaries>(m, "MediumBoundaries")
        .value("Nested", MediumBoundaries::Nested)
        .value("Interface", MediumBoundaries::Interface);

    using S = PyScene;
    py::class_<S, std::shared_ptr<S>>(
        m, "Scene",
        "A scene: loaded with load_scene(), or built here with the same builders as in C++ "
        "(ids returned by one add_ are passed to the next).")
        .def(py::init<>())
        .def_property_readonly("path", [](const S& s) { return s.path; },
                               "The file it was loaded from ('' if built in Python).")
        .def_property(
            "camera", [](S& s) -> Camera& { return s.scene.camera; },
            [](S& s, const Camera& c) { s.scene.camera = c; }, py::return_value_policy::reference_internal)
        .def_property(
            "render", [](S& s) -> RenderSettings& { return s.scene.render; },
            [](S& s, const RenderSettings& r) { s.scene.render = r; },
            py::return_value_policy::reference_internal)
        .def_property(
            "background", [](S& s) -> Background& { return s.scene.background; },
            [](S& s, const Background& b) { s.scene.background = b; },
            py::return_value_policy::reference_internal)
        .def_property(
            "medium_boundaries", [](const S& s) { return s.scene.medium_boundaries; },
            [](S& s, MediumBoundaries b) { s.scene.medium_boundaries = b; },
            "How crossing a medium boundary changes the medium: Nested (a stack) or Interface "
            "(Mitsuba's rule).")
        .def_property(
            "geometric_side_test", [](const S& s) { return s.scene.geometric_side_test; },
            [](S& s, bool on) { s.scene.geometric_side_test = on; },
            "Whether sampled and evaluated directions must also lie on the geometric surface's "
            "side their lobe says (False: the shading frame alone decides, as pbrt-v4 and "
            "Mitsuba 3).")
        .def("add_texture",
             [](S& s, const Texture& t) {
                 s.begin_change();
                 return s.scene.add_texture(t);
             },
             py::arg("texture"), "Adds a texture; returns its id.")
        .def("add_solid",
             [](S& s, Vec3 c) {
                 s.begin_change();
                 return s.scene.add_solid(c);
             },
             py::arg("color"), "Adds a constant-colour texture; returns its id.")
        .def("add_image",
             [](S& s, const py::array_t<float, py::array::c_style | py::array::forcecast>& a,
                const std::string& name) {
                 s.begin_change();
                 return s.scene.add_image(image_data(a, name));
             },
             py::arg("pixels"), py::arg("name") = "python",
             "Adds an image (linear RGB, shape (height, width, 3), row 0 at the top) for image "
             "textures and environment maps; returns its id.")
        .def("add_material",
             [](S& s, const Material& mat) {
                 s.begin_change();
                 return s.scene.add_material(mat);
             },
             py::arg("material"), "Adds a material; returns its id.")
        .def("add_medium",
             [](S& s, const std::string& name, const py::object& density, TextureId albedo) {
                 const Color sigma_t = py::isinstance<py::sequence>(density)
                                           ? density.cast<Vec3>()
                                           : Color(density.cast<float>());
                 s.begin_change();
                 return s.scene.add_medium(name, sigma_t, albedo);
             },
             py::arg("name"), py::arg("density"), py::arg("albedo"),
             "Adds a homogeneous medium (extinction `density` per unit, a number or one per "
             "channel (r, g, b); scattering albedo texture); returns its id.")
        .def("interface_material",
             [](S& s) {
                 s.begin_change();
                 return s.scene.interface_material();
             },
             "The pass-through material of medium boundaries.")
        .def("add_sphere",
             [](S& s, const Sphere& sp, const Transform& t) {
                 s.begin_change();
                 s.scene.add_sphere(sp, t);
             },
             py::arg("sphere"), py::arg("to_world") = Transform())
        .def("add_quad",
             [](S& s, const Quad& q, const Transform& t) {
                 s.begin_change();
                 s.scene.add_quad(q, t);
             },
             py::arg("quad"), py::arg("to_world") = Transform())
        .def("add_box",
             [](S& s, Vec3 lo, Vec3 hi, MaterialId mat, MediumId interior, const Transform& t) {
                 s.begin_change();
                 s.scene.add_box(lo, hi, mat, interior, t);
             },
             py::arg("lo"), py::arg("hi"), py::arg("material"), py::arg("interior") = kNone,
             py::arg("to_world") = Transform(), "Adds six outward-facing quads spanning [lo, hi].")
        .def("add_mesh",
             [](S& s, const py::handle& positions, const py::handle& indices, MaterialId mat,
                const py::handle& normals, const py::handle& uvs, MediumId interior,
                const std::string& name, const Transform& t, const py::dict& attributes) {
                 auto idx = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(indices);
                 if (!idx || (!(idx.ndim() == 2 && idx.shape(1) == 3) && idx.ndim() != 1))
                     throw py::value_error("indices: expected an array of shape (n, 3)");
                 if (idx.size() % 3 != 0)
                     throw py::value_error("indices: expected a multiple of 3 indices");
                 std::vector<uint32_t> index(idx.size());
                 for (py::ssize_t i = 0; i < idx.size(); ++i) {
                     const int64_t v = idx.data()[i];
                     // Out-of-range indices are the builder's to skip: map negatives there too.
                     index[i] = v < 0 || v > int64_t(0xfffffffe) ? 0xffffffffu : uint32_t(v);
                 }
                 auto p = rows<Point3>(positions, 3, "positions");
                 auto n = rows<Normal3>(normals, 3, "normals");
                 auto uv = rows<Vec2>(uvs, 2, "uvs");
                 if ((!n.empty() && n.size() != p.size()) || (!uv.empty() && uv.size() != p.size()))
                     throw py::value_error("normals and uvs: one per position");
                 std::vector<MeshAttribute> attrs;
                 for (const auto& [key, value] : attributes) {
                     MeshAttribute a;
                     a.name = py::cast<std::string>(key);
                     a.per_face = a.name.rfind("face_", 0) == 0;
                     if (!a.per_face && a.name.rfind("vertex_", 0) != 0)
                         throw py::value_error("attributes: '" + a.name +
                                               "' does not start with vertex_ or face_");
                     using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;
                     auto v = Floats::ensure(value);
                     if (!v || !(v.ndim() == 1 || (v.ndim() == 2 && v.shape(1) == 3)))
                         throw py::value_error("attributes: '" + a.name +
                                               "': expected an array of shape (k,) or (k, 3)");
                     a.channels = v.ndim() == 1 ? 1 : 3;
                     const py::ssize_t k = v.shape(0);
                     if (size_t(k) != (a.per_face ? index.size() / 3 : p.size()))
                         throw py::value_error("attributes: '" + a.name +
                                               "': expected one value per " +
                                               (a.per_face ? "triangle" : "position"));
                     const float* x = v.data();
                     for (py::ssize_t i = 0; i < k; ++i)
                         a.values.push_back(a.channels == 1
                                                ? Color(x[i])
                                                : Color(x[3 * i], x[3 * i + 1], x[3 * i + 2]));
                     attrs.push_back(std::move(a));
                 }
                 s.begin_change();
                 Mesh mesh;
                 mesh.name = name;
                 mesh.material = mat;
                 mesh.interior = interior;
                 return s.scene.add_mesh(mesh, p, n, uv, index, t, std::move(attrs));
             },
             py::arg("positions"), py::arg("indices"), py::arg("material"),
             py::arg("normals") = py::none(), py::arg("uvs") = py::none(),
             py::arg("interior") = kNone, py::arg("name") = "", py::arg("to_world") = Transform(),
             py::arg("attributes") = py::dict(),
             "Adds a triangle mesh from arrays: positions (n, 3), indices (m, 3) counter-clockwise "
             "seen from the front, optional normals (n, 3) and uvs (n, 2), and attributes: a dict "
             "of name to one value per position (\"vertex_NAME\") or per triangle "
             "(\"face_NAME\"), shape (k,) or (k, 3), read by TextureKind.MeshAttribute. "
             "Degenerate triangles are skipped (with their face values); returns how many were.")
        .def("add_light",
             [](S& s, const Light& l) {
                 s.begin_change();
                 s.scene.lights.push_back(l);
             },
             py::arg("light"), "Adds a point, spot or directional light.")
        .def("check", [](const S& s) { check_scene(s.scene); },
             "Raises SceneError if the scene refers to what it does not hold.")
        .def("info",
             [](const S& s) {
                 const Scene& sc = s.scene;
                 const Aabb b = sc.bounds();
                 py::dict d;
                 d["path"] = s.path;
                 d["primitives"] = sc.primitive_count();
                 d["triangles"] = sc.triangles.size();
                 d["quads"] = sc.quads.size();
                 d["spheres"] = sc.spheres.size();
                 d["meshes"] = sc.meshes.size();
                 d["vertices"] = sc.positions.size();
                 d["emitters"] = collect_emitters(sc).size();
                 d["lights"] = sc.lights.size();
                 d["materials"] = sc.materials.size();
                 d["textures"] = sc.textures.size();
                 d["images"] = sc.images.size();
                 d["media"] = sc.media.size();
                 d["bounds"] = py::make_tuple(b.lo, b.hi);
                 d["width"] = sc.render.width;
                 d["height"] = sc.render.height;
                 d["spp"] = sc.render.spp;
                 d["max_depth"] = sc.render.max_depth;
                 d["sampler"] = to_string(sc.render.sampler);
                 return d;
             },
             "Counts, bounds and render defaults, as `wavetrace info` prints them.")
        .def("__repr__", [](const S& s) {
            return "<wavetrace.Scene " + (s.path.empty() ? std::string("built in Python") : s.path) +
                   ": " + std::to_string(s.scene.primitive_count()) + " primitives>";
        });

    m.def("load_scene", &load, py::arg("path"), py::arg("camera") = "",
          py::arg("params") = std::map<std::string, std::string>{},
          py::arg("asset_root") = py::none(),
          "Loads a scene file: our JSON, Mitsuba 3 XML (.xml; params are its $parameters), "
          "pbrt-v4 (.pbrt) or glTF 2.0 (.gltf, .glb; camera: the one to render through); with "
          "asset_root, every file read must lie inside it. Raises "
          "SceneError naming the file and the place; warnings become UserWarnings.");
}

}  // namespace wavetrace::python
