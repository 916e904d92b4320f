// JSON scene files -> Scene. The format is documented in docs/scene-format.md; every check
// here has a matching sentence there.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

#include "bsdfs/principled.h"
#include "files/confinement.h"
#include "files/input_file.h"
#include "files/output_file.h"
#include "formats/gltf_json.h"
#include "formats/json_reader.h"
#include "formats/ply_write.h"
#include "formats/serialized_mesh.h"
#include "formats/volume_file.h"
#include "loaders/mesh_file.h"
#include "mitsuba/mitsuba_xml.h"
#include "pbrt/translate.h"
#include "scene/material_lookup.h"
#include "scene/named_metals.h"
#include "scene/tessellate.h"
#include "wavetrace/image/image.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace fs = std::filesystem;
using json_reader::Object;
using json_reader::Value;

namespace {

constexpr float kMaxCoordinate = 1e7f;  // beyond this float spacing exceeds ~1 unit

class Loader {
  public:
    Loader(const fs::path& path, const LoadOptions& options)
        : path_(path), file_(path.string()), options_(options) {}
    Loader(const Loader&) = delete;
    Loader& operator=(const Loader&) = delete;
    ~Loader() { json_reader::release(json_); }  // freed without allocating: see release()

    Scene load() {
        if (!options_.camera.empty())
            throw SceneError(file_ + ": --camera chooses among a glTF file's cameras; a JSON "
                             "scene has one");
        try {
            check_input_file(path_, kMaxSceneFileBytes, "scene files");
        } catch (const std::runtime_error& e) {
            throw SceneError(file_ + ": cannot open scene file: " + e.what());
        }
        if (std::string why = Confinement{{}, options_.asset_root}.problem(path_); !why.empty())
            throw SceneError(file_ + ": " + why);
        std::string text;
        try {
            text = read_input_file(path_);
        } catch (const std::runtime_error& e) {
            throw SceneError(file_ + ": cannot read scene file: " + e.what());
        }
        json_reader::Document document = json_reader::parse(text, file_);
        std::string().swap(text);  // its memory back before the scene is built
        return build(std::move(document.root));
    }

    // A scene document already in memory (a Mitsuba XML or pbrt file translated into our
    // JSON); its file names are relative to path_'s folder, but those of `meshes`, which are
    // taken from there.
    Scene build(nlohmann::json document, const std::map<std::string, PbrtMesh>* meshes = nullptr) {
        json_ = std::move(document);
        memory_meshes_ = meshes;
        Object root(Value(json_, file_, ""));
        root.only({"description", "render", "camera", "background", "lights", "materials", "media",
                   "medium_boundaries", "geometric_side_test", "objects"});
        scene_.name = path_.stem().string();
        if (auto v = root.optional("description")) v->string();
        if (auto v = root.optional("render")) read_render(*v);
        read_camera(root.required("camera"));
        if (auto v = root.optional("background")) read_background(*v);
        if (auto v = root.optional("lights")) read_lights(*v);
        if (auto v = root.optional("materials")) read_materials(*v);
        if (auto v = root.optional("media")) read_media(*v);
        if (auto v = root.optional("medium_boundaries")) {
            const std::string rule = v->string();
            if (rule == "interface") scene_.medium_boundaries = MediumBoundaries::Interface;
            else if (rule != "nested")
                v->fail("unknown rule \"" + rule + "\" (expected nested or interface)");
        }
        if (auto v = root.optional("geometric_side_test"))
            scene_.geometric_side_test = v->boolean();
        Value objects = root.required("objects");
        for (size_t i = 0; i < objects.size(); ++i) read_object(objects[i], Transform{});
        root.finish();
        if (skipped_triangles_ > 0)
            warn(std::to_string(skipped_triangles_) + " degenerate triangles skipped");
        return std::move(scene_);
    }

    // A glTF 2.0 file as a whole scene (docs/scene-format.md, "glTF files as scenes"): its
    // meshes with their materials, the first camera of its default scene (or one framing the
    // model), its punctual lights.
    Scene load_gltf(bool binary) {
        scene_.name = path_.stem().string();
        MeshFile mesh;
        GltfPlacements placed;
        try {
            mesh = read_mesh_file(path_, options_.asset_root);
            placed = gltf_placements(path_, binary);
        } catch (const std::exception& e) {
            throw SceneError(file_ + ": " + e.what());
        }
        json_ = nlohmann::json::object();
        add_mesh_parts(mesh, path_, kNone, Transform{}, Value(json_, file_, "/materials"));
        for (const std::string& w : mesh.warnings) warn(w);
        for (const std::string& w : placed.warnings) warn(w);
        const Aabb box = scene_.bounds();
        if (box.empty()) throw SceneError(file_ + ": no triangles in the default scene");
        if (!(max_component(abs(box.lo)) <= kMaxCoordinate &&
              max_component(abs(box.hi)) <= kMaxCoordinate))
            throw SceneError(file_ + ": the model reaches beyond +-1e7");
        Camera& c = scene_.camera;
        RenderSettings& r = scene_.render;
        r.width = 800;
        r.height = 600;
        auto chosen = placed.cameras.begin();
        if (!options_.camera.empty()) {
            chosen = std::find_if(placed.cameras.begin(), placed.cameras.end(),
                                  [&](const GltfCamera& g) { return g.name == options_.camera; });
            if (chosen == placed.cameras.end()) {
                std::string names;
                for (const GltfCamera& g : placed.cameras)
                    names += (names.empty() ? "" : ", ") + ("\"" + g.name + "\"");
                throw SceneError(file_ + ": no camera named \"" + options_.camera +
                                 "\" (the file has " + (names.empty() ? "none" : names) + ")");
            }
        }
        if (!placed.cameras.empty()) {
            const GltfCamera& g = *chosen;
            c.look_from = g.position;
            c.look_at = g.position + g.forward;
            c.up = g.up;
            c.vfov = g.yfov_degrees;
            c.orthographic = g.orthographic;
            c.view_width = g.view_width;
            c.view_height = g.view_height;
            if (g.aspect > 0.0f)
                r.height = std::clamp(static_cast<int>(std::lround(800.0f / g.aspect)), 1, 8000);
            if (max_component(abs(c.look_from)) > kMaxCoordinate)
                throw SceneError(file_ + ": " + g.pointer + ": the camera is beyond +-1e7");
            if (placed.cameras.size() > 1 && options_.camera.empty())
                warn(std::to_string(placed.cameras.size()) + " cameras; rendering through the "
                     "first, \"" + g.name + "\" (" + g.pointer + "); --camera chooses");
        } else {
            // The whole model in view from its front (+z, glTF's forward), a little above.
            const Point3 centre = 0.5f * (box.lo + box.hi);
            const float radius = std::max(0.5f * length(box.hi - box.lo), 1e-6f);
            const float distance = 1.1f * radius / std::sin(radians(0.5f * c.vfov));
            c.look_at = centre;
            c.look_from = centre + distance * normalize(Vec3{0.0f, 0.25f, 1.0f});
            warn("no camera in the default scene; framing the model from +z");
        }
        for (const GltfLight& g : placed.lights) {
            Light l;
            l.position = g.position;
            l.intensity = g.color;
            if (g.kind == GltfLight::Kind::Spot) {
                l.kind = Light::Kind::Spot;
                l.direction = g.direction;
                l.cutoff_degrees = g.outer_degrees;
                l.falloff_start_degrees = g.inner_degrees;
                l.falloff = Light::Falloff::Smoothstep;
            } else if (g.kind == GltfLight::Kind::Directional) {
                l.kind = Light::Kind::Directional;
                l.direction = g.direction;
            }
            if (max_component(abs(l.position)) > kMaxCoordinate)
                throw SceneError(file_ + ": " + g.pointer + ": the light is beyond +-1e7");
            if (g.has_range)
                warn(g.pointer + ": range ignored (lights fall off with the inverse square)");
            scene_.lights.push_back(l);
        }
        const bool emits = std::any_of(scene_.materials.begin(), scene_.materials.end(),
                                       [](const Material& m) { return m.is_emissive(); });
        if (scene_.lights.empty() && !emits)
            warn("no lights and no emissive materials: the image will be black (glTF viewers "
                 "add an environment; a JSON scene can hold this file as a mesh under one)");
        if (skipped_triangles_ > 0)
            warn(std::to_string(skipped_triangles_) + " degenerate triangles skipped");
        return std::move(scene_);
    }

  private:
    void warn(const std::string& message) const {
        std::string full = file_ + ": warning: " + message;
        if (options_.warn)
            options_.warn(full);
        else
            std::cerr << full << "\n";
    }

    // A path in the scene file, relative to the scene file's folder.
    fs::path resolve(const Value& v) const {
        const std::string name = v.string();
        if (name.empty()) v.fail("expected a file name, got \"\"");
        // The file system ends a name at a NUL: "a.png\u0000.jpg" would open a.png.
        if (name.find('\0') != std::string::npos)
            v.fail("a file name cannot hold a NUL character (\\u0000)");
        fs::path p = name;
        if (!p.is_absolute()) p = path_.parent_path() / p;
        if (std::string why = Confinement{{}, options_.asset_root}.problem(p); !why.empty())
            v.fail(p.string() + ": " + why);
        return p;
    }

    void read_render(const Value& v) {
        Object o(v);
        RenderSettings& r = scene_.render;
        if (auto x = o.optional("width")) r.width = x->integer(1, kMaxImageSide);
        if (auto x = o.optional("height")) r.height = x->integer(1, kMaxImageSide);
        if (auto x = o.optional("spp")) r.spp = x->integer(1, kMaxSpp);
        if (auto x = o.optional("max_depth")) r.max_depth = x->integer(1, kMaxDepth);
        if (auto x = o.optional("sampler")) {
            const std::string name = x->string();
            const std::optional<SamplerKind> kind = parse_sampler(name);
            if (!kind)
                x->fail("expected \"independent\", \"sobol\" or \"zsobol\", got \"" + name + "\"");
            r.sampler = *kind;
        }
        o.finish();
        if (static_cast<long long>(r.width) * r.height > kMaxPixels)
            v.fail(
                "width x height = " + std::to_string(static_cast<long long>(r.width) * r.height) +
                " pixels exceeds the limit of " + std::to_string(kMaxPixels));
    }

    Vec3 point(const Value& v) const {
        Vec3 p = v.vec3();
        if (max_component(abs(p)) > kMaxCoordinate)
            v.fail("coordinate beyond +-1e7, got " + v.describe());
        return p;
    }

