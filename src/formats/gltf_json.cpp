#include "formats/gltf_json.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "files/input_file.h"
#include "formats/json_reader.h"

namespace wavetrace {
namespace {

uint32_t le32(const std::string& s, size_t at) {
    uint32_t v;
    std::memcpy(&v, s.data() + at, 4);
    return v;  // glTF is little-endian, as every platform we build for
}

// The whole file.
// The JSON text of a .gltf, or of a .glb's first chunk: the 12-byte header (magic "glTF",
// version 2, total length) and a chunk of type "JSON" whose length fits in the file (glTF 2.0
// specification, "Binary glTF Layout").
std::string json_text(const std::string& bytes, bool binary) {
    if (!binary) return bytes;
    if (bytes.size() < 20 || le32(bytes, 0) != 0x46546C67u || le32(bytes, 4) != 2)
        throw std::runtime_error("not a binary glTF 2.0 file (header)");
    const uint32_t length = le32(bytes, 12), type = le32(bytes, 16);
    if (type != 0x4E4F534Au || length > bytes.size() - 20)
        throw std::runtime_error("binary glTF: the first chunk is no JSON chunk within the file");
    return bytes.substr(20, length);
}

// A 4 x 4 affine matrix, m[row][column], in double.
struct Mat4 {
    double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    Mat4 operator*(const Mat4& b) const {
        Mat4 r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                r.m[i][j] = 0;
                for (int k = 0; k < 4; ++k) r.m[i][j] += m[i][k] * b.m[k][j];
            }
        return r;
    }
    Vec3 point(double x, double y, double z) const {
        return {float(m[0][0] * x + m[0][1] * y + m[0][2] * z + m[0][3]),
                float(m[1][0] * x + m[1][1] * y + m[1][2] * z + m[1][3]),
                float(m[2][0] * x + m[2][1] * y + m[2][2] * z + m[2][3])};
    }
    Vec3 vector(double x, double y, double z) const {
        return {float(m[0][0] * x + m[0][1] * y + m[0][2] * z),
                float(m[1][0] * x + m[1][1] * y + m[1][2] * z),
                float(m[2][0] * x + m[2][1] * y + m[2][2] * z)};
    }
};

// `count` finite numbers at key `key` of object `o`, or `fallback` where the key is absent.
std::vector<double> numbers(const json_reader::json& o, const char* key, size_t count,
                            std::vector<double> fallback, const std::string& where) {
    if (!o.contains(key)) return fallback;
    const auto& a = o[key];
    if (!a.is_array() || a.size() != count)
        throw std::runtime_error(where + "/" + key + ": expected " + std::to_string(count) +
                                 " numbers");
    std::vector<double> out;
    for (const auto& x : a) {
        if (!x.is_number() || !std::isfinite(x.get<double>()))
            throw std::runtime_error(where + "/" + key + ": expected finite numbers");
        out.push_back(x.get<double>());
    }
    return out;
}

double number(const json_reader::json& o, const char* key, double fallback,
              const std::string& where) {
    if (!o.contains(key)) return fallback;
    const auto& x = o[key];
    if (!x.is_number() || !std::isfinite(x.get<double>()))
        throw std::runtime_error(where + "/" + key + ": expected a finite number");
    return x.get<double>();
}

// A node's local matrix: `matrix` (column-major), or T R S from translation, rotation and scale.
Mat4 local_matrix(const json_reader::json& node, const std::string& where) {
    Mat4 r;
    if (node.contains("matrix")) {
        const std::vector<double> a = numbers(node, "matrix", 16, {}, where);
        for (int c = 0; c < 4; ++c)
            for (int row = 0; row < 4; ++row) r.m[row][c] = a[size_t(c) * 4 + row];
        return r;
    }
    const std::vector<double> t = numbers(node, "translation", 3, {0, 0, 0}, where);
    std::vector<double> q = numbers(node, "rotation", 4, {0, 0, 0, 1}, where);
    const std::vector<double> s = numbers(node, "scale", 3, {1, 1, 1}, where);
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(len > 0)) throw std::runtime_error(where + "/rotation: a zero quaternion");
    for (double& c : q) c /= len;
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double rot[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                              {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                              {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) r.m[i][j] = rot[i][j] * s[size_t(j)];
        r.m[i][3] = t[size_t(i)];
    }
    return r;
}

Vec3 unit(Vec3 v, const std::string& what) {
    const float l = length(v);
    if (!(l > 1e-12f) || !std::isfinite(l))
        throw std::runtime_error(what + ": its transform collapses or overflows a direction");
    return v / l;
}

}  // namespace

