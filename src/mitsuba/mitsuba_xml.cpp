// Mitsuba 3 XML -> our JSON scene document. Two steps: the files are read into one tree of
// elements (includes spliced in, $parameters substituted, 0.5/0.6 names upgraded as Mitsuba 3's
// own parser upgrades them), then the tree is translated plugin by plugin. Mitsuba's scene
// format and plugin parameters are documented in its manual ("Scene file format", "Plugin
// reference"); every default below is the manual's.
#include "mitsuba/mitsuba_xml.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <pugixml.hpp>
#include <set>

#include "files/confinement.h"
#include "files/input_file.h"
#include "formats/affine.h"
#include "formats/spectrum_rgb.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr int kMaxIncludeDepth = 15;  // Mitsuba 3's own limit
constexpr int kMaxNesting = 64;       // elements inside elements
constexpr size_t kMaxElements = 1u << 22;

// One XML element after includes and parameters: its tag, attributes and children, and where
// it was written ("scenes/a.xml:12").
struct Element {
    std::string tag;
    std::vector<std::pair<std::string, std::string>> attrs;
    std::vector<Element> children;
    std::string place;

    const std::string* attr(const std::string& name) const {
        for (const auto& [k, v] : attrs)
            if (k == name) return &v;
        return nullptr;
    }
    std::string attr_or(const std::string& name, const std::string& fallback) const {
        const std::string* v = attr(name);
        return v ? *v : fallback;
    }
};

[[noreturn]] void fail(const std::string& place, const std::string& message) {
    throw SceneError(place + ": " + message);
}
[[noreturn]] void fail(const Element& e, const std::string& message) { fail(e.place, message); }

std::vector<std::string> tokens(const std::string& text, const char* separators = ", \t\r\n") {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < text.size()) {
        const size_t start = text.find_first_not_of(separators, i);
        if (start == std::string::npos) break;
        const size_t end = text.find_first_of(separators, start);
        out.push_back(text.substr(start, end - start));
        i = end == std::string::npos ? text.size() : end;
    }
    return out;
}

double parse_number(const Element& e, const std::string& text) {
    const char* begin = text.c_str();
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || *end != '\0' || !std::isfinite(v))
        fail(e, "<" + e.tag + ">: expected a finite number, got \"" + text + "\"");
    return v;
}

// camelCase -> snake_case as Mitsuba 3 upgrades 0.5/0.6 property names: an underscore before
// each upper-case run that follows a lower-case letter, the run lower-cased ("intIOR" ->
// "int_ior", "toWorld" -> "to_world").
std::string snake_case(std::string name) {
    for (size_t i = 0; i + 1 < name.size(); ++i) {
        if (std::islower(static_cast<unsigned char>(name[i])) &&
            std::isupper(static_cast<unsigned char>(name[i + 1]))) {
            name.insert(i + 1, "_");
            i += 2;
            while (i < name.size() && std::isupper(static_cast<unsigned char>(name[i]))) {
                name[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[i])));
                ++i;
            }
        }
    }
    return name;
}

// ---------------------------------------------------------------------------------------------
// Reading: files -> one element tree.

class Reader {
  public:
    Reader(const fs::path& main,
           const std::map<std::string, std::string>& params,
           const fs::path& asset_root)
        : params_(params), asset_root_(asset_root) {
        search_.push_back(main.parent_path());
    }

    // Throws std::runtime_error unless `p` lies inside the asset root (if there is one).
    void confine(const fs::path& p) const {
        if (std::string why = Confinement{{}, asset_root_}.problem(p); !why.empty())
            throw std::runtime_error(why);
    }

    Element read_main(const fs::path& path) {
        std::vector<Element> roots = read_file(path, "", true);
        return std::move(roots.front());
    }

    const std::vector<fs::path>& search_paths() const { return search_; }

    // A file named in the scene: absolute, or found in the <path> folders (the latest first),
    // then in the main file's folder, as Mitsuba's file resolver looks.
    fs::path resolve(const std::string& name, const Element& where) const {
        if (name.empty()) fail(where, "empty file name");
        if (name.find('\0') != std::string::npos) fail(where, "a file name holds a NUL byte");
        fs::path p(name);
        if (p.is_absolute()) return p;
        std::error_code ec;
        for (const fs::path& dir : search_)
            if (fs::exists(dir / p, ec)) return dir / p;
        return search_.back() / p;
    }

  private:
    struct Source {
        std::string name;
        std::vector<size_t> line_starts;  // the offsets of the newlines
        // 1 + the newlines before `offset`.
        int line(ptrdiff_t offset) const {
            const size_t at = static_cast<size_t>(std::max<ptrdiff_t>(offset, 0));
            return 1 + static_cast<int>(std::lower_bound(line_starts.begin(), line_starts.end(),
                                                         at) -
                                        line_starts.begin());
        }
    };