    void read_camera(const Value& v) {
        Object o(v);
        Camera& c = scene_.camera;
        c.look_from = point(o.required("look_from"));
        Value at = o.required("look_at");
        c.look_at = point(at);
        // A viewing direction shorter than this cannot be normalized in float: the camera frame
        // would be infinite or NaN.
        const float dist = length(c.look_at - c.look_from);
        if (!(dist > 1e-6f * std::max(1.0f, max_component(abs(c.look_from)))))
            at.fail("look_at must differ from look_from");
        auto up = o.optional("up");
        if (up) c.up = up->nonzero_vec3();
        if (length(cross(normalize(c.up), normalize(c.look_at - c.look_from))) < 1e-6f) {
            if (up) up->fail("up must not be parallel to the viewing direction");
            v.fail("the viewing direction is parallel to the default up [0, 1, 0]; set \"up\"");
        }
        if (auto x = o.optional("vfov")) {
            if (!x->is_number() || !(x->number() > 0.0f && x->number() <= 179.0f))
                x->fail("expected a number in (0, 179], got " + x->describe());
            c.vfov = x->number();
        }
        if (auto x = o.optional("type")) {
            const std::string type = x->string();
            if (type == "orthographic")
                c.orthographic = true;
            else if (type != "perspective")
                x->fail("unknown camera type \"" + type +
                        "\" (expected perspective or orthographic)");
        }
        // Orthographic: the film's extent in world units (coordinates stay within 1e7).
        auto extent = [](const Value& x) {
            if (!x.is_number() || !(x.number() > 0.0f && x.number() <= kMaxCoordinate))
                x.fail("expected a number in (0, 1e7], got " + x.describe());
            return x.number();
        };
        for (const char* key : {"view_height", "view_width"})
            if (auto x = o.optional(key)) {
                if (!c.orthographic) x->fail(std::string(key) + " is an orthographic camera's");
                (std::string_view(key) == "view_height" ? c.view_height : c.view_width) =
                    extent(*x);
            }
        if (auto x = o.optional("aperture")) {
            c.aperture = x->non_negative();
            if (c.orthographic && c.aperture > 0.0f) x->fail("an orthographic camera has no lens");
        }
        if (auto x = o.optional("focus_distance")) c.focus_distance = x->positive();
        if (auto x = o.optional("mirror")) c.mirror = x->boolean();
        if (auto x = o.optional("filter")) c.filter = read_filter(*x);
        o.finish();
    }

    // The pixel filter (docs/scene-format.md, "camera"): its type, radius and deviation.
    static PixelFilter read_filter(const Value& v) {
        Object o(v);
        PixelFilter f;
        const Value type = o.required("type");
        const std::string kind = type.string();
        if (kind == "box") {
            f.kind = PixelFilter::Kind::Box;
        } else if (kind == "tent") {
            f.kind = PixelFilter::Kind::Tent;
            f.radius = 1.0f;
        } else if (kind == "gaussian") {
            f.kind = PixelFilter::Kind::Gaussian;
            f.radius = 2.0f;
        } else {
            type.fail("unknown filter type \"" + kind + "\" (expected box, tent or gaussian)");
        }
        auto bounded = [](const Value& x, float hi) {
            if (!x.is_number() || !(x.number() > 0.0f && x.number() <= hi))
                x.fail("expected a number in (0, " + std::to_string(static_cast<int>(hi)) +
                       "], got " + x.describe());
            return x.number();
        };
        if (auto x = o.optional("radius")) f.radius = bounded(*x, 8.0f);
        if (kind == "gaussian") {
            if (auto x = o.optional("sigma")) f.sigma = bounded(*x, 8.0f);
        }
        o.finish();
        return f;
    }

    void read_background(const Value& v) {
        Background& bg = scene_.background;
        if (!v.is_object()) {
            bg.kind = Background::Kind::Constant;
            bg.radiance = v.color();
            return;
        }
        Object o(v);
        std::string type = o.required("type").string();
        if (type == "constant") {
            bg.kind = Background::Kind::Constant;
            bg.radiance = o.required("radiance").color();
        } else if (type == "environment") {
            bg.kind = Background::Kind::Environment;
            Value file = o.required("file");
            bg.image = scene_.add_image(read_image_at(file));
            bg.radiance = Vec3(1.0f);
            if (auto x = o.optional("scale")) bg.radiance = x->color();
            std::string mapping = "latlong";
            if (auto x = o.optional("mapping")) {
                mapping = x->string();
                if (mapping == "equal_area") bg.mapping = Background::Mapping::EqualArea;
                else if (mapping != "latlong")
                    x->fail("unknown mapping \"" + mapping + "\" (expected latlong or equal_area)");
            }
            if (bg.mapping == Background::Mapping::LatLong) {
                if (auto x = o.optional("rotation")) bg.rotation = x->number();
                if (auto x = o.optional("rows_at_poles")) bg.rows_at_poles = x->boolean();
            } else {
                for (const char* key : {"rotation", "rows_at_poles"})
                    if (auto x = o.optional(key))
                        x->fail(std::string("\"") + key + "\" applies to latlong maps only "
                                "(turn an equal_area map with \"to_world\")");
                const ImageData& img = scene_.images[bg.image];
                if (img.width != img.height)
                    file.fail("an equal_area map must be square; '" + resolve(file).string() +
                              "' is " + std::to_string(img.width) + " x " +
                              std::to_string(img.height));
            }
            if (auto x = o.optional("illuminance")) {
                // Scaled so that a surface facing the map's pole receives this illuminance
                // (pbrt-v4's `illuminance`), then by `scale`.
                const float target = x->positive();
                const double e = environment_illuminance(bg, scene_.images[bg.image]);
                const float k = static_cast<float>(target / e);
                if (!(e > 0) || !std::isfinite(k))
                    x->fail("the map '" + resolve(file).string() + "' is black above its "
                            "horizon: no scale gives it an illuminance of " + x->describe());
                bg.radiance = bg.radiance * k;
            }
            if (auto x = o.optional("to_world")) bg.frame = rotation_frame(*x);
        } else {
            o.required("type").fail("unknown background type \"" + type +
                                    "\" (expected constant or environment)");
        }
        o.finish();
    }

    // A 3 x 3 rotation (rows; possibly mirrored) as the frame of its columns: the map's own
    // axes in world space.
    static Frame rotation_frame(const Value& v) {
        if (!v.is_array() || v.size() != 3)
            v.fail("expected a 3 x 3 matrix [[a, b, c], [d, e, f], [g, h, i]], got " + v.describe());
        const Vec3 rows[3] = {v[0].vec3(), v[1].vec3(), v[2].vec3()};
        const Frame f{{rows[0].x, rows[1].x, rows[2].x},
                      {rows[0].y, rows[1].y, rows[2].y},
                      {rows[0].z, rows[1].z, rows[2].z}};
        if (!f.is_orthonormal(1e-4f))
            v.fail("expected a rotation (orthonormal columns), got " + v.describe());
        return f;
    }

    ImageData read_image_at(const Value& file, bool raw = false) const {
        fs::path p = resolve(file);
        std::error_code ec;
        const fs::file_status st = fs::status(p, ec);
        if (st.type() == fs::file_type::not_found)
            file.fail("cannot open image '" + p.string() + "': no such file");
        if (ec) file.fail("cannot open image '" + p.string() + "': " + ec.message());
        try {
            return read_image(p, raw ? ImageChannels::Raw : ImageChannels::Linear);
        } catch (const ImageError& e) {
            file.fail(e.what());
        } catch (const std::bad_alloc&) {
            file.fail("out of memory reading image '" + p.string() + "'");
        }
    }

    // Texture `id`, read at `v` for something that is no mesh's surface, which must not read a
    // mesh attribute.
    TextureId off_meshes(TextureId id, const Value& v) const {
        if (texture_reads_attributes(scene_, id))
            v.fail("a mesh attribute is read only on a mesh's surface");
        return id;
    }

    // A texture: a colour [r, g, b] (or a grey number), or an object with a "type". Reflectances
    // (albedos) must not exceed 1 in any channel; radiances may.
    enum class Range { Reflectance, Radiance };
    TextureId read_texture(const Value& v, Range range) {
        auto colour = [range](const Value& c) {
            return range == Range::Reflectance ? c.reflectance() : c.color();
        };
        if (!v.is_object()) return scene_.add_solid(colour(v));
        Object o(v);
        Value type_value = o.required("type");
        std::string type = type_value.string();
        Texture t;
        if (type == "solid") {
            t.kind = TextureKind::Solid;
            t.color = colour(o.required("color"));
        } else if (type == "checker") {
            t.kind = TextureKind::Checker;
            t.scale = o.required("scale").positive();
            t.even = read_texture(o.required("even"), range);
            t.odd = read_texture(o.required("odd"), range);
        } else if (type == "noise") {
            t.kind = TextureKind::Noise;
            t.scale = o.required("scale").positive();
            t.color = Vec3(1.0f);
            if (auto x = o.optional("color")) t.color = colour(*x);
        } else if (type == "product") {
            t.kind = TextureKind::Product;
            Value factors = o.required("factors");
            if (!factors.is_array() || factors.size() != 2)
                factors.fail("expected two textures, got " + factors.describe());
            for (size_t k = 0; k < 2; ++k) t.factors[k] = read_texture(factors[k], range);
        } else if (type == "mesh_attribute") {
            t.kind = TextureKind::MeshAttribute;
            Value name = o.required("name");
            t.attribute = name.string();
            if (t.attribute.rfind("vertex_", 0) != 0 && t.attribute.rfind("face_", 0) != 0)
                name.fail("expected a name that starts with \"vertex_\" or \"face_\", got " +
                          name.describe());
            if (auto x = o.optional("scale")) t.scale = x->number();
        } else if (type == "uv_checker") {
            t.kind = TextureKind::UvChecker;
            t.scale = o.required("scale").positive();
            t.even = read_texture(o.required("even"), range);
            t.odd = read_texture(o.required("odd"), range);
            if (auto x = o.optional("uv_transform")) read_uv_transform(*x, t);
        } else if (type == "image") {
            t.kind = TextureKind::Image;
            bool raw = false;
            if (auto x = o.optional("raw")) raw = x->boolean();
            t.image = scene_.add_image(read_image_at(o.required("file"), raw));
            if (auto x = o.optional("uv_transform")) read_uv_transform(*x, t);
            if (auto x = o.optional("factor")) t.factor = colour(*x);
            if (auto x = o.optional("filter")) {
                const std::string f = x->string();
                if (f == "bilinear") t.filter = TextureFilter::Bilinear;
                else if (f == "nearest") t.filter = TextureFilter::Nearest;
                else x->fail("expected \"bilinear\" or \"nearest\", got \"" + f + "\"");
            }
            if (auto x = o.optional("wrap")) {  // one mode, or [along u, along v]
                if (x->is_array()) {
                    if (x->size() != 2) x->fail("expected a wrap mode or two, [along u, along v]");
                    t.wrap_u = wrap_mode((*x)[0]);
                    t.wrap_v = wrap_mode((*x)[1]);
                } else {
                    t.wrap_u = t.wrap_v = wrap_mode(*x);
                }
            }
        } else if (type == "grid") {
            t.kind = TextureKind::Grid;
            t.grid = read_volume_grid(v, range, &o);
        } else {
            type_value.fail("unknown texture type \"" + type +
                            "\" (expected solid, checker, uv_checker, noise, image or grid)");
        }
        o.finish();
        return scene_.add_texture(t);
    }