GltfPlacements gltf_placements(const std::filesystem::path& path, bool binary) {
    const json_reader::Document document =
        json_reader::parse(json_text(read_input_file(path), binary), "glTF JSON");
    const json_reader::json& doc = document.root;
    GltfPlacements out;
    const auto empty = json_reader::json::array();
    auto array = [&](const json_reader::json& o, const char* key) -> const json_reader::json& {
        return o.contains(key) && o[key].is_array() ? o[key] : empty;
    };
    const auto& nodes = array(doc, "nodes");
    const auto& cameras = array(doc, "cameras");
    const auto& scenes = array(doc, "scenes");
    const json_reader::json* lights = &empty;
    if (doc.contains("extensions") && doc["extensions"].is_object() &&
        doc["extensions"].contains("KHR_lights_punctual"))
        lights = &array(doc["extensions"]["KHR_lights_punctual"], "lights");
    size_t scene = 0;
    if (doc.contains("scene")) {
        if (!doc["scene"].is_number_unsigned() || doc["scene"].get<size_t>() >= scenes.size())
            throw std::runtime_error("/scene: no such scene");
        scene = doc["scene"].get<size_t>();
    }
    if (scene >= scenes.size()) return out;
    auto index = [](const json_reader::json& v, size_t size, const std::string& where) {
        if (!v.is_number_unsigned() || v.get<size_t>() >= size)
            throw std::runtime_error(where + ": expected an index below " + std::to_string(size));
        return v.get<size_t>();
    };
    // Depth first, each node with the product of its ancestors' matrices; a node met twice is a
    // cycle or a node shared by two parents, both invalid glTF.
    std::vector<bool> seen(nodes.size(), false);
    struct Entry {
        size_t node;
        Mat4 parent;
        int depth;
    };
    std::vector<Entry> stack;
    const std::string scene_where = "/scenes/" + std::to_string(scene) + "/nodes";
    const auto& roots = array(scenes[scene], "nodes");
    for (size_t i = roots.size(); i-- > 0;)
        stack.push_back({index(roots[i], nodes.size(), scene_where + "/" + std::to_string(i)),
                         Mat4{}, 0});
    while (!stack.empty()) {
        const Entry e = stack.back();
        stack.pop_back();
        const std::string where = "/nodes/" + std::to_string(e.node);
        if (seen[e.node]) throw std::runtime_error(where + ": reached twice (a cycle?)");
        if (e.depth > kMaxGltfNodeDepth)
            throw std::runtime_error(where + ": nested deeper than " +
                                     std::to_string(kMaxGltfNodeDepth) + " nodes");
        seen[e.node] = true;
        const auto& node = nodes[e.node];
        if (!node.is_object()) throw std::runtime_error(where + ": expected an object");
        const Mat4 world = e.parent * local_matrix(node, where);
        if (node.contains("camera")) {
            const size_t c = index(node["camera"], cameras.size(), where + "/camera");
            const auto& cam = cameras[c];
            const std::string cam_where = "/cameras/" + std::to_string(c);
            const bool ortho =
                cam.is_object() && cam.contains("orthographic") && cam["orthographic"].is_object();
            if (!ortho && (!cam.is_object() || !cam.contains("perspective") ||
                           !cam["perspective"].is_object())) {
                out.warnings.push_back(cam_where +
                                       ": neither a perspective nor an orthographic "
                                       "camera; left out");
            } else {
                GltfCamera g;
                g.pointer = where;
                g.name = cam.contains("name") && cam["name"].is_string()
                             ? cam["name"].get<std::string>()
                             : node.contains("name") && node["name"].is_string()
                                   ? node["name"].get<std::string>()
                                   : "camera " + std::to_string(c);
                if (ortho) {
                    // xmag and ymag: half the view's width and height (the specification's
                    // "magnifications").
                    const std::string o_where = cam_where + "/orthographic";
                    const double xmag = std::fabs(number(cam["orthographic"], "xmag", 0, o_where));
                    const double ymag = std::fabs(number(cam["orthographic"], "ymag", 0, o_where));
                    if (!(xmag > 0 && ymag > 0 && xmag <= 1e7 && ymag <= 1e7 && xmag / ymag < 100 &&
                          ymag / xmag < 100))
                        throw std::runtime_error(o_where +
                                                 ": expected xmag and ymag in (0, 1e7], "
                                                 "their ratio within 100");
                    g.orthographic = true;
                    g.view_width = float(2 * xmag);
                    g.view_height = float(2 * ymag);
                    g.aspect = float(xmag / ymag);
                } else {
                    const double yfov =
                        number(cam["perspective"], "yfov", -1, cam_where + "/perspective");
                    if (!(yfov > 0 && yfov < 3.12))
                        throw std::runtime_error(cam_where +
                                                 "/perspective/yfov: expected "
                                                 "radians in (0, 3.12)");
                    g.yfov_degrees = float(yfov * 180.0 / 3.14159265358979323846);
                    g.aspect = float(
                        number(cam["perspective"], "aspectRatio", 0, cam_where + "/perspective"));
                    if (!(g.aspect >= 0 && g.aspect < 100))
                        throw std::runtime_error(cam_where +
                                                 "/perspective/aspectRatio: expected (0, 100)");
                }
                g.position = world.point(0, 0, 0);
                g.forward = unit(world.vector(0, 0, -1), where);
                g.up = unit(world.vector(0, 1, 0), where);
                out.cameras.push_back(g);
            }
        }
        if (node.contains("extensions") && node["extensions"].is_object() &&
            node["extensions"].contains("KHR_lights_punctual")) {
            const auto& ref = node["extensions"]["KHR_lights_punctual"];
            const std::string ref_where = where + "/extensions/KHR_lights_punctual/light";
            if (!ref.is_object() || !ref.contains("light"))
                throw std::runtime_error(ref_where + ": missing");
            const size_t l = index(ref["light"], lights->size(), ref_where);
            const auto& light = (*lights)[l];
            GltfLight g;
            g.pointer = "/extensions/KHR_lights_punctual/lights/" + std::to_string(l);
            if (!light.is_object() || !light.contains("type") || !light["type"].is_string())
                throw std::runtime_error(g.pointer + "/type: missing");
            const std::string type = light["type"].get<std::string>();
            if (type == "point")
                g.kind = GltfLight::Kind::Point;
            else if (type == "spot")
                g.kind = GltfLight::Kind::Spot;
            else if (type == "directional")
                g.kind = GltfLight::Kind::Directional;
            else
                throw std::runtime_error(g.pointer + "/type: unknown light type \"" + type + "\"");
            const std::vector<double> c = numbers(light, "color", 3, {1, 1, 1}, g.pointer);
            const double intensity = number(light, "intensity", 1, g.pointer);
            for (double x : c)
                if (!(x >= 0 && x * intensity <= 1e9 && intensity >= 0))
                    throw std::runtime_error(g.pointer +
                                             ": color and intensity must be non-negative");
            g.color = Color(float(c[0] * intensity), float(c[1] * intensity),
                            float(c[2] * intensity));
            if (g.kind == GltfLight::Kind::Spot) {
                const json_reader::json spot = light.contains("spot") ? light["spot"]
                                                                      : json_reader::json::object();
                const double inner = number(spot, "innerConeAngle", 0, g.pointer + "/spot");
                const double outer =
                    number(spot, "outerConeAngle", 3.14159265358979323846 / 4, g.pointer + "/spot");
                if (!(inner >= 0 && inner < outer && outer <= 3.14159265358979323846 / 2))
                    throw std::runtime_error(g.pointer + "/spot: expected 0 <= innerConeAngle < "
                                             "outerConeAngle <= pi / 2");
                g.inner_degrees = float(inner * 180.0 / 3.14159265358979323846);
                g.outer_degrees = float(outer * 180.0 / 3.14159265358979323846);
            }
            g.has_range = light.contains("range");
            g.position = world.point(0, 0, 0);
            g.direction = unit(world.vector(0, 0, -1), where);
            out.lights.push_back(g);
        }
        const auto& children = array(node, "children");
        for (size_t i = children.size(); i-- > 0;)
            stack.push_back({index(children[i], nodes.size(),
                                   where + "/children/" + std::to_string(i)),
                             world, e.depth + 1});
    }
    return out;
}