    // The file's root element(s): a <scene> root gives its children (to splice into the
    // including element), any other root itself.
    std::vector<Element> read_file(const fs::path& path, const std::string& from, bool main) {
        const std::string name = path.string();
        const std::string who = from.empty() ? name : from;
        try {
            check_input_file(path, kMaxSceneFileBytes, "scene files");
            confine(path);
        } catch (const std::runtime_error& e) {
            fail(who, (from.empty() ? "cannot open scene file: " : "cannot include '" + name +
                                                                       "': ") +
                          e.what());
        }
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(path, ec);
        for (const fs::path& open : stack_)
            if (open == canonical) fail(who, "include cycle: '" + name + "' includes itself");
        if (static_cast<int>(stack_.size()) > kMaxIncludeDepth)
            fail(who, "includes nested deeper than " + std::to_string(kMaxIncludeDepth));

        std::string text;
        try {
            text = read_input_file(path);
        } catch (const std::runtime_error& e) {
            fail(who, (from.empty() ? "cannot read scene file: " : "cannot include '" + name +
                                                                       "': ") +
                          e.what());
        }
        Source source{name, {}};
        for (size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n') source.line_starts.push_back(i);

        pugi::xml_document doc;
        const pugi::xml_parse_result parsed = doc.load_buffer(
            text.data(), text.size(), pugi::parse_default | pugi::parse_doctype);
        if (!parsed)
            fail(name + ":" + std::to_string(source.line(parsed.offset)),
                 std::string("XML: ") + parsed.description());
        for (pugi::xml_node n : doc.children())
            if (n.type() == pugi::node_doctype)
                fail(name + ":" + std::to_string(source.line(n.offset_debug())),
                     "a DOCTYPE is not accepted (entities are not expanded)");
        const pugi::xml_node root = doc.document_element();
        if (!root) fail(name, "no root element");
        const std::string root_place = name + ":" + std::to_string(source.line(root.offset_debug()));

        bool legacy = false;
        if (const pugi::xml_attribute version = root.attribute("version")) {
            const std::vector<std::string> parts = tokens(version.value(), ". ");
            int major = -1;
            if (parts.size() == 3) major = std::atoi(parts[0].c_str());
            if (parts.size() != 3 || major < 0)
                fail(root_place, "version \"" + std::string(version.value()) +
                                     "\": expected three numbers, e.g. 3.0.0");
            legacy = major < 2;
        } else if (main) {
            fail(root_place, "the root element needs a version attribute (e.g. version=\"3.0.0\")");
        }
        if (main && std::string(root.name()) != "scene")
            fail(root_place, "the root element is <" + std::string(root.name()) +
                                 ">; a scene file's is <scene>");

        stack_.push_back(canonical);
        Element top;
        top.tag = root.name();
        top.place = root_place;
        const bool splice = top.tag == "scene";
        if (splice) {
            for (pugi::xml_node child : root.children())
                build(child, source, legacy, top, 1);
        } else {
            build(root, source, legacy, top, 1);
        }
        stack_.pop_back();
        if (main) return {std::move(top)};
        return std::move(top.children);
    }

    std::string substitute(const std::string& value, const std::string& place) const {
        if (value.find('$') == std::string::npos) return value;
        std::vector<std::pair<std::string, std::string>> sorted(params_.begin(), params_.end());
        std::sort(sorted.begin(), sorted.end(),
                  [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
        std::string out = value;
        for (const auto& [k, v] : sorted) {
            const std::string key = "$" + k;
            for (size_t at = out.find(key); at != std::string::npos;
                 at = out.find(key, at + v.size()))
                out.replace(at, key.size(), v);
        }
        if (out.find('$') != std::string::npos)
            fail(place, "undefined parameter in \"" + value +
                            "\" (give it with <default> or -D name=value)");
        return out;
    }

    void build(const pugi::xml_node& node, const Source& source, bool legacy, Element& parent,
               int depth) {
        if (node.type() == pugi::node_comment || node.type() == pugi::node_declaration ||
            node.type() == pugi::node_pi)
            return;
        const std::string place = source.name + ":" + std::to_string(source.line(node.offset_debug()));
        if (node.type() != pugi::node_element) {
            const std::string text = node.value();
            if (text.find_first_not_of(" \t\r\n") == std::string::npos) return;
            fail(place, "unexpected text \"" + text.substr(0, 40) + "\"");
        }
        if (depth > kMaxNesting)
            fail(place, "elements nested deeper than " + std::to_string(kMaxNesting));
        if (++elements_ > kMaxElements)
            fail(place, "more than " + std::to_string(kMaxElements) + " elements");

        Element e;
        e.tag = node.name();
        e.place = place;
        if (legacy && e.tag == "lookAt") e.tag = "lookat";
        for (pugi::xml_attribute a : node.attributes()) {
            std::string value = substitute(a.value(), place);
            if (legacy && std::string(a.name()) == "name" && e.tag != "default")
                value = snake_case(value);
            e.attrs.emplace_back(a.name(), value);
        }
        if (legacy && parent.tag == "bsdf" && parent.attr_or("type", "") == "diffuse") {
            for (auto& [k, v] : e.attrs)
                if (k == "name" && v == "diffuse_reflectance") v = "reflectance";
        }

        if (e.tag == "default") {
            const std::string* name = e.attr("name");
            const std::string* value = e.attr("value");
            if (!name || name->empty() || !value)
                fail(e, "<default> needs a name and a value");
            if (!params_.count(*name)) params_[*name] = *value;
            return;
        }
        if (e.tag == "path") {
            const std::string* value = e.attr("value");
            if (!value) fail(e, "<path> needs a value");
            if (depth != 1) fail(e, "<path> may only appear directly in <scene>");
            fs::path dir(*value);
            if (dir.is_absolute() == false) dir = fs::path(source.name).parent_path() / dir;
            std::error_code ec;
            if (!fs::is_directory(dir, ec)) fail(e, "<path>: no folder '" + dir.string() + "'");
            search_.insert(search_.begin(), dir);
            return;
        }
        if (e.tag == "include") {
            const std::string* file = e.attr("filename");
            if (!file) fail(e, "<include> needs a filename");
            for (Element& child : read_file(resolve(*file, e), place, false))
                parent.children.push_back(std::move(child));
            return;
        }
        for (pugi::xml_node child : node.children()) build(child, source, legacy, e, depth + 1);
        if (legacy) upgrade_uv_offsets(e);
        parent.children.push_back(std::move(e));
    }

    // 0.5/0.6 textures scaled and offset their uvs with floats; Mitsuba 3 has a to_uv
    // transform: translate by the offset, then scale.
    static void upgrade_uv_offsets(Element& e) {
        auto is_offset = [](const Element& c) {
            const std::string name = c.attr_or("name", "");
            return c.tag == "float" &&
                   (name == "uoffset" || name == "voffset" || name == "uscale" || name == "vscale");
        };
        if (std::none_of(e.children.begin(), e.children.end(), is_offset)) return;
        double uv[4] = {0, 0, 1, 1};  // uoffset, voffset, uscale, vscale
        std::vector<Element> kept;
        for (Element& c : e.children) {
            if (!is_offset(c)) {
                kept.push_back(std::move(c));
                continue;
            }
            const std::string name = c.attr_or("name", "");
            const int which = name == "uoffset" ? 0 : name == "voffset" ? 1 : name == "uscale" ? 2 : 3;
            uv[which] = parse_number(c, c.attr_or("value", ""));
        }
        Element t{"transform", {{"name", "to_uv"}}, {}, e.place};
        t.children.push_back(Element{"translate", {{"x", std::to_string(uv[0])},
                                                   {"y", std::to_string(uv[1])}}, {}, e.place});
        t.children.push_back(Element{"scale", {{"x", std::to_string(uv[2])},
                                               {"y", std::to_string(uv[3])}}, {}, e.place});
        kept.push_back(std::move(t));
        e.children = std::move(kept);
    }

    std::map<std::string, std::string> params_;
    std::vector<fs::path> search_;
    std::vector<fs::path> stack_;
    size_t elements_ = 0;
    fs::path asset_root_;
};

// ---------------------------------------------------------------------------------------------
// Transforms: the JSON steps (the JSON loader composes them exactly as a hand-written scene's)
// and, for cameras and lights, the same composition as a matrix.

using affine::add;
using affine::cross;
using affine::dot;
using affine::M4;
using affine::norm;
using affine::normalized;
using affine::sub;
using affine::to_json;
using affine::V3;

struct Xform {
    json steps = json::array();
    M4 m = affine::identity();

    void then(const M4& op) { m = affine::mul(op, m); }
    V3 point(double x, double y, double z) const { return affine::apply_point(m, {x, y, z}); }
    V3 vector(double x, double y, double z) const { return affine::apply_vector(m, {x, y, z}); }
};

V3 xyz(const Element& e, double fallback) {
    V3 v = {fallback, fallback, fallback};
    if (const std::string* value = e.attr("value")) {
        if (e.attr("x") || e.attr("y") || e.attr("z"))
            fail(e, "<" + e.tag + ">: give either value or x, y, z");
        const std::vector<std::string> t = tokens(*value);
        if (t.size() == 1) v = {parse_number(e, t[0]), parse_number(e, t[0]), parse_number(e, t[0])};
        else if (t.size() == 3)
            v = {parse_number(e, t[0]), parse_number(e, t[1]), parse_number(e, t[2])};
        else fail(e, "<" + e.tag + ">: value needs 1 or 3 numbers, got \"" + *value + "\"");
        return v;
    }
    const char* names[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
        if (const std::string* c = e.attr(names[i])) v[i] = parse_number(e, *c);
    return v;
}

V3 named_vector(const Element& e, const char* name) {
    const std::string* text = e.attr(name);
    if (!text) fail(e, "<" + e.tag + ">: needs " + name);
    const std::vector<std::string> t = tokens(*text);
    if (t.size() != 3) fail(e, "<" + e.tag + ">: " + name + " needs 3 numbers");
    return {parse_number(e, t[0]), parse_number(e, t[1]), parse_number(e, t[2])};
}

Xform read_transform(const Element& t) {
    Xform x;
    for (const Element& op : t.children) {
        M4 m = affine::identity();
        if (op.tag == "translate") {
            const V3 v = xyz(op, 0.0);
            for (int i = 0; i < 3; ++i) m[i * 4 + 3] = v[i];
            x.steps.push_back({{"translate", to_json(v)}});
        } else if (op.tag == "scale") {
            const V3 v = xyz(op, 1.0);
            for (int i = 0; i < 3; ++i) m[i * 5] = v[i];
            x.steps.push_back({{"scale", to_json(v)}});
        } else if (op.tag == "rotate") {
            const V3 axis = xyz(op, 0.0);
            const std::string* angle_text = op.attr("angle");
            if (!angle_text) fail(op, "<rotate> needs an angle");
            const double angle = parse_number(op, *angle_text);
            if (!(norm(axis) > 0)) fail(op, "<rotate>: the axis is zero");
            m = affine::rotation(angle, axis);
            x.steps.push_back({{"rotate", {{"axis", to_json(axis)}, {"degrees", angle}}}});
        } else if (op.tag == "matrix" || op.tag == "lookat") {
            if (op.tag == "matrix") {
                const std::vector<std::string> values = tokens(op.attr_or("value", ""));
                if (values.size() == 16) {
                    for (int k = 0; k < 16; ++k) m[k] = parse_number(op, values[k]);
                    if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
                        fail(op, "<matrix>: the last row must be 0 0 0 1 (no projective maps)");
                } else if (values.size() == 9) {
                    for (int k = 0; k < 9; ++k) m[k / 3 * 4 + k % 3] = parse_number(op, values[k]);
                } else {
                    fail(op, "<matrix>: expected 16 or 9 numbers, got " +
                                 std::to_string(values.size()));
                }
            } else {
                const V3 origin = named_vector(op, "origin"), target = named_vector(op, "target");
                V3 up = op.attr("up") ? named_vector(op, "up") : V3{0, 0, 0};
                const V3 dir = normalized(sub(target, origin));
                if (!(norm(sub(target, origin)) > 0)) fail(op, "<lookat>: target equals origin");
                if (!(norm(up) > 0)) up = std::abs(dir[0]) > 0.9 ? V3{0, 1, 0} : V3{1, 0, 0};
                const V3 left = normalized(cross(up, dir));
                if (!std::isfinite(left[0])) fail(op, "<lookat>: up is parallel to the view");
                const V3 new_up = cross(dir, left);
                for (int i = 0; i < 3; ++i) {
                    m[i * 4] = left[i];
                    m[i * 4 + 1] = new_up[i];
                    m[i * 4 + 2] = dir[i];
                    m[i * 4 + 3] = origin[i];
                }
            }
            json rows = json::array();
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 4; ++j) rows.push_back(m[i * 4 + j]);
            x.steps.push_back({{"matrix", rows}});
        } else {
            fail(op, "<" + op.tag + "> in a <transform> (expected translate, rotate, scale, "
                     "matrix or lookat)");
        }
        x.then(m);
    }
    return x;
}

// ---------------------------------------------------------------------------------------------
// Translation: the element tree -> our JSON.

class Translator {
  public:
    Translator(Reader& reader, const fs::path& main,
               const std::function<void(const std::string&)>& warn)
        : reader_(reader), base_(main.parent_path()), warn_(warn) {}

    MitsubaDocument translate(const Element& scene) {
        collect_ids(scene);
        out_["render"] = {{"width", 768}, {"height", 576}, {"max_depth", kMaxDepth}};
        out_["camera"] = {{"look_from", {0, 0, 0}}, {"look_at", {0, 0, 1}}, {"up", {0, 1, 0}}};
        out_["materials"] = json::object();
        out_["objects"] = json::array();
        bool sensor = false, integrator = false;
        for (const Element& e : scene.children) {
            if (e.tag == "sensor") {
                if (sensor) warn(e, "a second <sensor> is ignored (wavetrace renders the first)");
                else sensor_(e);
                sensor = true;
            } else if (e.tag == "integrator") {
                if (!integrator) integrator_(e);
                integrator = true;
            } else if (e.tag == "emitter") {
                emitter(e);
            } else if (e.tag == "shape") {
                if (e.attr_or("type", "") == "shapegroup") continue;  // drawn by its instances
                shape(e, out_["objects"], &doc_.object_places);
            } else if (e.tag == "bsdf" || e.tag == "texture" || e.tag == "medium" ||
                       e.tag == "spectrum" || e.tag == "rgb") {
                // Declared for reference by id; translated where used.
                if (!e.attr("id")) warn(e, "<" + e.tag + "> without an id is never used");
            } else {
                warn(e, "<" + e.tag + "> in <scene> is not supported; ignored");
            }
        }
        if (!sensor) warn(scene, "no <sensor>: Mitsuba's default camera at the origin looking down +z");
        if (!integrator) out_["render"]["max_depth"] = kMaxDepth;
        if (!media_.empty()) {
            out_["media"] = media_;
            // Mitsuba sets the medium at each crossing from the crossed shape alone.
            out_["medium_boundaries"] = "interface";
        }
        if (!lights_.empty()) out_["lights"] = lights_;
        // Mitsuba's BSDFs answer in the shading frame alone (no geometric-side test).
        out_["geometric_side_test"] = false;
        doc_.scene = std::move(out_);
        return std::move(doc_);
    }

  private:
    // ---- properties of an object element ----
    class Props {
      public:
        Props(const Element& e, Translator& t) : e_(e), t_(t) {}

        const Element* get(const std::string& name) {
            for (const Element& c : e_.children) {
                const std::string* n = c.attr("name");
                if (n && *n == name) {
                    used_.insert(name);
                    return t_.deref(c);
                }
            }
            return nullptr;
        }
        double number(const std::string& name, double fallback) {
            const Element* c = get(name);
            if (!c) return fallback;
            if (c->tag != "float" && c->tag != "integer")
                fail(*c, type_() + ": " + name + " should be a <float>");
            return parse_number(*c, c->attr_or("value", ""));
        }
        // An integer property within [lo, hi] (the film's size, a sample count, a depth).
        int integer(const std::string& name, int fallback, int lo, int hi) {
            const Element* c = get(name);
            if (!c) return fallback;
            const double v = number(name, fallback);
            if (!(v >= lo && v <= hi) || v != std::floor(v))
                fail(*c, type_() + ": " + name + " must be an integer in [" + std::to_string(lo) +
                             ", " + std::to_string(hi) + "], got " + c->attr_or("value", ""));
            return static_cast<int>(v);
        }
        bool boolean(const std::string& name, bool fallback) {
            const Element* c = get(name);
            if (!c) return fallback;
            std::string v = c->attr_or("value", "");
            std::transform(v.begin(), v.end(), v.begin(), [](unsigned char ch) {
                return static_cast<char>(std::tolower(ch));
            });
            if (c->tag != "boolean" || (v != "true" && v != "false"))
                fail(*c, type_() + ": " + name + " should be a <boolean> true or false");
            return v == "true";
        }
        std::string string(const std::string& name, const std::string& fallback) {
            const Element* c = get(name);
            if (!c) return fallback;
            if (c->tag != "string") fail(*c, type_() + ": " + name + " should be a <string>");
            return c->attr_or("value", "");
        }
        // A float or a string naming an index of refraction, as our JSON takes it.
        json ior(const std::string& name, const json& fallback) {
            const Element* c = get(name);
            if (!c) return fallback;
            if (c->tag == "string") return c->attr_or("value", "");
            if (c->tag == "float" || c->tag == "integer")
                return parse_number(*c, c->attr_or("value", ""));
            const json rgb = t_.color(*c, false, false);  // a spectrum: its mean
            if (rgb.is_number()) return rgb;
            if (!rgb.is_array()) fail(*c, type_() + ": " + name + " must be a number or a name");
            return (rgb[0].get<double>() + rgb[1].get<double>() + rgb[2].get<double>()) / 3;
        }
        Xform transform(const std::string& name) {
            const Element* c = get(name);
            if (!c) return {};
            if (c->tag != "transform") fail(*c, type_() + ": " + name + " should be a <transform>");
            return read_transform(*c);
        }
        // Unnamed nested objects of a tag (a shape's bsdf, a wrapper's nested bsdf).
        std::vector<const Element*> nested(const std::string& tag) {
            std::vector<const Element*> out;
            for (const Element& c : e_.children) {
                const Element* d = t_.deref(c);
                if (d->tag != tag) continue;
                if (const std::string* n = c.attr("name")) used_.insert(*n);
                out.push_back(d);
            }
            return out;
        }
        // Properties nobody read: a warning each, naming the plugin and place.
        void finish(std::initializer_list<const char*> quiet = {}) {
            for (const Element& c : e_.children) {
                const std::string* n = c.attr("name");
                if (!n || used_.count(*n)) continue;
                if (std::find_if(quiet.begin(), quiet.end(),
                                 [&](const char* q) { return *n == q; }) != quiet.end())
                    continue;
                t_.warn(c, type_() + ": property \"" + *n + "\" is not supported; ignored");
            }
        }

      private:
        std::string type_() const { return e_.tag + " \"" + e_.attr_or("type", "") + "\""; }
        const Element& e_;
        Translator& t_;
        std::set<std::string> used_;
    };

    void warn(const Element& e, const std::string& message) {
        warn_(e.place + ": warning: " + message);
    }

    void collect_ids(const Element& e) {
        for (const Element& c : e.children) {
            if (const std::string* id = c.attr("id"); id && c.tag != "ref") {
                auto [it, fresh] = ids_.emplace(*id, &c);
                if (!fresh)
                    fail(c, "duplicate id \"" + *id + "\" (first at " + it->second->place + ")");
            }
            collect_ids(c);
        }
    }

    // A <ref id="..."/> stands for the element of that id.
    const Element* deref(const Element& e) const {
        if (e.tag != "ref") return &e;
        const std::string* id = e.attr("id");
        if (!id) fail(e, "<ref> needs an id");
        auto it = ids_.find(*id);
        if (it == ids_.end()) fail(e, "no element with id \"" + *id + "\"");
        return it->second;
    }

    std::string file(const Element& where, const std::string& name) {
        const fs::path p = reader_.resolve(name, where);
        const fs::path rel = p.lexically_relative(base_);
        return (rel.empty() || p.is_absolute() ? p : rel).generic_string();
    }

    // ---- colours, spectra and textures ----

    // A colour-valued property: <rgb>, <spectrum> (constant, wavelength:value pairs, a file,
    // or a blackbody) or a texture. `bounded`: a reflectance (spectra clamped to [0, 1], as
    // Mitsuba's RGB variants clamp them); `emitter`: radiance; `scalar`: a texture is looked up
    // as a number (see texture()).
    json color(const Element& c, bool bounded, bool emitter, bool scalar = false) {
        if (c.tag == "rgb") {
            const std::vector<std::string> t = tokens(c.attr_or("value", ""));
            if (t.size() == 1) return parse_number(c, t[0]);
            if (t.size() != 3) fail(c, "<rgb> needs 1 or 3 numbers");
            return json::array({parse_number(c, t[0]), parse_number(c, t[1]),
                                parse_number(c, t[2])});
        }
        if (c.tag == "float" || c.tag == "integer") return parse_number(c, c.attr_or("value", ""));
        if (c.tag == "spectrum") {
            std::vector<std::pair<double, double>> points;
            if (c.attr_or("type", "") == "blackbody") {
                Props p(c, *this);
                const double kelvin = p.number("temperature", -1);
                if (!(kelvin > 0)) fail(c, "blackbody: needs a temperature > 0 (kelvin)");
                p.finish();
                for (int nm = 360; nm <= 830; nm += 5) points.emplace_back(nm, planck(nm, kelvin));
            } else if (const std::string* f = c.attr("filename")) {
                points = spectrum_file(c, *f);
            } else {
                const std::vector<std::string> t = tokens(c.attr_or("value", ""));
                if (t.size() == 1 && t[0].find(':') == std::string::npos)
                    return parse_number(c, t[0]);
                for (const std::string& pair : t) {
                    const std::vector<std::string> wv = tokens(pair, ":");
                    if (wv.size() != 2) fail(c, "<spectrum>: expected wavelength:value pairs");
                    points.emplace_back(parse_number(c, wv[0]), parse_number(c, wv[1]));
                }
            }
            check_spectrum(c, points);
            const Color rgb = spectrum_to_rgb(points, bounded && !emitter);
            return json::array({rgb.x, rgb.y, rgb.z});
        }
        if (c.tag == "texture") return texture(c, scalar);
        fail(c, "<" + c.tag + "> where a colour or texture is expected");
    }

    static void check_spectrum(const Element& c, const std::vector<std::pair<double, double>>& p) {
        if (p.size() < 2) fail(c, "<spectrum>: needs two or more wavelength:value pairs");
        for (size_t i = 1; i < p.size(); ++i)
            if (!(p[i].first > p[i - 1].first))
                fail(c, "<spectrum>: wavelengths must increase");
    }

    std::vector<std::pair<double, double>> spectrum_file(const Element& c, const std::string& f) {
        const fs::path p = reader_.resolve(f, c);
        try {
            check_input_file(p, uintmax_t(1) << 20, "spectrum files");
            reader_.confine(p);
        } catch (const std::runtime_error& e) {
            fail(c, "spectrum file '" + p.string() + "': " + e.what());
        }
        std::ifstream in(p);
        std::vector<std::pair<double, double>> points;
        std::string line;
        int number = 0;
        while (std::getline(in, line)) {
            ++number;
            const std::vector<std::string> t = tokens(line, " \t\r");
            if (t.empty() || t[0][0] == '#') continue;
            if (t.size() != 2)
                fail(p.string() + ":" + std::to_string(number), "expected \"wavelength value\"");
            points.emplace_back(parse_number(c, t[0]), parse_number(c, t[1]));
        }
        return points;
    }

    json uv_transform(const Element& where, const Xform& x) {
        // uv' = A uv + t, written as our scale, then rotation, then offset: A = R(theta) S.
        const double a = x.m[0], b = x.m[1], c = x.m[4], d = x.m[5];
        const double su = std::hypot(a, c), theta = std::atan2(c, a);
        const double sv = -std::sin(theta) * b + std::cos(theta) * d;
        const double shear = std::cos(theta) * b + std::sin(theta) * d;
        if (std::abs(shear) > 1e-6 * std::max(su, std::abs(sv)))
            warn(where, "to_uv shears the texture; wavetrace scales, rotates and offsets only "
                        "(the shear is dropped)");
        if (!(su > 0) || sv == 0) fail(where, "to_uv is singular");
        return {{"scale", json::array({su, sv})},
                {"rotate", theta * 180 / kPiD},
                {"offset", json::array({x.m[3], x.m[7]})}};
    }

    // `scalar`: the texture is looked up as one number (Mitsuba's Texture::eval_1: roughness,
    // opacity), not as a colour (eval). Mitsuba's checkerboard gives color0 where the two halves'
    // tests agree in eval and where they differ in eval_1 (src/textures/checkerboard.cpp, since
    // its first version): its references hold that phase, so a number's checker swaps colours.
    json texture(const Element& e, bool scalar = false) {
        const std::string type = e.attr_or("type", "");
        Props p(e, *this);
        json t;
        if (type == "bitmap") {
            const std::string f = p.string("filename", "");
            if (f.empty()) fail(e, "bitmap: needs a filename");
            t = {{"type", "image"}, {"file", file(e, f)}};
            if (p.boolean("raw", false)) t["raw"] = true;
            const std::string filter = p.string("filter_type", "bilinear");
            if (filter == "nearest")
                t["filter"] = "nearest";
            else if (filter != "bilinear")
                warn(e, "bitmap: filter_type \"" + filter + "\" is not supported; bilinear is used");
            const std::string wrap = p.string("wrap_mode", "repeat");
            if (wrap == "mirror" || wrap == "clamp")
                t["wrap"] = wrap;
            else if (wrap != "repeat")
                warn(e, "bitmap: wrap_mode \"" + wrap + "\" is not supported; repeat is used");
        } else if (type == "checkerboard") {
            json c0 = color_property(p, "color0", 0.4, true, false, scalar),
                 c1 = color_property(p, "color1", 0.2, true, false, scalar);
            if (scalar) std::swap(c0, c1);
            t = {{"type", "uv_checker"}, {"scale", 0.5}, {"even", c0}, {"odd", c1}};
        } else if (type == "mesh_attribute") {
            // The hit mesh's attribute, as the mesh reader names a PLY's further properties.
            t = {{"type", "mesh_attribute"}, {"name", p.string("name", "")}};
            if (const double scale = p.number("scale", 1.0); scale != 1.0) t["scale"] = scale;
            p.finish();
            return t;
        } else if (type == "rawconstant") {
            // Its value as it stands (a number, or a vector such as a flat normal map's).
            const Element* v = p.get("value");
            if (!v) fail(e, "rawconstant: needs a value");
            p.finish();
            return to_json(xyz(*v, 0.0));
        } else {
            warn(e, "texture \"" + type + "\" is not supported; a grey 0.5 stands for it");
            return 0.5;
        }
        const Element* to_uv = p.get("to_uv");
        if (to_uv && to_uv->tag != "transform") fail(*to_uv, "to_uv should be a <transform>");
        Xform x = to_uv ? read_transform(*to_uv) : Xform{};
        // Mitsuba looks a texture up at to_uv(uv_M), where uv_M is (u, 1 - v) of our uv on every
        // mesh and quad the reader writes (see shape(): flip_v) and v_M runs down an image from
        // its top row, ours up from its bottom row. With F(u, v) = (u, 1 - v): a checkerboard is
        // looked up at to_uv F, an image at F to_uv F (the identity without a to_uv).
        for (int row : {0, 4}) {  // to_uv F
            x.m[row + 3] += x.m[row + 1];
            x.m[row + 1] = -x.m[row + 1];
        }
        if (type == "bitmap") {  // F to_uv F
            for (int k : {4, 5, 7}) x.m[k] = -x.m[k];
            x.m[7] += 1;
        }
        if (to_uv || type == "checkerboard") t["uv_transform"] = uv_transform(to_uv ? *to_uv : e, x);
        p.finish({"format", "accel"});
        return t;
    }

    json color_property(Props& p, const std::string& name, const json& fallback, bool bounded,
                        bool emitter = false, bool scalar = false) {
        const Element* c = p.get(name);
        return c ? color(*c, bounded, emitter, scalar) : fallback;
    }

    // ---- materials ----

    // normalmap's and bumpmap's corrections of the mapped normal, on by default in Mitsuba 3.
    void mapped_normal_switches(Props& p, json& m) {
        m["flip_invalid_normals"] = p.boolean("flip_invalid_normals", true);
        m["bump_shadowing"] = p.boolean("use_shadowing_function", true);
    }

    // `anisotropic`: the material takes alpha_u and alpha_v, numbers or textures (conductors);
    // others their mean, numbers.
    void roughness(Props& p, json& m, const Element& e, const char* default_distribution,
                   bool anisotropic = false) {
        const std::string d = p.string("distribution", default_distribution);
        if (d != "ggx" && d != "beckmann") fail(e, "distribution \"" + d + "\" (expected ggx or beckmann)");
        auto textured = [&](const char* name) {
            const Element* c = p.get(name);
            return c && c->tag == "texture" ? c : nullptr;
        };
        if (anisotropic && (textured("alpha") || textured("alpha_u") || textured("alpha_v"))) {
            m["distribution"] = d;
            auto value = [&](const char* name) -> json {
                if (const Element* t = textured(name)) return texture(*t, true);
                return p.number(name, 0.1);
            };
            if (p.get("alpha_u") || p.get("alpha_v")) {
                m["alpha_u"] = value("alpha_u");
                m["alpha_v"] = value("alpha_v");
            } else {
                m["alpha"] = value("alpha");
            }
            return;
        }
        double alpha = p.number("alpha", 0.1);
        if (p.get("alpha_u") || p.get("alpha_v")) {
            const double au = p.number("alpha_u", 0.1), av = p.number("alpha_v", 0.1);
            if (au != av && anisotropic) {
                m["alpha_u"] = au;
                m["alpha_v"] = av;
                m["distribution"] = d;
                return;
            }
            if (au != av)
                warn(e, "anisotropic roughness (alpha_u " + std::to_string(au) + ", alpha_v " +
                            std::to_string(av) + ") is rendered isotropic with their mean");
            alpha = 0.5 * (au + av);
        }
        m["alpha"] = alpha;
        m["distribution"] = d;
    }

    json bsdf(const Element& e, int depth) {
        if (depth > 16) fail(e, "BSDFs nested deeper than 16");
        const std::string type = e.attr_or("type", "");
        Props p(e, *this);
        json m;
        auto wrapped = [&](const char* what) -> json {
            const std::vector<const Element*> inner = p.nested("bsdf");
            if (inner.empty()) fail(e, std::string(what) + ": needs a nested <bsdf>");
            if (inner.size() > 1)
                warn(e, std::string(what) + ": two nested BSDFs; the first is used on both sides");
            return bsdf(*inner.front(), depth + 1);
        };
        if (type == "twosided") {
            m = wrapped("twosided");
            two_sided(m);
        } else if (type == "blendbsdf") {
            const std::vector<const Element*> inner = p.nested("bsdf");
            if (inner.size() != 2) fail(e, "blendbsdf: needs two nested BSDFs");
            m = {{"type", "blend"}, {"materials", json::array()}};
            for (const Element* b : inner) {
                json c = bsdf(*b, depth + 1);
                // What a hit decides before it is shaded must be the blend's own.
                if (c.contains("opacity") || c["type"] == "thin_dielectric")
                    fail(*b,
                         "blendbsdf: a mask or a thindielectric inside a blend is not "
                         "supported; put the mask around the blend");
                m["materials"].push_back(std::move(c));
            }
            // Mitsuba reads the weight as a number (eval_1), a checkerboard's cells the other
            // way round (texture(..., true)).
            const Element* w = p.get("weight");
            if (!w) fail(e, "blendbsdf: needs a weight");
            m["weight"] = w->tag == "texture" ? texture(*w, true) : json(p.number("weight", 0.5));
        } else if (type == "mask") {
            m = wrapped("mask");
            m["opacity"] = color_property(p, "opacity", 0.5, true, false, /*scalar=*/true);
        } else if (type == "normalmap") {
            m = wrapped("normalmap");
            const Element* n = p.get("normalmap");
            if (!n) fail(e, "normalmap: needs a normalmap texture");
            m["normal_map"] = color(*n, false, false);
            mapped_normal_switches(p, m);
        } else if (type == "bumpmap") {
            m = wrapped("bumpmap");
            const std::vector<const Element*> t = p.nested("texture");
            if (t.empty()) fail(e, "bumpmap: needs a nested <texture>");
            m["bump_map"] = texture(*t.front());
            m["bump_scale"] = p.number("scale", 1.0);
            mapped_normal_switches(p, m);
        } else if (type == "diffuse") {
            m = {{"type", "lambertian"}, {"albedo", color_property(p, "reflectance", 0.5, true)},
                 {"one_sided", true}};
        } else if (type == "conductor" || type == "roughconductor") {
            m = {{"type", "conductor"}, {"one_sided", true}};
            const std::string metal = p.string("material", "");
            const Element* eta = p.get("eta");
            const Element* k = p.get("k");
            if (eta || k) {
                if (!metal.empty()) fail(e, "conductor: give material or eta and k, not both");
                m["eta"] = eta ? color(*eta, false, false) : json(0.0);
                m["k"] = k ? color(*k, false, false) : json(1.0);
            } else {
                m["metal"] = metal.empty() ? "none" : metal;
            }
            if (const Element* r = p.get("specular_reflectance"))
                m["reflectance"] = color(*r, true, false);
            if (type == "roughconductor") roughness(p, m, e, "beckmann", true);
        } else if (type == "dielectric" || type == "roughdielectric" || type == "thindielectric") {
            m = {{"type", type == "thindielectric" ? "thin_dielectric" : "dielectric"},
                 {"ior", p.ior("int_ior", "bk7")},
                 {"ext_ior", p.ior("ext_ior", "air")}};
            for (const char* s : {"specular_reflectance", "specular_transmittance"})
                if (const Element* c = p.get(s)) {
                    const json v = color(*c, true, false);
                    if (v != json(1.0) && v != json::array({1.0, 1.0, 1.0}))
                        warn(*c, type + ": " + s + " other than 1 is not supported; ignored");
                }
            if (type == "roughdielectric") roughness(p, m, e, "beckmann");
        } else if (type == "plastic" || type == "roughplastic") {
            m = {{"type", "plastic"},
                 {"albedo", color_property(p, "diffuse_reflectance", 0.5, true)},
                 {"ior", p.ior("int_ior", "polypropylene")},
                 {"ext_ior", p.ior("ext_ior", "air")},
                 {"one_sided", true}};
            if (const Element* s = p.get("specular_reflectance"))
                m["specular"] = color(*s, false, false);
            if (p.boolean("nonlinear", false)) m["nonlinear"] = true;
            if (type == "roughplastic") roughness(p, m, e, "beckmann");
        } else if (type == "principled" || type == "principledthin") {
            const bool thin = type == "principledthin";
            m = {{"type", "principled"},
                 {"base_color", color_property(p, "base_color", 0.5, true)}};
            if (thin) m["thin"] = true;
            // Each weight a number or a texture; Mitsuba's scalar lookups (eval_1) of a
            // checkerboard take its cells the other way round (texture(..., true)).
            PrincipledWeights().for_each([&](const char* name, const TexturedNumber&) {
                const Element* c = p.get(name);
                if (!c) return;
                if (!PrincipledWeights::has(name, thin)) {
                    warn(*c, type + ": " + name + " is not one of its parameters; ignored");
                    return;
                }
                m[name] = c->tag == "texture" ? texture(*c, true) : json(p.number(name, 0.0));
            });
            const bool transmits = m.contains("spec_trans") && m["spec_trans"] != json(0.0);
            const Element* eta = p.get("eta");
            if (eta && eta->tag == "texture")
                fail(*eta, type + ": eta as a texture is not supported");
            if (thin) {
                m["ior"] = p.number("eta", 1.5);
            } else if (eta && p.get("specular")) {
                fail(e, "principled: give eta or specular, not both");
            } else if (eta) {
                // An index of 1 cannot transmit; Mitsuba takes 1.001 then.
                const double v = p.number("eta", 1.5);
                m["ior"] = transmits && v == 1.0 ? 1.001 : v;
            } else {
                const double v = p.number("specular", 0.5);
                m["specular"] = transmits && v == 0.0 ? 1e-3 : v;
            }
            for (const char* rate :
                 {"main_specular_sampling_rate", "clearcoat_sampling_rate",
                  "diffuse_reflectance_sampling_rate", "specular_reflectance_sampling_rate",
                  "specular_transmittance_sampling_rate", "diffuse_transmittance_sampling_rate"})
                if (const Element* r = p.get(rate))
                    warn(*r, type + ": " + rate + " is not supported (sampling only); ignored");
        } else {
            warn(e, "bsdf \"" + type + "\" is not supported; a grey diffuse (0.5) stands for it");
            return {{"type", "lambertian"}, {"albedo", 0.5}, {"one_sided", true}};
        }
        p.finish({"sample_visible", "id"});
        return m;
    }

    // A material seen from both sides, as Mitsuba's twosided makes its BSDF: a blend's
    // materials each.
    static void two_sided(json& m) {
        m.erase("one_sided");
        if (m["type"] == "blend")
            for (json& c : m["materials"]) two_sided(c);
    }

    // The material name of a <bsdf> element, translated once however often it is referenced.
    std::string material(const Element& e) {
        auto it = materials_.find(&e);
        if (it != materials_.end()) return it->second;
        const std::string name = material_name(e);
        out_["materials"][name] = bsdf(e, 0);
        materials_[&e] = name;
        return name;
    }

    // The id, or the type and where it is ("roughplastic at sphere_grid.xml:125").
    std::string material_name(const Element& e) {
        const std::string* id = e.attr("id");
        std::string name =
            id ? *id : e.attr_or("type", "bsdf") + " at " + fs::path(e.place).filename().string();
        while (out_["materials"].contains(name)) name += "'";
        return name;
    }

    // ---- shapes ----

    void shape(const Element& e, json& objects, std::vector<std::string>* places) {
        const std::string type = e.attr_or("type", "");
        Props p(e, *this);
        const Xform to_world = p.transform("to_world");
        json o;
        if (type == "obj" || type == "ply" || type == "gltf" || type == "serialized") {
            const std::string f = p.string("filename", "");
            if (f.empty()) fail(e, type + ": needs a filename");
            o = {{"type", "mesh"}, {"file", file(e, f)}};
            if (type == "serialized") {
                const int index = p.integer("shape_index", 0, 0, 1 << 30);
                if (index > 0) o["shape_index"] = index;
            }
            // Mitsuba computes vertex normals for a mesh whose file has none.
            o["normals"] = p.boolean("face_normals", false) ? "flat" : "file_or_smooth";
            // Mitsuba's v runs down an image from its top row, ours up from the bottom row: a
            // file's v is ours where Mitsuba flips it (an OBJ's by default), else flipped.
            const bool mitsuba_flips = type != "serialized" && type != "gltf" &&
                                       p.boolean("flip_tex_coords", type == "obj");
            if (type != "gltf" && !mitsuba_flips) o["flip_v"] = true;
        } else if (type == "sphere") {
            const Element* c = p.get("center");
            // Mitsuba's (u, v) in its to_world frame is (u, 1 - v) of pbrt-v4's mapping.
            o = {{"type", "sphere"},
                 {"center", c ? to_json(xyz(*c, 0.0)) : json::array({0, 0, 0})},
                 {"radius", p.number("radius", 1.0)},
                 {"uv_mapping", "z_up"}};
        } else if (type == "rectangle") {
            // Mitsuba's uv ((x + 1) / 2, (y + 1) / 2), as ours: (u, 1 - v) is flip_v's.
            o = {{"type", "quad"}, {"q", {-1, -1, 0}}, {"u", {2, 0, 0}}, {"v", {0, 2, 0}},
                 {"flip_v", true}};
        } else if (type == "cube") {
            // [-1, 1]^3 as six quads whose (a, b) is (u, 1 - v) of Mitsuba's faces, each of
            // which maps onto [0, 1]^2 (its cube.cpp); u x v is the outward normal.
            static const int faces[6][9] = {
                {1, -1, -1, 0, 0, 2, -2, 0, 0},  {1, 1, -1, -2, 0, 0, 0, 0, 2},
                {1, -1, -1, 0, 2, 0, 0, 0, 2},   {1, -1, 1, 0, 2, 0, -2, 0, 0},
                {-1, -1, 1, 0, 2, 0, 0, 0, -2},  {1, 1, -1, 0, -2, 0, -2, 0, 0}};
            o = {{"type", "group"}, {"objects", json::array()}};
            for (const int* f : faces)
                o["objects"].push_back({{"type", "quad"},
                                        {"q", {f[0], f[1], f[2]}},
                                        {"u", {f[3], f[4], f[5]}},
                                        {"v", {f[6], f[7], f[8]}}});
        } else if (type == "disk") {
            // The unit disk at z = 0, facing +z, or -z with flip_normals: the side that emits
            // and that one-sided materials reflect from.
            const bool flip = p.boolean("flip_normals", false);
            o = {{"type", "disk"},
                 {"center", {0, 0, 0}},
                 {"normal", {0, 0, flip ? -1 : 1}},
                 {"radius", 1}};
        } else if (type == "cylinder") {
            const Element* p0 = p.get("p0");
            const Element* p1 = p.get("p1");
            // Mitsuba's uv (phi / 2 pi, the fraction of the axis), phi in the same frame of the
            // axis as ours (Duff et al. 2017): flip_v gives its (u, 1 - v).
            o = {{"type", "cylinder"},
                 {"p0", p0 ? to_json(xyz(*p0, 0.0)) : json::array({0, 0, 0})},
                 {"p1", p1 ? to_json(xyz(*p1, 0.0)) : json::array({0, 0, 1})},
                 {"radius", p.number("radius", 1.0)},
                 {"flip_v", true}};
        } else if (type == "instance") {
            const std::vector<const Element*> groups = p.nested("shape");
            if (groups.size() != 1 || groups.front()->attr_or("type", "") != "shapegroup")
                fail(e, "instance: needs one reference to a shapegroup");
            o = {{"type", "group"}, {"objects", json::array()}};
            for (const Element& c : groups.front()->children)
                if (deref(c)->tag == "shape") shape(*deref(c), o["objects"], nullptr);
            if (!to_world.steps.empty()) o["transform"] = to_world.steps;
            p.finish();
            push(objects, places, std::move(o), e);
            return;
        } else {
            warn(e, "shape \"" + type + "\" is not supported; skipped");
            return;
        }
        if (!to_world.steps.empty()) o["transform"] = to_world.steps;
        if (type != "disk" && p.boolean("flip_normals", false))
            warn(e, type + ": flip_normals is not supported; ignored");

        const std::vector<const Element*> bsdfs = p.nested("bsdf");
        const std::vector<const Element*> emitters = p.nested("emitter");
        // A medium's role is the name on the element in the shape (a <ref> or the medium).
        for (const Element& c : e.children)
            if (deref(c)->tag == "medium") medium(*deref(c), c.attr_or("name", ""), o);
        p.nested("medium");  // read
        const Element* b = bsdfs.empty() ? nullptr : bsdfs.front();
        if (bsdfs.size() > 1) warn(*bsdfs[1], "a second <bsdf> in a shape is ignored");
        if (!emitters.empty()) {
            o["material"] = area_light(*emitters.front(), b);
        } else if (b && b->attr_or("type", "") == "null") {
            if (!o.contains("interior")) {
                warn(*b, "a shape with a null BSDF and no interior medium is invisible; skipped");
                return;
            }
        } else if (b) {
            o["material"] = material(*b);
        } else {
            o["material"] = default_material();
        }
        if (type == "cube") {  // the group's quads carry its material and medium
            for (const char* key : {"material", "interior"}) {
                if (!o.contains(key)) continue;
                for (json& face : o["objects"]) face[key] = o[key];
                o.erase(key);
            }
        }
        if (type == "disk" && o.contains("material") &&
            reads_uv(out_["materials"][o["material"].get<std::string>()]))
            warn(e, type + ": its texture coordinates are wavetrace's, not Mitsuba's; its "
                           "textures and normal maps appear differently");
        p.finish({"id"});
        push(objects, places, std::move(o), e);
    }

    // Whether a material we wrote looks anything up at the surface's texture coordinates.
    static bool reads_uv(const json& j) {
        if (j.is_object()) {
            if (j.contains("normal_map") || j.contains("bump_map")) return true;
            const auto type = j.find("type");
            if (type != j.end() && type->is_string() &&
                (*type == "image" || *type == "uv_checker"))
                return true;
            for (const auto& [key, value] : j.items())
                if (reads_uv(value)) return true;
        } else if (j.is_array()) {
            for (const json& value : j)
                if (reads_uv(value)) return true;
        }
        return false;
    }

    static void push(json& objects, std::vector<std::string>* places, json o, const Element& e) {
        objects.push_back(std::move(o));
        if (places) places->push_back(e.place);
    }

    // Mitsuba's default BSDF: diffuse of reflectance 0.5, black from behind.
    std::string default_material() {
        const std::string name = "default diffuse";
        if (!out_["materials"].contains(name))
            out_["materials"][name] = {{"type", "lambertian"}, {"albedo", 0.5}, {"one_sided", true}};
        return name;
    }

    // An area emitter on a shape: our diffuse_light, reflecting as the shape's diffuse BSDF.
    std::string area_light(const Element& emitter_element, const Element* b) {
        if (emitter_element.attr_or("type", "") != "area")
            fail(emitter_element, "a shape's emitter must be of type area");
        Props p(emitter_element, *this);
        json m = {{"type", "diffuse_light"},
                  {"radiance", color_property(p, "radiance", to_json_color(kD65Rgb), false, true)}};
        p.finish();
        json reflect = b ? bsdf(*b, 0) : json{{"type", "lambertian"}, {"albedo", 0.5}};
        if (reflect["type"] == "lambertian") {
            m["albedo"] = reflect["albedo"];
        } else {
            warn(*b, "an area light's surface reflects only as a diffuse surface; its bsdf \"" +
                         b->attr_or("type", "") + "\" is ignored");
        }
        std::string name = "area light at " + fs::path(emitter_element.place).filename().string();
        while (out_["materials"].contains(name)) name += "'";
        out_["materials"][name] = std::move(m);
        return name;
    }

    static json to_json_color(Color c) { return json::array({c.x, c.y, c.z}); }

    // A <volume> as our JSON grid: a `gridvolume` (its file over the unit cube, or over the
    // file's box with use_grid_bbox, placed by to_world; its filter and wrap mode) or a
    // `constvolume` (its value over its to_world's unit cube, the box a heterogeneous medium is
    // confined to).
    json volume(const Element& v, bool bounded) {
        const std::string type = v.attr_or("type", "");
        Props p(v, *this);
        json g;
        if (type == "gridvolume") {
            const std::string f = p.string("filename", "");
            if (f.empty()) fail(v, "gridvolume: needs a filename");
            g["file"] = file(v, f);
            if (p.boolean("use_grid_bbox", false)) g["file_bounds"] = true;
            const std::string filter = p.string("filter_type", "trilinear");
            if (filter != "trilinear" && filter != "nearest")
                fail(v,
                     "gridvolume: filter_type \"" + filter + "\" (expected trilinear or nearest)");
            if (filter == "nearest") g["filter"] = filter;
            const std::string wrap = p.string("wrap_mode", "clamp");
            if (wrap != "clamp" && wrap != "repeat" && wrap != "mirror")
                fail(v,
                     "gridvolume: wrap_mode \"" + wrap + "\" (expected clamp, repeat or mirror)");
            if (wrap != "clamp") g["wrap"] = wrap;
        } else if (type == "constvolume") {
            const Element* c = p.get("value");
            g["value"] = c ? color(*c, bounded, false) : json(0.75);
        } else {
            fail(v, "volume \"" + type + "\" is not supported (gridvolume or constvolume)");
        }
        if (const Xform x = p.transform("to_world"); !x.steps.empty()) g["transform"] = x.steps;
        p.finish({"raw", "accel"});
        return g;
    }

    // A medium inside a shape: homogeneous, or heterogeneous over a volume (the medium is
    // empty outside the sigma_t volume's box, as Mitsuba's); our media scatter isotropically.
    void medium(const Element& e, const std::string& role, json& o) {
        if (role != "interior") {
            warn(e, "medium \"" + role + "\": only interior media are supported; ignored");
            return;
        }
        auto it = media_names_.find(&e);
        if (it == media_names_.end()) {
            const std::string type = e.attr_or("type", "");
            if (type != "homogeneous" && type != "heterogeneous") {
                warn(e, "medium \"" + type + "\" is not supported; ignored");
                return;
            }
            Props p(e, *this);
            const double scale = p.number("scale", 1.0);
            const Element* st = p.get("sigma_t");
            json grid;
            json sigma_t = json(1.0);
            if (st && st->tag == "volume") {
                if (type != "heterogeneous")
                    fail(*st, "homogeneous: sigma_t must be a number or an rgb");
                grid = volume(*st, false);
            } else if (st) {
                sigma_t = color(*st, false, false);
            }
            json density;  // sigma_t x scale, per channel where it has channels
            if (sigma_t.is_array()) {
                density = json::array();
                for (int c = 0; c < 3; ++c) density.push_back(sigma_t[c].get<double>() * scale);
            } else if (sigma_t.is_number()) {
                density = sigma_t.get<double>() * scale;
            } else {
                fail(*st, type + ": sigma_t must be a number, an rgb or a volume");
            }
            for (const Element* phase : p.nested("phase"))
                if (phase->attr_or("type", "") != "isotropic")
                    warn(*phase, "phase \"" + phase->attr_or("type", "") +
                                     "\": wavetrace's media scatter isotropically");
            std::string name = "medium at " + fs::path(e.place).filename().string();
            while (media_.contains(name)) name += "'";
            json albedo;
            if (const Element* a = p.get("albedo"); a && a->tag == "volume") {
                // A grid texture; a constant's box confines nothing (an albedo is read only
                // where the medium scatters).
                albedo = volume(*a, true);
                if (albedo.contains("value"))
                    albedo = albedo["value"];
                else
                    albedo["type"] = "grid";
            } else {
                albedo = color_property(p, "albedo", 0.75, true);
            }
            media_[name] = {{"density", density}, {"albedo", albedo}};
            if (!grid.is_null()) media_[name]["density_grid"] = grid;
            p.finish({"sample_emitters", "has_spectral_extinction"});
            it = media_names_.emplace(&e, name).first;
        }
        o["interior"] = it->second;
    }

    // ---- emitters, sensor, integrator ----

    void emitter(const Element& e) {
        const std::string type = e.attr_or("type", "");
        Props p(e, *this);
        const Xform to_world = p.transform("to_world");
        if (type == "point") {
            const Element* at = p.get("position");
            const V3 position = at ? xyz(*at, 0.0) : to_world.point(0, 0, 0);
            lights_.push_back({{"type", "point"}, {"position", to_json(position)},
                               {"intensity", color_property(p, "intensity",
                                                            to_json_color(kD65Rgb), false, true)}});
        } else if (type == "spot") {
            const V3 position = to_world.point(0, 0, 0);
            const V3 axis = normalized(to_world.vector(0, 0, 1));
            const double cutoff = p.number("cutoff_angle", 20.0);
            const double beam = p.number("beam_width", cutoff * 0.75);
            lights_.push_back({{"type", "spot"}, {"position", to_json(position)},
                               {"look_at", to_json(add(position, axis))},
                               {"intensity", color_property(p, "intensity",
                                                            to_json_color(kD65Rgb), false, true)},
                               {"cutoff", cutoff}, {"falloff_start", std::min(beam, cutoff)}});
            if (const Element* t = p.get("texture")) {
                // Mitsuba looks the texture up at (1/2 + x / (2 z tan cutoff), 1/2 + y / (...))
                // of the light's local direction, v_M down the image from its top row: our
                // (u, 1 - v) with right = +x, so up = -y (Light::texture).
                lights_.back()["texture"] = color(*t, false, true);
                const V3 y = to_world.vector(0, 1, 0);
                lights_.back()["up"] = to_json(V3{-y[0], -y[1], -y[2]});
            }
        } else if (type == "projector") {
            // Mitsuba looks its irradiance up at (1/2 - x / (2 z tan_x), 1/2 - y / (2 z tan_y))
            // of the light's local direction (a camera's film; v_M down from the image's top):
            // our (u, 1 - v) with right = -x, so up = +y (Light::texture).
            const V3 position = to_world.point(0, 0, 0);
            const V3 axis = normalized(to_world.vector(0, 0, 1));
            json light = {{"type", "projector"},
                          {"position", to_json(position)},
                          {"look_at", to_json(add(position, axis))},
                          {"up", to_json(to_world.vector(0, 1, 0))},
                          {"scale", p.number("scale", 1.0)}};
            const Element* irradiance = p.get("irradiance");
            light["irradiance"] =
                irradiance ? color(*irradiance, false, true) : to_json_color(kD65Rgb);
            if (const Element* f = p.get("fov")) {
                light["fov"] = parse_number(*f, f->attr_or("value", ""));
                light["fov_axis"] = p.string("fov_axis", "x");
            } else {
                // A focal length on 35 mm film: its field of view on the diagonal.
                std::string text = p.string("focal_length", "50mm");
                if (text.size() > 2 && text.substr(text.size() - 2) == "mm")
                    text = text.substr(0, text.size() - 2);
                light["fov"] = 2 * std::atan(std::hypot(36.0, 24.0) / (2 * parse_number(e, text))) *
                               180 / kPiD;
                light["fov_axis"] = "diagonal";
            }
            lights_.push_back(light);
        } else if (type == "directional") {
            const Element* d = p.get("direction");
            const V3 direction = d ? xyz(*d, 0.0) : to_world.vector(0, 0, 1);
            lights_.push_back({{"type", "directional"}, {"direction", to_json(direction)},
                               {"irradiance", color_property(p, "irradiance",
                                                             to_json_color(kD65Rgb), false, true)}});
        } else if (type == "constant" || type == "envmap") {
            if (out_.contains("background")) {
                warn(e, "a second background emitter is ignored (wavetrace has one background)");
            } else {
                doc_.background_place = e.place;
                if (type == "constant")
                    out_["background"] = {{"type", "constant"},
                                          {"radiance", color_property(p, "radiance",
                                                                      to_json_color(kD65Rgb),
                                                                      false, true)}};
                else
                    out_["background"] = envmap(e, p, to_world);
            }
        } else {
            warn(e, "emitter \"" + type + "\" is not supported; ignored");
            return;
        }
        doc_.light_places.resize(lights_.size(), e.place);
        p.finish();
    }

    // Mitsuba's envmap looks up direction d (in its local frame, +y up) at
    // u = atan2(d.x, -d.z) / 2pi, v = acos(d.y) / pi, rows from pole to pole; ours puts
    // u = 0.5 + (atan2(d.x, -d.z) - rotation) / 2pi in the map's frame. A to_world turning
    // about +y maps to our rotation alone; any other rotation becomes the map's `to_world`.
    json envmap(const Element& e, Props& p, const Xform& to_world) {
        const std::string f = p.string("filename", "");
        if (f.empty()) fail(e, "envmap: needs a filename");
        const double scale = p.number("scale", 1.0);
        std::array<V3, 3> axes;
        bool rigid;
        if (!affine::rotation_axes(to_world.m, &axes, &rigid)) fail(e, "envmap: to_world is singular");
        if (!rigid)
            warn(e, "envmap: to_world is not a rotation (times a uniform scale); the rotation "
                    "of its x and y axes is used");
        json bg = {{"type", "environment"}, {"file", file(e, f)},
                   {"scale", json::array({scale, scale, scale})}, {"rows_at_poles", true}};
        const V3 up = axes[1], back = affine::normalized({-axes[2][0], -axes[2][1], -axes[2][2]});
        const bool about_y = std::abs(up[1] - 1) < 1e-5 &&
                             affine::dot(axes[0], affine::cross(axes[1], axes[2])) > 0;
        if (about_y) {
            bg["rotation"] = std::atan2(back[0], -back[2]) * 180 / kPiD + 180;
        } else {
            bg["rotation"] = 180;
            bg["to_world"] = affine::axes_matrix(axes);
        }
        return bg;
    }

    void sensor_(const Element& e) {
        const std::string type = e.attr_or("type", "");
        if (type != "perspective" && type != "thinlens" && type != "orthographic") {
            warn(e, "sensor \"" + type + "\" is not supported; rendered as a perspective camera");
        }
        Props p(e, *this);
        const Xform to_world = p.transform("to_world");
        int width = 768, height = 576;
        // Mitsuba's default filter: its Gaussian of deviation 0.5 and radius 4 sigma.
        json filter = {{"type", "gaussian"}, {"sigma", 0.5}, {"radius", 2.0}};
        for (const Element* film : p.nested("film")) {
            Props f(*film, *this);
            width = f.integer("width", 768, 1, kMaxImageSide);
            height = f.integer("height", 576, 1, kMaxImageSide);
            for (const char* crop : {"crop_width", "crop_height", "crop_offset_x", "crop_offset_y"})
                if (f.get(crop)) warn(*film, std::string("film: ") + crop + " is not supported; the whole film is rendered");
            for (const Element* r : f.nested("rfilter")) {
                Props rp(*r, *this);
                const std::string rt = r->attr_or("type", "");
                if (rt == "box") {
                    filter = nullptr;
                } else if (rt == "tent") {
                    filter = {{"type", "tent"}, {"radius", rp.number("radius", 1.0)}};
                } else if (rt == "gaussian") {
                    const double sigma = rp.number("stddev", 0.5);
                    filter = {{"type", "gaussian"}, {"sigma", sigma}, {"radius", 4 * sigma}};
                } else {
                    warn(*r, "rfilter \"" + rt + "\" is not supported; a box filter is used");
                    filter = nullptr;
                }
                rp.finish(rt == "box" || rt == "tent" || rt == "gaussian"
                              ? std::initializer_list<const char*>{}
                              : std::initializer_list<const char*>{"radius", "stddev", "B", "C", "lobes"});
            }
            f.finish({"pixel_format", "component_format", "file_format", "banner",
                      "high_quality_edges", "sample_border", "compensate"});
        }
        for (const Element* sampler : p.nested("sampler")) {
            Props s(*sampler, *this);
            const std::string st = sampler->attr_or("type", "");
            // Independent as it is; the stratified and low-discrepancy ones as our Sobol sampler.
            out_["render"]["sampler"] = st == "independent" ? "independent" : "sobol";
            if (st != "independent")
                warn(*sampler, "sampler \"" + st +
                                   "\": wavetrace draws Owen-scrambled Sobol points per pixel");
            out_["render"]["spp"] = s.integer("sample_count", 4, 1, kMaxSpp);
            s.finish({"seed", "jitter", "scramble_seed"});
        }
        out_["render"]["width"] = width;
        out_["render"]["height"] = height;

        const double aspect = static_cast<double>(width) / height;
        double fov;
        std::string axis = p.string("fov_axis", "x");
        if (const Element* f = p.get("fov")) {
            fov = parse_number(*f, f->attr_or("value", ""));
        } else {
            // A focal length on 35 mm film (36 x 24 mm): its field of view on the diagonal.
            std::string text = p.string("focal_length", "50mm");
            if (text.size() > 2 && text.substr(text.size() - 2) == "mm")
                text = text.substr(0, text.size() - 2);
            const double mm = parse_number(e, text);
            fov = 2 * std::atan(std::hypot(36.0, 24.0) / (2 * mm)) * 180 / kPiD;
            axis = "diagonal";
        }
        if (!(fov > 0 && fov < 180)) fail(e, "sensor: the field of view must lie in (0, 180)");
        const double half = std::tan(fov * kPiD / 360);
        double tan_v = half;
        if (axis == "x" || (axis == "smaller" && aspect < 1) || (axis == "larger" && aspect > 1))
            tan_v = half / aspect;
        else if (axis == "diagonal")
            tan_v = half / std::sqrt(1 + aspect * aspect);
        else if (axis != "y" && axis != "smaller" && axis != "larger")
            fail(e, "fov_axis \"" + axis + "\" (expected x, y, diagonal, smaller or larger)");
        const double vfov = 2 * std::atan(tan_v) * 180 / kPiD;

        const V3 from = to_world.point(0, 0, 0);
        const V3 forward = normalized(to_world.vector(0, 0, 1));
        const V3 up = to_world.vector(0, 1, 0);
        const V3 left = to_world.vector(1, 0, 0);
        json camera = {{"look_from", to_json(from)},
                       {"look_at", to_json(add(from, forward))},
                       {"up", to_json(up)},
                       {"vfov", vfov}};
        // Mitsuba's camera looks along +z with +x to the left of the image: our right is
        // forward x up, so a to_world that mirrors (a scale by -1) needs our mirrored camera.
        if (dot(cross(forward, up), left) > 0) camera["mirror"] = true;
        if (!filter.is_null()) camera["filter"] = filter;
        if (type == "orthographic") {
            // Mitsuba's orthographic film spans [-1, 1] x [-1 / aspect, 1 / aspect] of camera
            // space, scaled by to_world.
            camera.erase("vfov");
            camera["type"] = "orthographic";
            camera["view_width"] = 2 * norm(left);
            camera["view_height"] = 2 * norm(up) / aspect;
        }
        if (type == "thinlens") {
            camera["aperture"] = 2 * p.number("aperture_radius", 0.0);
            camera["focus_distance"] = p.number("focus_distance", 0.0);
        }
        out_["camera"] = camera;
        const double near_clip = p.number("near_clip", 0.01), far_clip = p.number("far_clip", 1e4);
        if (near_clip != 0.01 || far_clip != 1e4)
            warn(e, "sensor: near_clip and far_clip are not supported; nothing is clipped");
        p.finish({"principal_point_offset_x", "principal_point_offset_y", "srf", "shutter_open",
                  "shutter_close"});
    }

    void integrator_(const Element& e) {
        std::string type = e.attr_or("type", "");
        const Element* inner = &e;
        // moment and aov integrators wrap the one that renders.
        while (type == "moment" || type == "aov") {
            Props w(*inner, *this);
            const std::vector<const Element*> nested = w.nested("integrator");
            if (nested.empty()) {
                warn(*inner, "integrator \"" + type + "\" without a nested integrator; path "
                             "tracing");
                return;
            }
            inner = nested.front();
            type = inner->attr_or("type", "");
        }
        Props p(*inner, *this);
        int depth = p.integer("max_depth", -1, -1, 1 << 30);
        if (type == "direct") {
            warn(*inner, "integrator \"direct\" is rendered as path tracing of max_depth 2");
            depth = 2;
        } else if (type != "path" && type != "volpath" && type != "volpathmis") {
            warn(*inner, "integrator \"" + type + "\": wavetrace path traces instead");
        }
        if (depth == 0) warn(*inner, "integrator: max_depth 0 (a black image) is rendered as 1");
        out_["render"]["max_depth"] = depth < 0 ? kMaxDepth : std::max(1, std::min(depth, kMaxDepth));
        if (p.number("rr_depth", 5) != 5)
            warn(*inner, "integrator: rr_depth is not supported; wavetrace's roulette starts at "
                         "the third vertex");
        if (p.boolean("hide_emitters", false))
            warn(*inner, "integrator: hide_emitters is not supported; emitters are seen");
        p.finish({"emitter_samples", "bsdf_samples"});
    }

    Reader& reader_;
    fs::path base_;
    std::function<void(const std::string&)> warn_;
    json out_ = json::object();
    json lights_ = json::array();
    json media_ = json::object();
    MitsubaDocument doc_;
    std::map<std::string, const Element*> ids_;
    std::map<const Element*, std::string> materials_;
    std::map<const Element*, std::string> media_names_;
};

}  // namespace

MitsubaDocument translate_mitsuba_xml(const fs::path& path,
                                      const std::map<std::string, std::string>& params,
                                      const std::function<void(const std::string&)>& warn,
                                      const fs::path& asset_root) {
    Reader reader(path, params, asset_root);
    const Element scene = reader.read_main(path);
    return Translator(reader, path, warn).translate(scene);
}

}  // namespace wavetrace