    static TextureWrap wrap_mode(const Value& m) {
        const std::string w = m.string();
        if (w == "repeat") return TextureWrap::Repeat;
        if (w == "mirror") return TextureWrap::Mirror;
        if (w == "clamp") return TextureWrap::Clamp;
        if (w == "black") return TextureWrap::Black;
        m.fail("expected \"repeat\", \"mirror\", \"clamp\" or \"black\", got \"" + w + "\"");
    }

    // A volume grid: {"file": a Mitsuba .vol file, "value": a number or a colour (one voxel), or
    // "resolution" and "values"; "transform": steps placing its unit cube in the world,
    // "filter", "wrap", "file_bounds"};
    // reflectances must not exceed 1. `in` is the object it is part of (a grid texture), else
    // the grid is an object of its own.
    VolumeGridId read_volume_grid(const Value& v, Range range, Object* in = nullptr) {
        std::optional<Object> own;
        if (!in) in = &own.emplace(v);
        VolumeGrid g;
        Aabb bounds;
        if (auto values = in->optional("values")) {
            // Inline voxels (a pbrt-v4 grid medium's density), x fastest.
            const Value resolution = in->required("resolution");
            if (resolution.size() != 3) resolution.fail("expected [nx, ny, nz]");
            uint64_t voxels = 1;
            for (size_t a = 0; a < 3; ++a) {
                g.res[a] = resolution[a].integer(1, 1 << 20);
                voxels *= static_cast<uint64_t>(g.res[a]);
            }
            const size_t n = values->size();
            g.channels = n == voxels ? 1 : 3;
            if (n != voxels && n != 3 * voxels)
                values->fail("expected " + std::to_string(voxels) + " or " +
                             std::to_string(3 * voxels) +
                             " numbers (one or three per voxel), got " + std::to_string(n));
            g.values.resize(n);
            for (size_t i = 0; i < n; ++i)
                g.values[i] = range == Range::Reflectance ? (*values)[i].in_range(0.0f, 1.0f)
                                                          : (*values)[i].non_negative();
        } else if (auto value = in->optional("value")) {
            const Color c = range == Range::Reflectance ? value->reflectance() : value->color();
            g.res[0] = g.res[1] = g.res[2] = 1;
            g.channels = value->is_number() ? 1 : 3;
            g.values =
                value->is_number() ? std::vector<float>{c.x} : std::vector<float>{c.x, c.y, c.z};
        } else {
            const Value file = in->required("file");
            const fs::path p = resolve(file);
            try {
                g = read_volume_file(p, &bounds);
            } catch (const std::runtime_error& e) {
                file.fail("volume grid '" + p.string() + "' " + e.what());
            } catch (const std::bad_alloc&) {
                file.fail("out of memory reading volume grid '" + p.string() + "'");
            }
            if (range == Range::Reflectance)
                for (const float x : g.values)
                    if (x > 1.0f)
                        file.fail("volume grid '" + p.string() + "' holds " + std::to_string(x) +
                                  "; a reflectance grid's values must not exceed 1");
        }
        if (auto x = in->optional("transform")) g.to_local = read_transform(*x).inverse();
        // The box the file states, in the grid's frame, mapped onto the unit cube.
        if (auto x = in->optional("file_bounds"); x && x->boolean()) {
            const Vec3 size = bounds.hi - bounds.lo;
            if (!(size.x > 0 && size.y > 0 && size.z > 0) || !is_finite(bounds.lo) ||
                !is_finite(size))
                x->fail("the grid file's bounding box is empty or not finite");
            const Transform to_unit = Transform::scale({1 / size.x, 1 / size.y, 1 / size.z}) *
                                      Transform::translate(-bounds.lo);
            if (!to_unit.is_well_conditioned(kMaxCoordinate))
                x->fail("the grid file's bounding box scales beyond [1e-7, 1e7]");
            g.to_local = to_unit * g.to_local;
        }
        if (auto x = in->optional("filter")) {
            const std::string f = x->string();
            if (f != "trilinear" && f != "nearest")
                x->fail("expected \"trilinear\" or \"nearest\", got \"" + f + "\"");
            g.nearest = f == "nearest";
        }
        if (auto x = in->optional("wrap")) g.wrap = wrap_mode(*x);
        if (own) own->finish();
        scene_.volume_grids.push_back(std::move(g));
        return static_cast<VolumeGridId>(scene_.volume_grids.size() - 1);
    }

    // {"scale": s or [su, sv], "rotate": degrees, "offset": [ou, ov]}: uv scaled, then rotated
    // counter-clockwise about (0, 0), then offset.
    void read_uv_transform(const Value& v, Texture& t) {
        Object o(v);
        float su = 1.0f, sv = 1.0f, degrees = 0.0f, ou = 0.0f, ov = 0.0f;
        if (auto x = o.optional("scale")) {
            if (x->is_array()) {
                if (x->size() != 2) x->fail("expected [su, sv]");
                su = (*x)[0].number();
                sv = (*x)[1].number();
            } else {
                su = sv = x->number();
            }
            if (su == 0.0f || sv == 0.0f) x->fail("a uv scale must not be 0");
        }
        if (auto x = o.optional("rotate")) degrees = x->number();
        if (auto x = o.optional("offset")) {
            if (x->size() != 2) x->fail("expected [ou, ov]");
            ou = (*x)[0].number();
            ov = (*x)[1].number();
        }
        o.finish();
        const float c = std::cos(radians(degrees)), s = std::sin(radians(degrees));
        t.uv[0][0] = c * su;
        t.uv[0][1] = -s * sv;
        t.uv[0][2] = ou;
        t.uv[1][0] = s * su;
        t.uv[1][1] = c * sv;
        t.uv[1][2] = ov;
    }

    // A microfacet roughness alpha (0: smooth) and its distribution.
    // A roughness: a number in [0, 1], or where `textured` (conductors) a texture, its number
    // then 1 (rough; the texture says how).
    void read_alpha(const Value& x, bool textured, float* alpha, TextureId* texture) {
        if (textured && x.is_object()) {
            *texture = read_texture(x, Range::Reflectance);
            *alpha = 1.0f;
        } else {
            *alpha = x.in_range(0.0f, 1.0f);
        }
    }

    void read_roughness(Object& o, Material& m, bool textured = false) {
        if (auto x = o.optional("alpha")) {
            read_alpha(*x, textured, &m.alpha_u, &m.alpha_u_texture);
            m.alpha_v = m.alpha_u;
            m.alpha_v_texture = m.alpha_u_texture;
        }
        if (auto x = o.optional("distribution")) {
            const std::string d = x->string();
            if (d == "ggx")
                m.distribution = Microfacet::Ggx;
            else if (d == "beckmann")
                m.distribution = Microfacet::Beckmann;
            else
                x->fail("unknown distribution \"" + d + "\" (expected ggx or beckmann)");
        }
    }

    // An index of refraction: a number > 0, or a name from Mitsuba's table (Hecht, Optics, at
    // about 589 nm and 0-20 degrees C).
    float read_ior(const Value& v) {
        if (!v.is_string()) return v.positive();
        static const std::pair<const char*, float> kNamed[] = {
            {"vacuum", 1.0f},      {"helium", 1.000036f},        {"hydrogen", 1.000132f},
            {"air", 1.000277f},    {"carbon dioxide", 1.00045f}, {"water", 1.333f},
            {"acetone", 1.36f},    {"ethanol", 1.361f},          {"carbon tetrachloride", 1.461f},
            {"glycerol", 1.4729f}, {"benzene", 1.501f},          {"silicone oil", 1.52045f},
            {"bromine", 1.661f},   {"water ice", 1.31f},         {"fused quartz", 1.458f},
            {"pyrex", 1.47f},      {"acrylic glass", 1.49f},     {"polypropylene", 1.49f},
            {"bk7", 1.5046f},      {"sodium chloride", 1.544f},  {"amber", 1.55f},
            {"pet", 1.575f},       {"diamond", 2.419f}};
        const std::string name = v.string();
        std::string known;
        for (const auto& [n, ior] : kNamed) {
            if (name == n) return ior;
            known += std::string(known.empty() ? "" : ", ") + n;
        }
        v.fail("unknown index of refraction \"" + name + "\" (expected a number or one of " +
               known + ")");
    }

    // An inside index of refraction `ior` over the optional "ext_ior" (default 1: vacuum).
    float read_relative_ior(Object& o, float ior) {
        if (auto x = o.optional("ext_ior")) ior /= read_ior(*x);
        return ior;
    }