json_reader::Document check_gltf(const std::filesystem::path& path, bool binary) {
    const std::string bytes = read_input_file(path);
    const std::string text = json_text(bytes, binary);
    if (binary) {
        // Every chunk within the length the header gives, and that length within the file.
        const uint64_t length = le32(bytes, 8);
        if (length > bytes.size())
            throw std::runtime_error("binary glTF: the header claims " + std::to_string(length) +
                                     " bytes; the file has " + std::to_string(bytes.size()));
        for (uint64_t at = 12; at + 8 <= length;) {
            const uint64_t chunk = le32(bytes, size_t(at));
            if (chunk > length - at - 8)
                throw std::runtime_error("binary glTF: the chunk at byte " + std::to_string(at) +
                                         " claims " + std::to_string(chunk) +
                                         " bytes, beyond the file's length");
            at += 8 + chunk;
        }
    }
    json_reader::Document document = json_reader::parse(text, "glTF JSON");
    const json_reader::json& doc = document.root;
    if (!doc.contains("nodes") || !doc["nodes"].is_array()) return document;
    const auto& nodes = doc["nodes"];
    // Each node at most one parent (glTF 2.0, "Nodes and Hierarchy"), then depth first from the
    // roots: a node never reached sits on a cycle.
    std::vector<int> parents(nodes.size(), 0);
    std::vector<std::vector<size_t>> children(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (!nodes[i].is_object() || !nodes[i].contains("children")) continue;
        const auto& list = nodes[i]["children"];
        if (!list.is_array()) continue;
        for (const auto& c : list) {
            if (!c.is_number_unsigned() || c.get<size_t>() >= nodes.size())
                throw std::runtime_error("/nodes/" + std::to_string(i) +
                                         "/children: expected node indices below " +
                                         std::to_string(nodes.size()));
            const size_t child = c.get<size_t>();
            if (++parents[child] > 1)
                throw std::runtime_error("/nodes/" + std::to_string(child) +
                                         ": a child of two nodes (or twice of one)");
            children[i].push_back(child);
        }
    }
    std::vector<std::pair<size_t, int>> stack;
    for (size_t i = 0; i < nodes.size(); ++i)
        if (parents[i] == 0) stack.push_back({i, 1});
    size_t reached = 0;
    while (!stack.empty()) {
        const auto [node, depth] = stack.back();
        stack.pop_back();
        ++reached;
        if (depth > kMaxGltfNodeDepth)
            throw std::runtime_error("/nodes/" + std::to_string(node) + ": nested deeper than " +
                                     std::to_string(kMaxGltfNodeDepth) + " nodes");
        for (size_t c : children[node]) stack.push_back({c, depth + 1});
    }
    if (reached != nodes.size()) throw std::runtime_error("/nodes: the hierarchy has a cycle");
    return document;
}