    // A conductor: a named metal, or eta and k per channel (default 0 and 1: every direction
    // reflects fully, as Mitsuba's conductor "none"); a roughness alpha (0: smooth) and its
    // distribution; a reflectance texture scaling the Fresnel term.
    void read_conductor(Object& o, Material& m) {
        m.kind = MaterialKind::Conductor;
        m.eta = Color(0.0f);
        m.k = Color(1.0f);
        const std::optional<Value> eta = o.optional("eta"), k = o.optional("k");
        if (auto name = o.optional("metal")) {
            if (eta || k) name->fail("give either \"metal\" or \"eta\" and \"k\", not both");
            const std::string wanted = name->string();
            std::string known;
            for (const NamedMetal& metal : named_metals()) {
                if (wanted == metal.name) {
                    m.eta = metal.eta;
                    m.k = metal.k;
                    known.clear();
                    break;
                }
                known += std::string(known.empty() ? "" : ", ") + metal.name;
            }
            if (!known.empty() && wanted != "none")
                name->fail("unknown metal \"" + wanted + "\" (expected none, " + known + ")");
        }
        if (eta) m.eta = eta->color();
        if (k) m.k = k->color();
        for (int c = 0; c < 3; ++c)
            if (m.eta[c] == 0.0f && m.k[c] == 0.0f)
                (k ? *k : *eta)
                    .fail("eta and k are both 0 in channel " + std::to_string(c) +
                          ": a conductor needs eta > 0 or k > 0");
        read_roughness(o, m, true);
        // Anisotropic: alpha_u along the surface's dp/du, alpha_v across it (Mitsuba 3's and
        // pbrt-v4's uroughness / vroughness); each a number or a texture.
        if (auto u = o.optional("alpha_u")) {
            Value v = o.required("alpha_v");
            if (o.optional("alpha"))
                u->fail("give \"alpha\" or \"alpha_u\" and \"alpha_v\", not both");
            read_alpha(*u, true, &m.alpha_u, &m.alpha_u_texture);
            read_alpha(v, true, &m.alpha_v, &m.alpha_v_texture);
            if ((m.alpha_u == 0.0f) != (m.alpha_v == 0.0f))
                v.fail("alpha_u and alpha_v are both 0 (smooth) or both > 0");
        }
        auto x = o.optional("reflectance");
        m.albedo = x ? read_texture(*x, Range::Reflectance) : scene_.add_solid(Vec3(1.0f));
    }

    // A plastic (Mitsuba 3's plastic and roughplastic): the base's albedo (default 0.5), the
    // coating's ior over ext_ior (defaults polypropylene and 1), its roughness, the specular
    // reflectance (default 1) and the nonlinear rule.
    void read_plastic(Object& o, Material& m) {
        m.kind = MaterialKind::Plastic;
        auto albedo = o.optional("albedo");
        m.albedo =
            albedo ? read_texture(*albedo, Range::Reflectance) : scene_.add_solid(Vec3(0.5f));
        auto ior = o.optional("ior");
        m.ior = read_relative_ior(o, ior ? read_ior(*ior) : 1.49f);
        read_roughness(o, m);
        m.alpha_v = m.alpha_u;
        if (auto x = o.optional("specular")) m.specular = x->color();
        if (auto x = o.optional("nonlinear")) m.nonlinear = x->boolean();
    }

    // glTF 2.0's metallic-roughness material with its transmission and clearcoat extensions,
    // under glTF's names and defaults (metallic and roughness 1, base colour white, ior 1.5).
    void read_metallic_roughness(Object& o, Material& m) {
        m.kind = MaterialKind::MetallicRoughness;
        auto base = o.optional("base_color");
        m.albedo = base ? read_texture(*base, Range::Reflectance) : scene_.add_solid(Vec3(1.0f));
        m.metallic = m.roughness = 1.0f;
        if (auto x = o.optional("metallic")) m.metallic = x->in_range(0.0f, 1.0f);
        if (auto x = o.optional("roughness")) m.roughness = x->in_range(0.0f, 1.0f);
        if (auto x = o.optional("metallic_roughness"))
            m.metallic_roughness = read_texture(*x, Range::Reflectance);
        if (auto x = o.optional("ior")) m.ior = read_ior(*x);
        if (auto x = o.optional("transmission")) m.transmission = x->in_range(0.0f, 1.0f);
        if (auto x = o.optional("transmission_texture"))
            m.transmission_map = read_texture(*x, Range::Reflectance);
        if (auto x = o.optional("clearcoat")) m.clearcoat = x->in_range(0.0f, 1.0f);
        if (auto x = o.optional("clearcoat_roughness"))
            m.clearcoat_roughness = x->in_range(0.0f, 1.0f);
        if (auto x = o.optional("clearcoat_texture"))
            m.clearcoat_map = read_texture(*x, Range::Reflectance);
        if (auto x = o.optional("clearcoat_roughness_texture"))
            m.clearcoat_roughness_map = read_texture(*x, Range::Reflectance);
        if (auto x = o.optional("clearcoat_normal_map"))
            m.clearcoat_normal_map = read_texture(*x, Range::Reflectance);
        if (auto x = o.optional("emission")) m.emission = read_texture(*x, Range::Radiance);
        if (auto x = o.optional("two_sided")) m.two_sided = x->boolean();
    }

    // Mitsuba 3's principled BSDF, or with "thin": true its principledthin, under Mitsuba's
    // names and defaults (base colour 0.5, roughness 0.5, specular 0.5, i.e. ior 1.5); each
    // weight a number or a texture (its luminance).
    void read_principled(Object& o, Material& m) {
        m.kind = MaterialKind::Principled;
        PrincipledWeights& w = m.principled;
        if (auto x = o.optional("thin")) w.thin = x->boolean();
        auto base = o.optional("base_color");
        m.albedo = base ? read_texture(*base, Range::Reflectance) : scene_.add_solid(Vec3(0.5f));
        const std::optional<Value> ior = o.optional("ior"), specular = o.optional("specular");
        if (ior && specular) specular->fail("give \"ior\" or \"specular\", not both");
        if (specular && w.thin) specular->fail("a thin principled material takes \"ior\"");
        m.ior = ior ? read_ior(*ior)
                    : principled_eta_of_specular(specular ? specular->in_range(0.0f, 1.0f) : 0.5f);
        w.for_each([&](const char* name, TexturedNumber& n) {
            auto x = o.optional(name);
            if (!x) return;
            if (!PrincipledWeights::has(name, w.thin))
                x->fail(std::string(name) + " is a weight of " +
                        (w.thin ? "the full (not thin)" : "the thin") + " principled material");
            const float top = PrincipledWeights::max_of(name);
            if (x->is_object())
                n.texture = read_texture(*x, top > 1.0f ? Range::Radiance : Range::Reflectance);
            else
                n.value = x->in_range(0.0f, top);
        });
    }

    // A spot or projector at `position` aimed at `look_at`: its position and unit axis.
    void read_aim(Object& o, Light& light) {
        light.position = point(o.required("position"));
        Value at = o.required("look_at");
        const Vec3 axis = point(at) - light.position;
        if (!(length(axis) > 1e-6f * std::max(1.0f, max_component(abs(light.position)))))
            at.fail("look_at must differ from position");
        light.direction = normalize(axis);
    }

    // The top of a light's image: `up` made orthogonal to the axis, or by default +y (+z for an
    // axis along y), what a camera's default up would be.
    static Vec3 image_up(const std::optional<Value>& up, Vec3 axis) {
        Vec3 u = std::abs(axis.y) < 0.999f ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
        if (up) u = up->nonzero_vec3();
        const Vec3 across = u - dot(u, axis) * axis;
        if (up && !(length(across) > 1e-3f * length(u))) up->fail("up must not lie along the axis");
        return normalize(across);
    }

    // Mitsuba 3's projector: a pinhole at `position` looking at `look_at` (`up`, default as a
    // camera's, the image's top), projecting `irradiance` (a colour, or a texture; or
    // `intensity`, pbrt-v4's projection light) times `scale` through a frustum of field of view
    // `fov` degrees (default 90) on `fov_axis` (x, y, diagonal, smaller or larger, as Mitsuba's
    // sensors; default x), its aspect the image's (1 for any other texture or a colour).
    void read_projector(Object& o, Light& light) {
        light.kind = Light::Kind::Projector;
        read_aim(o, light);
        light.up = image_up(o.optional("up"), light.direction);
        float scale = 1.0f;
        if (auto x = o.optional("scale")) scale = x->non_negative();
        float aspect = 1.0f;
        light.intensity = Color(scale);
        std::optional<Value> given = o.optional("irradiance");
        if (auto i = o.optional("intensity")) {
            if (given) i->fail("give \"irradiance\" or \"intensity\", not both");
            light.projects_intensity = true;
            given = i;
        }
        if (given) {
            if (given->is_object()) {
                light.texture = off_meshes(read_texture(*given, Range::Radiance), *given);
                const Texture& t = scene_.textures[light.texture];
                if (t.kind == TextureKind::Image) {
                    const ImageData& image = scene_.images[t.image];
                    aspect = float(image.width) / float(image.height);
                }
            } else {
                light.intensity = given->color() * scale;
            }
        }
        float fov = 90.0f;
        if (auto x = o.optional("fov")) {
            fov = x->in_range(0.0f, 179.0f);
            if (!(fov > 0.0f)) x->fail("the field of view must lie in (0, 179]");
        }
        const float half = std::tan(radians(0.5f * fov));
        std::string axis_name = "x";
        auto fov_axis = o.optional("fov_axis");
        if (fov_axis) axis_name = fov_axis->string();
        // The frustum's half width at unit distance from the half extent on the named axis.
        if (axis_name == "x" || (axis_name == "larger" && aspect >= 1) ||
            (axis_name == "smaller" && aspect < 1))
            light.half_width = half;
        else if (axis_name == "y" || axis_name == "larger" || axis_name == "smaller")
            light.half_width = half * aspect;
        else if (axis_name == "diagonal")
            light.half_width = half * aspect / std::sqrt(1.0f + aspect * aspect);
        else
            fov_axis->fail("unknown fov_axis \"" + axis_name +
                           "\" (expected x, y, diagonal, smaller or larger)");
        light.half_height = light.half_width / aspect;
    }

    // Lights that are not shapes: point, spot and directional (docs/scene-format.md#lights).
    void read_lights(const Value& v) {
        for (size_t i = 0; i < v.size(); ++i) {
            Object o(v[i]);
            Value type_value = o.required("type");
            const std::string type = type_value.string();
            Light light;
            if (type == "point") {
                light.position = point(o.required("position"));
                light.intensity = o.required("intensity").color();
            } else if (type == "spot") {
                light.kind = Light::Kind::Spot;
                read_aim(o, light);
                light.intensity = o.required("intensity").color();
                if (auto x = o.optional("cutoff")) {
                    light.cutoff_degrees = x->in_range(0.0f, 90.0f);
                    if (!(light.cutoff_degrees > 0.0f)) x->fail("a spot's cutoff must be > 0");
                }
                light.falloff_start_degrees = 0.75f * light.cutoff_degrees;  // Mitsuba's default
                if (auto x = o.optional("falloff_start"))
                    light.falloff_start_degrees = x->in_range(0.0f, light.cutoff_degrees);
                if (auto x = o.optional("falloff")) {
                    const std::string f = x->string();
                    if (f == "linear")
                        light.falloff = Light::Falloff::Linear;
                    else if (f == "smoothstep")
                        light.falloff = Light::Falloff::Smoothstep;
                    else
                        x->fail("unknown falloff \"" + f + "\" (expected linear or smoothstep)");
                }
                if (auto x = o.optional("texture"))
                    light.texture = off_meshes(read_texture(*x, Range::Radiance), *x);
                const std::optional<Value> up = o.optional("up");
                if (up && light.texture == kNone)
                    up->fail("up orients a projected texture: give one");
                if (light.texture != kNone) light.up = image_up(up, light.direction);
            } else if (type == "directional") {
                light.kind = Light::Kind::Directional;
                light.direction = normalize(o.required("direction").nonzero_vec3());
                light.intensity = o.required("irradiance").color();
            } else if (type == "projector") {
                read_projector(o, light);
            } else {
                type_value.fail("unknown light type \"" + type +
                                "\" (expected point, spot, projector or directional)");
            }
            o.finish();
            scene_.lights.push_back(light);
        }
    }

    // Materials are read in the order blends need, each after the materials it blends, which
    // it names or holds.
    void read_materials(const Value& v) {
        Object all(v);
        for (const auto& [name, unused] : v.raw().items())
            declared_materials_.emplace(name, all.required(name));
        for (const auto& [name, unused] : v.raw().items()) named_material(name, nullptr);
        all.finish();
    }

    // The material /materials declares as `name`, read on first use; `from` the place that
    // names it (nullptr: /materials itself).
    MaterialId named_material(const std::string& name, const Value* from) {
        if (auto it = materials_.find(name); it != materials_.end()) return it->second;
        auto declared = declared_materials_.find(name);
        if (declared == declared_materials_.end())
            from->fail("no material named \"" + name + "\" in /materials");
        if (!reading_materials_.insert(name).second)
            from->fail("blend \"" + name + "\" contains itself");
        const MaterialId id = read_material(declared->second, name);
        reading_materials_.erase(name);
        return materials_[name] = id;
    }

    MaterialId read_material(const Value& mv, const std::string& name) {
        Object o(mv);
        Value type_value = o.required("type");
        std::string type = type_value.string();
        Material m;
        m.name = name;
        if (type == "lambertian") {
            m.kind = MaterialKind::Lambertian;
            m.albedo = read_texture(o.required("albedo"), Range::Reflectance);
        } else if (type == "metal") {
            m.kind = MaterialKind::Metal;
            m.albedo = read_texture(o.required("albedo"), Range::Reflectance);
            if (auto x = o.optional("roughness")) m.roughness = x->in_range(0.0f, 1.0f);
        } else if (type == "mirror") {
            m.kind = MaterialKind::Mirror;
            auto x = o.optional("albedo");
            m.albedo = x ? read_texture(*x, Range::Reflectance) : scene_.add_solid(Vec3(1.0f));
        } else if (type == "dielectric") {
            m.kind = MaterialKind::Dielectric;
            m.ior = read_relative_ior(o, read_ior(o.required("ior")));
            read_roughness(o, m);
            // Index-matched, the interface is invisible however rough it is (Walter's model
            // degenerates to a delta there): the smooth dielectric says so exactly.
            if (m.ior == 1.0f) m.alpha_u = m.alpha_v = 0.0f;
        } else if (type == "conductor") {
            read_conductor(o, m);
        } else if (type == "thin_dielectric") {
            m.kind = MaterialKind::ThinDielectric;
            m.ior = read_relative_ior(o, read_ior(o.required("ior")));
        } else if (type == "plastic") {
            read_plastic(o, m);
        } else if (type == "metallic_roughness") {
            read_metallic_roughness(o, m);
        } else if (type == "principled") {
            read_principled(o, m);
        } else if (type == "blend") {
            read_blend(o, m);
        } else if (type == "diffuse_light") {
            m.kind = MaterialKind::DiffuseLight;
            m.emission = read_texture(o.required("radiance"), Range::Radiance);
            if (auto x = o.optional("two_sided")) m.two_sided = x->boolean();
            // Optional: the emitter also reflects, as a Lambertian surface.
            if (auto x = o.optional("albedo")) m.albedo = read_texture(*x, Range::Reflectance);
        } else {
            type_value.fail("unknown material type \"" + type +
                            "\" (expected lambertian, metal, mirror, dielectric, "
                            "thin_dielectric, conductor, plastic, metallic_roughness, "
                            "principled, blend or diffuse_light; media are declared under "
                            "/media)");
        }
        // An alpha mask, for any surface (scene/opacity.h).
        if (auto x = o.optional("opacity")) m.opacity = read_texture(*x, Range::Reflectance);
        // Normal and bump maps, for any surface (scene/normal_maps.h).
        if (auto x = o.optional("normal_map")) m.normal_map = read_texture(*x, Range::Reflectance);
        if (auto x = o.optional("bump_map")) m.bump_map = read_texture(*x, Range::Radiance);
        if (auto x = o.optional("bump_scale")) m.bump_scale = x->number();
        if (auto x = o.optional("flip_invalid_normals")) m.flip_invalid_normals = x->boolean();
        if (auto x = o.optional("bump_shadowing")) m.bump_shadowing = x->boolean();
        if (auto x = o.optional("one_sided")) {
            if (m.kind != MaterialKind::Lambertian && m.kind != MaterialKind::Metal &&
                m.kind != MaterialKind::Mirror && m.kind != MaterialKind::Conductor &&
                m.kind != MaterialKind::Plastic && m.kind != MaterialKind::MetallicRoughness)
                x->fail(
                    "only lambertian, metal, mirror, conductor, plastic and "
                    "metallic_roughness materials are one-sided or not");
            m.one_sided = x->boolean();
        }
        o.finish();
        if (const char* field = attribute_misuse(scene_, m))
            mv.fail(std::string("its ") + field +
                    " reads a mesh attribute, which only a material's albedo, metallic_roughness, "
                    "alpha textures, opacity and a blend's weight can");
        return scene_.add_material(std::move(m));
    }

    // A blend of two materials, each a name in /materials or a material object, mixed by
    // "weight": a number or a texture (its luminance) in [0, 1], 0 the first, 1 the second.
    void read_blend(Object& o, Material& m) {
        m.kind = MaterialKind::Blend;
        Value list = o.required("materials");
        if (list.size() != 2) list.fail("expected two materials, names or objects");
        for (size_t k = 0; k < 2; ++k) {
            const Value c = list[k];
            m.blend[k] = c.is_string() ? named_material(c.string(), &c)
                                       : read_material(c, m.name + "/" + std::to_string(k));
            const Material& x = scene_.materials[m.blend[k]];
            if (!x.can_be_blended())
                c.fail(std::string("a blend's materials cannot emit, have an opacity, or be a "
                                   "thin_dielectric (found ") +
                       to_string(x.kind) + ")");
        }
        if (auto x = o.optional("weight")) {
            if (x->is_object())
                m.blend_weight.texture = read_texture(*x, Range::Reflectance);
            else
                m.blend_weight.value = x->in_range(0.0f, 1.0f);
        }
    }

    void read_media(const Value& v) {
        Object all(v);
        for (const auto& [name, unused] : v.raw().items()) {
            if (scene_.media.size() >= kMaxMedia)
                all.required(name).fail("more than " + std::to_string(kMaxMedia) + " media");
            Object o(all.required(name));
            // One extinction for all channels, or one per channel (none negative, one > 0).
            const Value d = o.required("density");
            const Color sigma_t = d.is_number() ? Color(d.positive()) : d.color();
            if (!(max_component(sigma_t) > 0.0f)) d.fail("a medium's density must be > 0 in some channel");
            const Value albedo_value = o.required("albedo");
            TextureId albedo =
                off_meshes(read_texture(albedo_value, Range::Reflectance), albedo_value);
            VolumeGridId grid = kNone;
            if (auto x = o.optional("density_grid")) grid = read_volume_grid(*x, Range::Radiance);
            o.finish();
            media_[name] = scene_.add_medium(name, sigma_t, albedo);
            scene_.media[media_[name]].density_grid = grid;
        }
        all.finish();
    }

    Transform read_transform(const Value& v) const {
        Transform t;
        for (size_t i = 0; i < v.size(); ++i) {
            Value step = v[i];
            Object o(step);
            Transform s;
            int ops = 0;
            if (auto x = o.optional("translate")) {
                s = Transform::translate(point(*x));
                ++ops;
            }
            if (auto x = o.optional("rotate")) {
                Object r(*x);
                Vec3 axis = r.required("axis").nonzero_vec3();
                float degrees = r.required("degrees").number();
                r.finish();
                s = Transform::rotate(axis, degrees);
                ++ops;
            }
            if (auto x = o.optional("scale")) {
                Vec3 k = x->is_number() ? Vec3(x->number()) : x->vec3();
                if (k.x == 0 || k.y == 0 || k.z == 0 || max_component(abs(k)) > kMaxCoordinate ||
                    min_component(abs(k)) < 1.0f / kMaxCoordinate)
                    x->fail("expected a non-zero scale within [1e-7, 1e7], got " + x->describe());
                s = Transform::scale(k);
                ++ops;
            }
            if (auto x = o.optional("matrix")) {
                // Row-major, 12 numbers (3 rows) or 16 (the last row 0 0 0 1).
                if (!x->is_array() || (x->size() != 12 && x->size() != 16))
                    x->fail("expected an array of 12 or 16 numbers (rows of a 3x4 or 4x4 matrix)");
                double rows[3][4];
                for (size_t k = 0; k < x->size(); ++k) {
                    const Value e = (*x)[k];
                    const double number = e.number();
                    if (k < 12 && !(std::abs(number) <= kMaxCoordinate))
                        e.fail("expected a number within +-1e7, got " + e.describe());
                    if (k >= 12 && number != (k == 15 ? 1.0 : 0.0))
                        e.fail("the last row of an affine matrix is 0 0 0 1, got " + e.describe());
                    if (k < 12) rows[k / 4][k % 4] = number;
                }
                if (!Transform::affine(rows, &s)) x->fail("the matrix is singular");
                ++ops;
            }
            o.finish();
            if (ops != 1)
                step.fail("expected exactly one of \"translate\", \"rotate\", \"scale\" or "
                          "\"matrix\"");
            t = s * t;  // steps apply in the order listed
            if (!t.is_well_conditioned(kMaxCoordinate))
                step.fail("the transform up to this step scales beyond [1e-7, 1e7] or overflows");
        }
        return t;
    }