std::vector<float> gltf_emissive_strengths(const json_reader::json& doc) {
    std::vector<float> out;
    const auto materials = doc.find("materials");
    if (materials == doc.end() || !materials->is_array()) return out;
    for (size_t i = 0; i < materials->size(); ++i) {
        float strength = 1.0f;
        const auto& m = (*materials)[i];
        if (m.is_object() && m.contains("extensions") && m["extensions"].is_object() &&
            m["extensions"].contains("KHR_materials_emissive_strength")) {
            const auto& ext = m["extensions"]["KHR_materials_emissive_strength"];
            if (ext.is_object() && ext.contains("emissiveStrength")) {
                const auto& s = ext["emissiveStrength"];
                const double v = s.is_number() ? s.get<double>() : -1.0;
                if (!(v >= 0.0 && v <= 1e6))
                    throw std::runtime_error(
                        "material " + std::to_string(i) +
                        ": KHR_materials_emissive_strength's emissiveStrength must be a number in "
                        "[0, 1e6], got " + s.dump());
                strength = float(v);
            }
        }
        out.push_back(strength);
    }
    return out;
}

namespace {

const char* const kTextureTransform = "KHR_texture_transform";

// The extension names of `j`'s "extensions" objects at any depth into `names` (once each), but
// those of `read` at the top and KHR_texture_transform below it.
void unread_extensions(const json_reader::json& j,
                       const std::vector<std::string>& read,
                       std::vector<std::string>* names) {
    static const std::vector<std::string> kReadBelow = {kTextureTransform};
    if (j.is_array()) {
        for (const auto& e : j) unread_extensions(e, kReadBelow, names);
        return;
    }
    if (!j.is_object()) return;
    for (const auto& [key, value] : j.items()) {
        if (key == "extensions" && value.is_object()) {
            for (const auto& [name, ext] : value.items()) {
                if (std::find(read.begin(), read.end(), name) == read.end() &&
                    std::find(names->begin(), names->end(), name) == names->end())
                    names->push_back(name);
                unread_extensions(ext, kReadBelow, names);
            }
        } else if (key != "extras") {
            unread_extensions(value, kReadBelow, names);
        }
    }
}

// The transforms of the textures (keys ending in "Texture") in `j`, at any depth, and those
// of the textures that read another uv set than the first (no transform but their uv set).
void texture_transforms(const json_reader::json& j,
                        const std::string& pointer,
                        std::vector<std::pair<std::string, GltfUvTransform>>* out) {
    if (!j.is_object()) return;
    for (const auto& [key, value] : j.items()) {
        if (key == "extras" || !value.is_object()) continue;
        const std::string at = pointer + "/" + key;
        const bool texture = key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0;
        // The uv set a textureInfo names (texCoord), a transform's own overriding it.
        auto uv_set = [](const json_reader::json& v, const std::string& where) {
            const double d = v.is_number() ? v.get<double>() : NAN;
            if (!(d >= 0 && d <= 1e6 && d == std::floor(d)))
                throw std::runtime_error(where + "/texCoord: expected a uv set's index");
            return int(d);
        };
        const int info_set =
            texture && value.contains("texCoord") ? uv_set(value["texCoord"], at) : 0;
        if (texture && value.contains("extensions") && value["extensions"].is_object() &&
            value["extensions"].contains(kTextureTransform)) {
            const auto& x = value["extensions"][kTextureTransform];
            const std::string where = at + "/extensions/" + kTextureTransform;
            if (!x.is_object()) throw std::runtime_error(where + ": expected an object");
            auto number = [&](const json_reader::json& v, const std::string& name) {
                const double d = v.is_number() ? v.get<double>() : NAN;
                if (!(std::abs(d) <= 1e6))
                    throw std::runtime_error(where + "/" + name +
                                             ": expected a number of magnitude at most 1e6");
                return float(d);
            };
            auto pair = [&](const char* name, float* two) {
                if (!x.contains(name)) return;
                const auto& v = x[name];
                if (!v.is_array() || v.size() != 2)
                    throw std::runtime_error(where + "/" + name + ": expected two numbers");
                two[0] = number(v[0], std::string(name) + "/0");
                two[1] = number(v[1], std::string(name) + "/1");
            };
            GltfUvTransform t;
            pair("offset", t.offset);
            pair("scale", t.scale);
            if (x.contains("rotation")) t.rotation = number(x["rotation"], "rotation");
            t.tex_coord = x.contains("texCoord") ? uv_set(x["texCoord"], where) : info_set;
            out->push_back({key, t});
        } else if (info_set > 0) {
            GltfUvTransform t;
            t.tex_coord = info_set;
            out->push_back({key, t});
        }
        texture_transforms(value, at, out);
    }
}

}  // namespace

std::vector<std::vector<std::pair<std::string, GltfUvTransform>>> gltf_texture_transforms(
    const json_reader::json& doc) {
    std::vector<std::vector<std::pair<std::string, GltfUvTransform>>> out;
    const auto materials = doc.find("materials");
    if (materials == doc.end() || !materials->is_array()) return out;
    for (size_t i = 0; i < materials->size(); ++i) {
        out.emplace_back();
        texture_transforms((*materials)[i], "/materials/" + std::to_string(i), &out.back());
    }
    return out;
}

std::vector<std::vector<std::string>> gltf_unread_material_extensions(
    const json_reader::json& doc) {
    static const std::vector<std::string> kRead = {
        "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission",
        "KHR_materials_clearcoat"};
    std::vector<std::vector<std::string>> out;
    const auto materials = doc.find("materials");
    if (materials == doc.end() || !materials->is_array()) return out;
    for (const auto& m : *materials) {
        std::vector<std::string> names;
        unread_extensions(m, kRead, &names);
        out.push_back(std::move(names));
    }
    return out;
}

}  // namespace wavetrace