    // One scene mesh per material part of a mesh file, each with its file material mapped.
    void add_mesh_parts(const MeshFile& mesh,
                        const fs::path& path,
                        MediumId interior,
                        const Transform& to_world,
                        const Value& where) {
        std::vector<MaterialId> mapped(mesh.materials.size(), kNone);
        for (const MeshPart& part : mesh.parts) {
            if (mapped[part.material] == kNone)
                mapped[part.material] = map_file_material(
                    mesh.materials[part.material], mesh.embedded, path, where, mesh.attributes);
            // The part's own vertices, re-indexed from 0, and its share of the attributes.
            std::vector<uint32_t> indices, remap(mesh.positions.size(), UINT32_MAX);
            std::vector<Point3> positions;
            std::vector<Normal3> normals;
            std::vector<Vec2> uvs;
            std::vector<MeshAttribute> attributes;
            for (const MeshAttribute& a : mesh.attributes) {
                attributes.push_back({a.name, a.per_face, a.channels, {}});
                if (a.per_face)
                    attributes.back().values.assign(
                        a.values.begin() + part.first_triangle,
                        a.values.begin() + part.first_triangle + part.triangles);
            }
            for (size_t k = 3 * part.first_triangle; k < 3 * (part.first_triangle + part.triangles);
                 ++k) {
                const uint32_t v = mesh.indices[k];
                if (v >= mesh.positions.size()) continue;  // add_mesh would skip it too
                if (remap[v] == UINT32_MAX) {
                    remap[v] = static_cast<uint32_t>(positions.size());
                    positions.push_back(mesh.positions[v]);
                    if (!mesh.normals.empty()) normals.push_back(mesh.normals[v]);
                    if (!mesh.uvs.empty()) uvs.push_back(mesh.uvs[v]);
                    for (size_t a = 0; a < attributes.size(); ++a)
                        if (!attributes[a].per_face)
                            attributes[a].values.push_back(mesh.attributes[a].values[v]);
                }
                indices.push_back(remap[v]);
            }
            Mesh m;
            m.name = path.filename().string() + ":" + mesh.materials[part.material].name;
            m.material = mapped[part.material];
            m.interior = interior;
            skipped_triangles_ += scene_.add_mesh(std::move(m), positions, normals, uvs, indices,
                                                  to_world, std::move(attributes));
        }
    }

    // A mesh file's material as a wavetrace material (docs/scene-format.md, "Materials from
    // mesh files"): Ke -> one-sided emitter (reflecting as Lambertian Kd if Kd > 0), illum 4/6/7 ->
    // dielectric of index Ni, Ks without
    // Kd -> metal (roughness from Ns), else Kd (or map_Kd) -> Lambertian. What does not map is
    // a warning naming the material.
    MaterialId map_file_material(const FileMaterial& fm,
                                 const std::vector<EmbeddedImage>& embedded,
                                 const fs::path& mesh_path,
                                 const Value& where,
                                 const std::vector<MeshAttribute>& attributes) {
        const std::string who = mesh_path.filename().string() + ": material \"" + fm.name + "\"";
        auto positive = [](Color c) { return max_component(c) > 0.0f; };
        auto check_color = [&](Color c, const char* key) {
            if (!is_finite(c) || c.x < 0 || c.y < 0 || c.z < 0 || max_component(c) > 1e6f)
                where.fail(who + ": " + key + " must be finite and non-negative");
        };
        check_color(fm.kd, "Kd");
        check_color(fm.ks, "Ks");
        check_color(fm.ke, "Ke");
        if (fm.pbr) return map_gltf_material(fm, embedded, mesh_path, where, who, attributes);
        Material m;
        m.name = fm.name;
        const bool dielectric = fm.illum == 4 || fm.illum == 6 || fm.illum == 7;
        std::vector<std::string> ignored = fm.other_maps;
        if (positive(fm.ke)) {
            m.kind = MaterialKind::DiffuseLight;
            m.emission = scene_.add_solid(fm.ke);
            if (positive(fm.kd)) m.albedo = scene_.add_solid(min(fm.kd, Color(1.0f)));
            if (positive(fm.ks)) ignored.push_back("Ks (an emitter reflects as Lambertian Kd)");
            if (!fm.map_kd.empty()) ignored.push_back("map_Kd of an emitter");
        } else if (dielectric) {
            m.kind = MaterialKind::Dielectric;
            if (!(fm.ni > 1.0f && fm.ni < 10.0f)) {
                warn(who + ": Ni " + std::to_string(fm.ni) +
                     " is no index of refraction of glass; using 1.5");
                m.ior = 1.5f;
            } else {
                m.ior = fm.ni;
            }
            if (positive(fm.kd) || !fm.map_kd.empty())
                ignored.push_back("Kd (a dielectric is clear)");
        } else if (positive(fm.ks) && !positive(fm.kd) && fm.map_kd.empty()) {
            m.kind = MaterialKind::Metal;
            m.albedo = scene_.add_solid(min(fm.ks, Color(1.0f)));
            // The Phong exponent as a microfacet width: alpha = sqrt(2 / (Ns + 2)) (the
            // Beckmann-Phong correspondence, Walter et al. 2007, section 5.2); roughness^2 = alpha.
            m.roughness = std::pow(2.0f / (std::max(fm.ns, 0.0f) + 2.0f), 0.25f);
        } else {
            m.kind = MaterialKind::Lambertian;
            if (!fm.map_kd.empty()) {
                m.albedo = file_texture(mesh_path, fm.map_kd, "map_Kd", ImageChannels::Linear,
                                        Color(1.0f), where, who);
            } else {
                if (!positive(fm.kd)) warn(who + ": no Kd, Ks or Ke; rendered black");
                m.albedo = scene_.add_solid(min(fm.kd, Color(1.0f)));
            }
            if (positive(fm.ks)) ignored.push_back("Ks (no diffuse + glossy material)");
        }
        if (fm.dissolve < 1.0f) ignored.push_back("d (transparency)");
        if (!ignored.empty()) {
            std::string list;
            for (const std::string& k : ignored) list += (list.empty() ? "" : ", ") + k;
            warn(who + ": ignored " + list);
        }
        return scene_.add_material(std::move(m));
    }

    // An image texture a mesh file names (path relative to the file): the channels asked for,
    // times factor.
    TextureId file_texture(const fs::path& mesh_path,
                           const std::string& relative,
                           const char* key,
                           ImageChannels channels,
                           Color factor,
                           const Value& where,
                           const std::string& who) {
        fs::path tex = mesh_path.parent_path() / relative;
        if (std::string why = Confinement{mesh_path.parent_path(), options_.asset_root}.problem(tex);
            !why.empty())
            where.fail(who + ": " + key + " '" + tex.string() + "': " + why);
        std::error_code ec;
        if (!fs::exists(tex, ec))
            where.fail(who + ": " + key + " '" + tex.string() + "': no such file");
        Texture t;
        t.kind = TextureKind::Image;
        t.factor = factor;
        try {
            t.image = scene_.add_image(read_image(tex, channels));
        } catch (const std::exception& e) {
            where.fail(who + ": " + key + " '" + tex.string() + "': " + e.what());
        }
        return scene_.add_texture(t);
    }

    // A glTF material (docs/scene-format.md, "Materials from mesh files"): metallic_roughness
    // with the file's factors and textures, beside the file or embedded in it (Assimp names
    // those "*N"); what the material cannot hold is a warning.
    MaterialId map_gltf_material(const FileMaterial& fm,
                                 const std::vector<EmbeddedImage>& embedded,
                                 const fs::path& mesh_path,
                                 const Value& where,
                                 const std::string& who,
                                 const std::vector<MeshAttribute>& attributes) {
        auto unit = [&](float x, const char* key) {
            if (!(x >= 0.0f && x <= 1.0f))
                where.fail(who + ": " + key + " " + std::to_string(x) + " is not in [0, 1]");
            return x;
        };
        if (!(fm.ni > 0.0f && fm.ni < 100.0f))
            where.fail(who + ": ior " + std::to_string(fm.ni) + " is not in (0, 100)");
        std::vector<std::string> ignored = fm.other_maps;
        // A texture beside the file, or embedded in it.
        auto load = [&](const std::string& rel, const char* key, ImageChannels channels,
                        Color factor) -> TextureId {
            if (rel.empty()) return kNone;
            if (rel[0] != '*')
                return file_texture(mesh_path, rel, key, channels, factor, where, who);
            const std::string name = mesh_path.filename().string() + ": image " + rel;
            char* end = nullptr;
            const unsigned long n = std::strtoul(rel.c_str() + 1, &end, 10);
            if (rel.size() < 2 || *end != '\0' || n >= embedded.size())
                where.fail(who + ": " + key + " '" + rel + "': no such embedded image");
            Texture t;
            t.kind = TextureKind::Image;
            t.factor = factor;
            try {
                t.image = scene_.add_image(
                    read_image_bytes(embedded[n].bytes, embedded[n].format, name, channels));
            } catch (const std::exception& e) {
                where.fail(who + ": " + key + ": " + e.what());
            }
            return scene_.add_texture(t);
        };
        // ... looked up as its sampler says.
        auto texture = [&](const std::string& rel, const char* key, ImageChannels channels,
                           Color factor, const FileMaterial::Sampler& sampler) -> TextureId {
            const TextureId id = load(rel, key, channels, factor);
            if (id != kNone) {
                Texture& t = scene_.textures[id];
                t.wrap_u = sampler.wrap_u;
                t.wrap_v = sampler.wrap_v;
                t.filter = sampler.filter;
                std::copy(&sampler.uv[0][0], &sampler.uv[0][0] + 6, &t.uv[0][0]);
            }
            return id;
        };
        Material m;
        m.name = fm.name;
        m.kind = MaterialKind::MetallicRoughness;
        const Color base = min(fm.kd, Color(1.0f));
        m.albedo = texture(fm.map_kd, "baseColorTexture", ImageChannels::Linear, base, fm.kd_sampler);
        if (m.albedo == kNone) m.albedo = scene_.add_solid(base);
        const auto has_attribute = [&](const char* name) {
            return std::any_of(attributes.begin(), attributes.end(),
                               [&](const MeshAttribute& a) { return a.name == name; });
        };
        // Texture `factor` times the mesh attribute `name`, then cut at `cutoff` (-1: not).
        const auto times_attribute = [&](TextureId factor, const char* name, float cutoff) {
            Texture attribute, product;
            attribute.kind = TextureKind::MeshAttribute;
            attribute.attribute = name;
            product.kind = TextureKind::Product;
            product.factors[0] = factor;
            product.factors[1] = scene_.add_texture(attribute);
            product.cutoff = cutoff;
            return scene_.add_texture(product);
        };
        // glTF's vertex colours multiply the base colour.
        if (has_attribute("vertex_color"))
            m.albedo = times_attribute(m.albedo, "vertex_color", -1.0f);
        m.metallic = unit(fm.metallic, "metallicFactor");
        m.roughness = unit(fm.roughness, "roughnessFactor");
        m.metallic_roughness = texture(fm.map_metallic_roughness, "metallicRoughnessTexture",
                                       ImageChannels::Raw, Color(1.0f), fm.metallic_roughness_sampler);
        m.ior = fm.ni;
        m.transmission = unit(fm.transmission, "transmissionFactor");
        m.transmission_map = texture(fm.map_transmission, "transmissionTexture", ImageChannels::Raw,
                                     Color(1.0f), fm.transmission_sampler);
        m.clearcoat = unit(fm.clearcoat, "clearcoatFactor");
        m.clearcoat_roughness = unit(fm.clearcoat_roughness, "clearcoatRoughnessFactor");
        m.clearcoat_map = texture(fm.map_clearcoat, "clearcoatTexture", ImageChannels::Raw,
                                  Color(1.0f), fm.clearcoat_sampler);
        m.clearcoat_roughness_map =
            texture(fm.map_clearcoat_roughness, "clearcoatRoughnessTexture", ImageChannels::Raw,
                    Color(1.0f), fm.clearcoat_roughness_sampler);
        m.normal_map = texture(fm.map_normal, "normalTexture", ImageChannels::Raw, Color(1.0f),
                               fm.normal_sampler);
        m.clearcoat_normal_map =
            texture(fm.map_clearcoat_normal, "clearcoatNormalTexture", ImageChannels::Raw,
                    Color(1.0f), fm.clearcoat_normal_sampler);
        m.emission = texture(fm.map_emissive, "emissiveTexture", ImageChannels::Linear, fm.ke,
                             fm.emissive_sampler);
        if (m.emission == kNone && max_component(fm.ke) > 0.0f)
            m.emission = scene_.add_solid(fm.ke);
        m.two_sided = fm.double_sided;  // a double-sided surface emits from both sides
        // Alpha: the base colour's alpha (its factor's times its texture's and its vertices'), as
        // coverage. MASK cuts at alphaCutoff; BLEND lets that share of rays through (the
        // stochastic opacity of a surface seen through many samples, as a blended one looks).
        if (fm.alpha_mode == "MASK" || fm.alpha_mode == "BLEND") {
            const float alpha = unit(fm.base_alpha, "baseColorFactor's alpha");
            const float cutoff = fm.alpha_mode == "MASK" ? fm.alpha_cutoff : -1.0f;
            if (fm.alpha_mode == "MASK" && !(cutoff >= 0.0f && cutoff <= 1e6f))
                where.fail(who + ": alphaCutoff must be a non-negative number");
            m.opacity = texture(fm.map_kd, "baseColorTexture", ImageChannels::Alpha, Color(alpha),
                                fm.kd_sampler);
            if (has_attribute("vertex_alpha")) {
                // COLOR_0's alpha multiplies the rest before the cutoff.
                if (m.opacity == kNone) m.opacity = scene_.add_solid(Color(alpha));
                m.opacity = times_attribute(m.opacity, "vertex_alpha", cutoff);
            } else if (m.opacity != kNone) {
                scene_.textures[m.opacity].cutoff = cutoff;
            } else if (cutoff >= 0.0f) {
                m.opacity = scene_.add_solid(Color(alpha >= cutoff ? 1.0f : 0.0f));
            } else if (alpha < 1.0f) {
                m.opacity = scene_.add_solid(Color(alpha));
            }
        } else if (fm.alpha_mode != "OPAQUE") {
            where.fail(who + ": unknown alphaMode \"" + fm.alpha_mode + "\"");
        }
        if (!ignored.empty()) {
            std::string list;
            for (const std::string& k : ignored) list += (list.empty() ? "" : ", ") + k;
            warn(who + ": ignored " + list);
        }
        return scene_.add_material(std::move(m));
    }

    MaterialId material_ref(const Value& v) const {
        std::string name = v.string();
        auto it = materials_.find(name);
        if (it == materials_.end()) v.fail("no material named \"" + name + "\" in /materials");
        return it->second;
    }

    MediumId medium_ref(const Value& v) const {
        std::string name = v.string();
        auto it = media_.find(name);
        if (it == media_.end()) v.fail("no medium named \"" + name + "\" in /media");
        return it->second;
    }

    void read_object(const Value& v, const Transform& parent) {
        Object o(v);
        Value type_value = o.required("type");
        std::string type = type_value.string();
        Transform to_world = parent;
        if (auto x = o.optional("transform")) {
            to_world = parent * read_transform(*x);
            // Each step is in range, but their product, with the groups' above, may not be.
            if (!to_world.is_well_conditioned(kMaxCoordinate))
                x->fail(
                    "the composed transform (with its groups') scales beyond [1e-7, 1e7] "
                    "or overflows");
        }

        if (type == "group") {
            Value children = o.required("objects");
            o.finish();
            for (size_t i = 0; i < children.size(); ++i) read_object(children[i], to_world);
            return;
        }

        const Counts before = counts();
        // Surface material and interior medium; a shape with only a medium is an invisible
        // boundary (constant_medium in Ray Tracing: The Next Week).
        MediumId interior = kNone;
        if (auto x = o.optional("interior")) interior = medium_ref(*x);
        MaterialId material = kNone;
        bool file_materials = false;  // a mesh whose materials come from its file (OBJ's MTL)
        if (auto x = type == "mesh" ? o.optional("materials") : std::nullopt) {
            if (x->string() != "file")
                x->fail("expected \"file\" (the materials the mesh file names), got " +
                        x->describe());
            if (auto m = o.optional("material"))
                m->fail("give \"material\" or \"materials\": \"file\", not both");
            file_materials = true;
        } else if (auto m = o.optional("material")) {
            material = material_ref(*m);
        } else if (interior != kNone) {
            material = scene_.interface_material();
        } else {
            v.fail("missing required key \"material\" (or \"interior\" for a medium boundary)");
        }

        if (type == "sphere") {
            Sphere s;
            s.center = point(o.required("center"));
            Value radius = o.required("radius");
            s.radius = radius.positive();
            s.material = material;
            s.interior = interior;
            if (auto x = o.optional("uv_mapping")) {
                const std::string mapping = x->string();
                if (mapping == "z_up") s.mapping = SphereMapping::ZUp;
                else if (mapping != "y_up")
                    x->fail("unknown uv_mapping \"" + mapping + "\" (expected y_up or z_up)");
            }
            o.finish();
            float scale;
            if (!to_world.preserves_shape(&scale))
                v.fail("a sphere's transform must not scale non-uniformly");
            scene_.add_sphere(s, to_world);
        } else if (type == "quad") {
            Quad q;
            q.q = point(o.required("q"));
            q.u = o.required("u").nonzero_vec3();
            Value vv = o.required("v");
            q.v = vv.nonzero_vec3();
            if (length_squared(cross(q.u, q.v)) == 0.0f) vv.fail("u and v must not be parallel");
            q.material = material;
            q.interior = interior;
            if (auto x = o.optional("flip_v")) q.flip_v = x->boolean();
            o.finish();
            scene_.add_quad(q, to_world);
        } else if (type == "box") {
            Point3 lo = point(o.required("min"));
            Value max_value = o.required("max");
            Point3 hi = point(max_value);
            if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
                max_value.fail("expected max > min in every axis, got " + max_value.describe());
            o.finish();
            scene_.add_box(lo, hi, material, interior, to_world);
        } else if (type == "mesh") {
            Value file = o.required("file");
            std::optional<Value> shape_index = o.optional("shape_index");
            std::string normals = "file";
            if (auto x = o.optional("normals")) {
                normals = x->string();
                if (normals != "file" && normals != "flat" && normals != "smooth" &&
                    normals != "file_or_smooth")
                    x->fail("expected \"file\", \"flat\", \"smooth\" or \"file_or_smooth\", got " +
                            x->describe());
            }
            bool flip_v = false;  // uvs read as (u, 1 - v)
            if (auto x = o.optional("flip_v")) flip_v = x->boolean();
            o.finish();
            MeshFile mesh;
            fs::path p;
            auto held = memory_meshes_ && file.is_string()
                            ? memory_meshes_->find(file.string())
                            : std::map<std::string, PbrtMesh>::const_iterator{};
            if (memory_meshes_ && file.is_string() && held != memory_meshes_->end()) {
                p = file.string();
                mesh.positions = held->second.positions;
                mesh.normals = held->second.normals;
                mesh.uvs = held->second.uvs;
                mesh.indices = held->second.indices;
            } else {
                p = resolve(file);
                std::string ext = p.extension().string();
                for (char& ch : ext)
                    ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
                const bool serialized = ext == ".serialized";
                if (shape_index && !serialized)
                    shape_index->fail("only a Mitsuba .serialized file holds several shapes");
                const uint32_t index =
                    shape_index ? static_cast<uint32_t>(shape_index->integer(0, 1 << 30)) : 0;
                try {
                    mesh = serialized ? read_serialized_mesh(p, index)
                                      : read_mesh_file(p, options_.asset_root);
                } catch (const std::bad_alloc&) {
                    file.fail("out of memory reading mesh '" + p.string() + "'");
                } catch (const std::exception& e) {
                    file.fail("cannot read mesh '" + p.string() + "': " + e.what());
                }
                for (const std::string& w : mesh.warnings)
                    warn(file.pointer() + ": mesh '" + p.string() + "' " + w);
            }
            if (flip_v)
                for (Vec2& t : mesh.uvs) t.y = 1.0f - t.y;
            if (normals == "flat") mesh.normals.clear();
            if (normals == "smooth" || (normals == "file_or_smooth" && mesh.normals.empty()))
                mesh.normals = smooth_normals(mesh.positions, mesh.indices);
            if (file_materials) {
                add_mesh_parts(mesh, p, interior, to_world, file);
            } else {
                Mesh m;
                m.name = p.filename().string();
                m.material = material;
                m.interior = interior;
                skipped_triangles_ +=
                    scene_.add_mesh(std::move(m), mesh.positions, mesh.normals, mesh.uvs,
                                    mesh.indices, to_world, std::move(mesh.attributes));
            }
        } else if (type == "disk" || type == "cylinder") {
            // Tessellated in a frame whose +z is the disk's normal or the cylinder's axis.
            constexpr double kTurn = 6.28318530717958647692;
            TessellatedShape t;
            Point3 origin;
            Vec3 axis;
            if (type == "disk") {
                origin = point(o.required("center"));
                axis = o.required("normal").nonzero_vec3();
                t = tessellate_disk(o.required("radius").positive(), 0, kTurn, 0);
            } else {
                origin = point(o.required("p0"));
                Value p1 = o.required("p1");
                axis = point(p1) - origin;
                if (!(length(axis) > 0)) p1.fail("p1 must differ from p0");
                t = tessellate_cylinder(o.required("radius").positive(), 0, length(axis), kTurn);
            }
            if (auto x = o.optional("flip_v"); x && x->boolean())
                for (Vec2& uv : t.uvs) uv.y = 1.0f - uv.y;
            o.finish();
            const Frame frame = Frame::from_normal(normalize(axis));
            for (Point3& p : t.positions) p = origin + frame.to_world(p);
            for (Normal3& n : t.normals) n = frame.to_world(n);
            Mesh m;
            m.name = type;
            m.material = material;
            m.interior = interior;
            skipped_triangles_ += scene_.add_mesh(std::move(m), t.positions, t.normals, t.uvs,
                                                  t.indices, to_world);
        } else {
            type_value.fail("unknown object type \"" + type +
                            "\" (expected sphere, quad, box, disk, cylinder, mesh or group)");
        }
        check_new_primitives(v, before);
    }

    struct Counts {
        size_t triangles, quads, spheres, meshes;
    };
    Counts counts() const {
        return {scene_.triangles.size(), scene_.quads.size(), scene_.spheres.size(),
                scene_.meshes.size()};
    }

    // The object's primitives, once transformed, must stay in the range where float
    // coordinates are precise, and each kind must stay addressable by a PrimRef.
    void check_new_primitives(const Value& v, const Counts& before) const {
        Counts now = counts();
        if (now.triangles > kMaxPrimsPerKind || now.quads > kMaxPrimsPerKind ||
            now.spheres > kMaxPrimsPerKind)
            v.fail("too many primitives of one kind (the limit is 2^30 - 1)");
        Aabb box;
        for (size_t i = before.triangles; i < now.triangles; ++i)
            box.grow(
                scene_.prim_bounds(PrimRef::make(PrimKind::Triangle, static_cast<uint32_t>(i))));
        for (size_t i = before.quads; i < now.quads; ++i)
            box.grow(scene_.prim_bounds(PrimRef::make(PrimKind::Quad, static_cast<uint32_t>(i))));
        for (size_t i = before.spheres; i < now.spheres; ++i)
            box.grow(scene_.prim_bounds(PrimRef::make(PrimKind::Sphere, static_cast<uint32_t>(i))));
        // Written so that NaN coordinates fail too.
        if (!box.empty() && !(max_component(abs(box.lo)) <= kMaxCoordinate &&
                              max_component(abs(box.hi)) <= kMaxCoordinate))
            v.fail("after its transform the object reaches beyond +-1e7");
        for (size_t i = before.meshes; i < now.meshes; ++i)
            if (const std::string missing = missing_attribute(scene_, uint32_t(i));
                !missing.empty())
                v.fail(missing);
        const bool quads = now.quads > before.quads, spheres = now.spheres > before.spheres;
        if ((quads || spheres) &&
            !material_attributes(
                 scene_, quads ? scene_.quads.back().material : scene_.spheres.back().material)
                 .empty())
            v.fail("its material reads a mesh attribute, and only meshes have them");
    }

    fs::path path_;
    std::string file_;
    const LoadOptions& options_;
    nlohmann::json json_;
    const std::map<std::string, PbrtMesh>* memory_meshes_ = nullptr;
    Scene scene_;
    std::map<std::string, MaterialId> materials_;
    std::map<std::string, Value> declared_materials_;  // /materials, before each is read
    std::set<std::string> reading_materials_;          // blends being read, to find cycles
    std::map<std::string, MediumId> media_;
    size_t skipped_triangles_ = 0;
};

}  // namespace

// An error the JSON loader finds in a translated document's object, light or background names
// the place in the source file (an XML element, a pbrt directive) it came from.
Scene build_translated(const fs::path& path,
                       const LoadOptions& options,
                       nlohmann::json scene,
                       const std::vector<std::string>& object_places,
                       const std::vector<std::string>& light_places,
                       const std::string& background_place,
                       const std::map<std::string, PbrtMesh>* meshes) {
    const std::string file = path.string();
    try {
        return Loader(path, options).build(std::move(scene), meshes);
    } catch (const SceneError& e) {
        std::string message = e.what();
        auto entry_of = [&](const char* array, const std::vector<std::string>& places) {
            const std::string prefix = file + ": /" + array + "/";
            if (message.rfind(prefix, 0) != 0) return false;
            const size_t index = std::strtoul(message.c_str() + prefix.size(), nullptr, 10);
            if (index < places.size())
                message = places[index] + ": " + message.substr(file.size() + 2);
            return true;
        };
        if (!entry_of("objects", object_places) && !entry_of("lights", light_places) &&
            !background_place.empty() && message.rfind(file + ": /background", 0) == 0)
            message = background_place + ": " + message.substr(file.size() + 2);
        throw SceneError(message);
    }
}

std::function<void(const std::string&)> warner(const LoadOptions& options) {
    return [&options](const std::string& message) {
        if (options.warn)
            options.warn(message);
        else
            std::cerr << message << "\n";
    };
}

// A Mitsuba XML file: translated into our JSON, then built as any JSON scene.
Scene load_mitsuba(const fs::path& path, const LoadOptions& options) {
    if (!options.camera.empty())
        throw SceneError(path.string() + ": --camera chooses among a glTF file's cameras; a "
                                         "Mitsuba scene has one sensor");
    MitsubaDocument doc = translate_mitsuba_xml(path, options.params, warner(options), options.asset_root);
    return build_translated(path, options, std::move(doc.scene), doc.object_places,
                            doc.light_places, doc.background_place, nullptr);
}

// A pbrt-v4 file: the same, its written-out meshes held in memory.
Scene load_pbrt(const fs::path& path, const LoadOptions& options) {
    if (!options.camera.empty())
        throw SceneError(path.string() + ": --camera chooses among a glTF file's cameras; a "
                                         "pbrt scene has one camera");
    if (!options.params.empty())
        throw SceneError(path.string() + ": -D sets a Mitsuba scene's parameters; a pbrt "
                                         "scene has none");
    PbrtDocument doc = translate_pbrt(path, warner(options), options.asset_root);
    return build_translated(path, options, std::move(doc.scene), doc.object_places,
                            doc.light_places, doc.background_place, &doc.meshes);
}

namespace {

// Every "file" string of a scene document, from relative to `from` to relative to `to`; those
// in `renamed` replaced by what it maps them to.
void rebase_files(nlohmann::json& j, const fs::path& from, const fs::path& to,
                  const std::map<std::string, std::string>& renamed) {
    if (j.is_object()) {
        for (auto& [key, value] : j.items()) {
            if (key == "file" && value.is_string()) {
                if (auto it = renamed.find(value.get<std::string>()); it != renamed.end()) {
                    value = it->second;
                    continue;
                }
                fs::path p = value.get<std::string>();
                if (p.is_relative()) {
                    const fs::path target = fs::absolute(from / p).lexically_normal();
                    const fs::path rel = target.lexically_relative(fs::absolute(to).lexically_normal());
                    value = (rel.empty() ? target : rel).generic_string();
                }
            } else {
                rebase_files(value, from, to, renamed);
            }
        }
    } else if (j.is_array()) {
        for (auto& value : j) rebase_files(value, from, to, renamed);
    }
}

void write_text(const fs::path& path, const std::string& text) {
    try {
        write_file_atomically(path, std::vector<unsigned char>(text.begin(), text.end()));
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(path.string() + ": " + e.what());
    }
}

}  // namespace

std::vector<fs::path> convert_scene(const fs::path& path, const fs::path& output,
                                    const LoadOptions& options) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext == ".gltf" || ext == ".glb")
        throw SceneError(path.string() + ": convert reads Mitsuba XML, pbrt and JSON scenes; a "
                                         "glTF file renders as it is");
    load_scene(path, options);  // the same checks and errors as a render
    const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    nlohmann::json doc;
    std::map<std::string, PbrtMesh> meshes;
    if (ext == ".xml" || ext == ".pbrt") {
        if (ext == ".xml") {
            doc = translate_mitsuba_xml(path, options.params, [](const std::string&) {}).scene;
        } else {
            PbrtDocument pbrt = translate_pbrt(path, [](const std::string&) {});
            doc = std::move(pbrt.scene);
            meshes = std::move(pbrt.meshes);
        }
        doc["description"] = "converted from " + path.filename().string() + " by wavetrace convert";
    } else {
        doc = std::move(json_reader::parse(read_input_file(path), path.string()).root);
    }
    // Meshes written out in the scene file become PLY files in a folder of their own.
    std::map<std::string, std::string> renamed;
    std::vector<fs::path> written;
    const std::string mesh_folder = output.stem().string() + "-meshes";
    if (!meshes.empty()) {
        std::error_code ec;
        fs::create_directories(folder / mesh_folder, ec);
        if (ec) throw std::runtime_error((folder / mesh_folder).string() + ": cannot create: " + ec.message());
    }
    for (const auto& [name, mesh] : meshes) {
        const std::string file = mesh_folder + "/mesh-" + name.substr(name.rfind('/') + 1) + ".ply";
        renamed[name] = file;
        const std::vector<unsigned char> bytes =
            encode_ply(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
        try {
            write_file_atomically(folder / file, bytes);
        } catch (const std::runtime_error& e) {
            throw std::runtime_error((folder / file).string() + ": " + e.what());
        }
        written.push_back(folder / file);
    }
    rebase_files(doc, path.parent_path(), folder, renamed);
    write_text(output, doc.dump(1) + "\n");
    written.push_back(output);
    return written;
}

Scene load_scene(const fs::path& path, const LoadOptions& options) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext == ".gltf" || ext == ".glb") return Loader(path, options).load_gltf(ext == ".glb");
    if (ext == ".xml") return load_mitsuba(path, options);
    if (ext == ".pbrt") return load_pbrt(path, options);
    return Loader(path, options).load();
}

}  // namespace wavetrace
