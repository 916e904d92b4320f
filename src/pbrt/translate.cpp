// pbrt-v4 scene files -> our JSON scene document. The directives and their parameters are
// pbrt-v4's file format as its documentation ("pbrt-v4 User's Guide", "File format") and the
// book (Physically Based Rendering, 4th ed.) define them; every default below is theirs.
// pbrt is spectral and wavetrace is RGB: spectra become linear sRGB as Mitsuba's RGB
// variants convert them (src/formats/spectrum_rgb.h).
#include "pbrt/translate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "files/confinement.h"
#include "files/input_file.h"
#include "formats/affine.h"
#include "pbrt/params.h"
#include "pbrt/shapes.h"
#include "pbrt/tokenizer.h"
#include "formats/spectrum_rgb.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr int kMaxIncludeDepth = 32;
constexpr size_t kMaxAttributeDepth = 4096;
// pbrt files hold meshes written out as text, so they may be larger than our JSON files.
constexpr uintmax_t kMaxPbrtFileBytes = uintmax_t(1) << 30;
// Instancing copies shapes: a file may place at most this many, and this many triangles of the
// meshes written out in it (each instance counts them again).
constexpr size_t kMaxPlacedShapes = size_t(1) << 20;
constexpr size_t kMaxPlacedTriangles = size_t(1) << 28;
// The material of shapes that are no surface, only the boundary of media; never a name in
// /materials.
const std::string kInterface = "@interface";

[[noreturn]] void fail(const std::string& place, const std::string& message) {
    throw SceneError(place + ": " + message);
}

// Points are columns (pbrt's convention too: CTM' = CTM * T).
using affine::M4;
using affine::V3;
using affine::add;
using affine::apply_point;
using affine::apply_vector;
using affine::cross;
using affine::dot;
using affine::identity;
using affine::invert;
using affine::mul;
using affine::norm;
using affine::normalized;
using affine::rotation;
using affine::sub;
using affine::to_json;

// The affine part as our JSON's "matrix" step (rows of a 3x4 matrix).
json matrix_step(const M4& m) {
    json rows = json::array();
    for (int k = 0; k < 12; ++k) rows.push_back(m[k]);
    return json::array({json{{"matrix", rows}}});
}



// ---------------------------------------------------------------------------------------------
// The files: a stack of tokenizers, one per open Include.

class Reader {
  public:
    Reader(const fs::path& main, const fs::path& asset_root)
        : folder_(main.parent_path()), asset_root_(asset_root) {
        open(main, main.string());
    }

    // Throws std::runtime_error unless `p` lies inside the asset root (if there is one).
    void confine(const fs::path& p) const {
        if (std::string why = Confinement{{}, asset_root_}.problem(p); !why.empty())
            throw std::runtime_error(why);
    }

    // pbrt resolves every relative path against the main file's folder.
    fs::path resolve(const std::string& name) const {
        fs::path p(name);
        return p.is_absolute() ? p : folder_ / p;
    }
    // A file name as our JSON takes it: pbrt's and ours are both relative to the scene
    // file's folder.
    static std::string relative(const std::string& name) { return fs::path(name).generic_string(); }

    void include(const std::string& name, const std::string& place) {
        if (stack_.size() > static_cast<size_t>(kMaxIncludeDepth))
            fail(place, "includes nested deeper than " + std::to_string(kMaxIncludeDepth));
        const fs::path p = resolve(name);
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(p, ec);
        for (const Source& s : stack_)
            if (s.canonical == canonical) fail(place, "Include \"" + name + "\" includes itself");
        open(p, place);
    }

    bool next(PbrtToken* t) {
        while (!stack_.empty()) {
            if (stack_.back().tokens.next(t)) {
                last_place_ = stack_.back().tokens.file() + ":" + std::to_string(t->line);
                return true;
            }
            stack_.pop_back();
        }
        return false;
    }
    void unget(PbrtToken t) { stack_.back().tokens.unget(std::move(t)); }
    std::string place(const PbrtToken& t) const {
        return stack_.back().tokens.file() + ":" + std::to_string(t.line);
    }
    // Where reading is (at the end of the files: the last token's place).
    std::string place() const {
        return stack_.empty() ? last_place_
                              : stack_.back().tokens.file() + ":" +
                                    std::to_string(stack_.back().tokens.line());
    }
    size_t depth() const { return stack_.size(); }

  private:
    struct Source {
        PbrtTokenizer tokens;
        fs::path canonical;
    };

    void open(const fs::path& p, const std::string& place) {
        const std::string name = p.string();
        try {
            check_input_file(p, kMaxPbrtFileBytes, "pbrt files");
            confine(p);
        } catch (const std::runtime_error& e) {
            throw SceneError((stack_.empty() ? name : place) + ": cannot open " +
                             (stack_.empty() ? "scene file: " : "'" + name + "': ") + e.what());
        }
        std::string text;
        try {
            text = read_input_file(p);
        } catch (const std::runtime_error& e) {
            throw SceneError(place + ": cannot read '" + name + "': " + e.what());
        }
        std::error_code ec;
        stack_.push_back({PbrtTokenizer(std::move(text), name), fs::weakly_canonical(p, ec)});
    }

    fs::path folder_;
    std::vector<Source> stack_;
    std::string last_place_;
    fs::path asset_root_;
};

// ---------------------------------------------------------------------------------------------
// Translation.

// pbrt-v4's named glasses (Schott catalogue), by their index at the d line (587.6 nm); our
// dielectrics take one index.
double named_glass(const std::string& name) {
    static const std::pair<const char*, double> table[] = {
        {"glass-BK7", 1.5168},   {"glass-BAF10", 1.6700}, {"glass-FK51A", 1.4866},
        {"glass-LASF9", 1.8503}, {"glass-F5", 1.6727},    {"glass-F10", 1.7283},
        {"glass-F11", 1.7847}};
    for (const auto& [n, v] : table)
        if (name == n) return v;
    return 0;
}

class Translator {
  public:
    Translator(const fs::path& path,
               const std::function<void(const std::string&)>& warn,
               const fs::path& asset_root)
        : reader_(path, asset_root), warn_(warn) {}

    PbrtDocument translate() {
        // pbrt-v4's defaults, its default sampler (zsobol) included.
        out_["render"] = {
            {"width", 1280}, {"height", 720}, {"spp", 16}, {"max_depth", 6}, {"sampler", "zsobol"}};
        out_["materials"] = json::object();
        out_["objects"] = json::array();
        states_.emplace_back();
        PbrtToken t;
        while (reader_.next(&t)) {
            if (t.kind != PbrtToken::Kind::Word)
                fail(reader_.place(t), "expected a directive, got " + describe(t));
            directive(t);
        }
        if (defining_) fail(defining_place_, "ObjectBegin without ObjectEnd");
        if (states_.size() > 1)
            warn(reader_.place(), "AttributeBegin without AttributeEnd at the end of the file");
        if (!camera_seen_) warn(reader_.place(), "no Camera: pbrt's default camera at the origin, looking down +z");
        camera();
        if (!lights_.empty()) out_["lights"] = lights_;
        if (!media_.empty()) out_["media"] = media_;
        // pbrt-v4's BSDF::f and Sample_f answer in the shading frame alone.
        out_["geometric_side_test"] = false;
        doc_.scene = std::move(out_);
        return std::move(doc_);
    }

  private:
    struct AreaLight {
        json radiance;
        bool two_sided = false;
        std::string place;
    };
    struct State {
        M4 ctm = identity();
        bool reverse = false;
        std::string material;  // our material name; empty: pbrt's default diffuse
        std::optional<AreaLight> area;
        std::string inside, outside;  // media names
    };

    void warn(const std::string& place, const std::string& message) {
        warn_(place + ": warning: " + message);
    }

    static std::string describe(const PbrtToken& t) {
        switch (t.kind) {
            case PbrtToken::Kind::String: return "\"" + t.text + "\"";
            case PbrtToken::Kind::Open: return "[";
            case PbrtToken::Kind::Close: return "]";
            default: return t.text;
        }
    }

    State& state() { return states_.back(); }

    // ---- reading arguments ----

    std::string string_arg(const std::string& directive) {
        PbrtToken t;
        if (!reader_.next(&t) || t.kind != PbrtToken::Kind::String)
            fail(reader_.place(), directive + " needs a quoted string");
        return t.text;
    }

    static double number(const std::string& place, const std::string& text,
                         const std::string& what) {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double v = std::strtod(begin, &end);
        if (end == begin || *end != '\0') fail(place, what + ": expected a number, got " + text);
        if (!std::isfinite(v) || std::abs(v) > 3.4e38)
            fail(place, "number " + text + " is not finite in float");
        return v;
    }

    // `n` numbers, bare or in brackets.
    std::vector<double> numbers_arg(const std::string& directive, size_t n) {
        PbrtToken t;
        std::vector<double> v;
        if (!reader_.next(&t)) fail(reader_.place(), directive + " needs " + std::to_string(n) + " numbers");
        const bool bracket = t.kind == PbrtToken::Kind::Open;
        if (bracket && !reader_.next(&t)) fail(reader_.place(), directive + ": unclosed [");
        for (;;) {
            if (bracket && t.kind == PbrtToken::Kind::Close) break;
            if (t.kind != PbrtToken::Kind::Word)
                fail(reader_.place(t), directive + ": expected a number, got " + describe(t));
            v.push_back(number(reader_.place(t), t.text, directive));
            if (!bracket && v.size() == n) break;
            if (v.size() > n) fail(reader_.place(t), directive + " takes " + std::to_string(n) + " numbers");
            if (!reader_.next(&t)) fail(reader_.place(), directive + " needs " + std::to_string(n) + " numbers");
        }
        if (v.size() != n)
            fail(reader_.place(t), directive + " takes " + std::to_string(n) + " numbers, got " +
                                       std::to_string(v.size()));
        return v;
    }

    PbrtParams params(const std::string& what) {
        PbrtParams out;
        out.what = what;
        PbrtToken t;
        while (reader_.next(&t)) {
            if (t.kind != PbrtToken::Kind::String) {
                reader_.unget(std::move(t));
                break;
            }
            PbrtParam p;
            p.place = reader_.place(t);
            std::istringstream decl(t.text);
            std::string extra;
            if (!(decl >> p.type >> p.name) || (decl >> extra))
                fail(p.place, what + ": expected a parameter as \"type name\", got \"" + t.text + "\"");
            if (p.type == "point") p.type = "point3";
            if (p.type == "vector") p.type = "vector3";
            if (p.type == "normal") p.type = "normal3";
            if (p.type == "color") p.type = "rgb";
            static const std::set<std::string> types = {
                "integer", "float", "point2", "vector2", "point3", "vector3", "normal3",
                "rgb", "spectrum", "blackbody", "bool", "string", "texture"};
            if (!types.count(p.type))
                fail(p.place, what + ": unknown parameter type \"" + p.type + "\"");
            for (const PbrtParam& q : out.list)
                if (q.name == p.name) fail(p.place, what + ": parameter \"" + p.name + "\" given twice");
            if (!reader_.next(&t)) fail(p.place, what + ": parameter \"" + p.name + "\" has no value");
            const bool bracket = t.kind == PbrtToken::Kind::Open;
            if (bracket && !reader_.next(&t)) fail(p.place, what + ": unclosed [");
            for (;;) {
                if (bracket && t.kind == PbrtToken::Kind::Close) break;
                value(p, t, what);
                if (!bracket) break;
                if (!reader_.next(&t)) fail(p.place, what + ": unclosed [");
            }
            const size_t values = p.numbers.size() + p.strings.size() + p.bools.size();
            if (values == 0) fail(p.place, what + ": parameter \"" + p.name + "\" has no value");
            if ((p.numbers.empty() ? 0 : 1) + (p.strings.empty() ? 0 : 1) +
                    (p.bools.empty() ? 0 : 1) > 1)
                fail(p.place, what + ": parameter \"" + p.name + "\" mixes kinds of values");
            out.list.push_back(std::move(p));
        }
        return out;
    }

    void value(PbrtParam& p, const PbrtToken& t, const std::string& what) {
        const std::string place = reader_.place(t);
        if (t.kind == PbrtToken::Kind::Open || t.kind == PbrtToken::Kind::Close)
            fail(place, what + ": unexpected " + describe(t) + " in \"" + p.name + "\"");
        if (p.type == "bool") {
            if (t.text != "true" && t.text != "false")
                fail(place, what + ": \"" + p.name + "\" expects true or false, got " + describe(t));
            p.bools.push_back(t.text == "true");
        } else if (p.type == "string" || p.type == "texture" ||
                   (p.type == "spectrum" && t.kind == PbrtToken::Kind::String)) {
            if (t.kind != PbrtToken::Kind::String)
                fail(place, what + ": \"" + p.name + "\" expects a quoted string, got " + describe(t));
            p.strings.push_back(t.text);
        } else {
            if (t.kind != PbrtToken::Kind::Word)
                fail(place, what + ": \"" + p.name + "\" expects numbers, got " + describe(t));
            p.numbers.push_back(number(place, t.text, what + ": \"" + p.name + "\""));
        }
    }

    // ---- directives ----

    void transform_by(const M4& m) {
        if (active_ == Active::End) return;  // only the end of a motion: not rendered
        state().ctm = mul(state().ctm, m);
    }

    void directive(const PbrtToken& t) {
        const std::string& d = t.text;
        const std::string place = reader_.place(t);
        if (d == "AttributeBegin" || d == "TransformBegin") {
            if (states_.size() >= kMaxAttributeDepth)
                fail(place, d + " nested deeper than " + std::to_string(kMaxAttributeDepth));
            states_.push_back(state());
            transform_only_.push_back(d == "TransformBegin");
        } else if (d == "AttributeEnd" || d == "TransformEnd") {
            if (states_.size() <= 1 || (defining_ && states_.size() <= defining_depth_))
                fail(place, d + " without a matching begin");
            if (transform_only_.back() != (d == "TransformEnd"))
                fail(place, d + " closes " + (transform_only_.back() ? "a TransformBegin"
                                                                     : "an AttributeBegin"));
            State top = states_.back();
            states_.pop_back();
            if (transform_only_.back()) {  // TransformEnd keeps the other attributes
                const M4 ctm = state().ctm;
                state() = top;
                state().ctm = ctm;
            }
            transform_only_.pop_back();
        } else if (d == "Identity") {
            if (active_ != Active::End) state().ctm = identity();
        } else if (d == "Translate") {
            const std::vector<double> v = numbers_arg(d, 3);
            transform_by({1, 0, 0, v[0], 0, 1, 0, v[1], 0, 0, 1, v[2], 0, 0, 0, 1});
        } else if (d == "Scale") {
            const std::vector<double> v = numbers_arg(d, 3);
            transform_by({v[0], 0, 0, 0, 0, v[1], 0, 0, 0, 0, v[2], 0, 0, 0, 0, 1});
        } else if (d == "Rotate") {
            const std::vector<double> v = numbers_arg(d, 4);
            if (!(norm({v[1], v[2], v[3]}) > 0)) fail(place, "Rotate: the axis is zero");
            transform_by(rotation(v[0], {v[1], v[2], v[3]}));
        } else if (d == "LookAt") {
            const std::vector<double> v = numbers_arg(d, 9);
            const V3 eye{v[0], v[1], v[2]}, look{v[3], v[4], v[5]}, up{v[6], v[7], v[8]};
            if (!(norm(sub(look, eye)) > 0)) fail(place, "LookAt: the eye and the target coincide");
            const V3 dir = normalized(sub(look, eye));
            const V3 right = cross(normalized(up), dir);
            if (!(norm(right) > 1e-9)) fail(place, "LookAt: up is parallel to the view direction");
            const V3 r = normalized(right);
            const V3 new_up = cross(dir, r);
            // pbrt's LookAt is camera-from-world: the inverse of the frame (right, up, dir, eye).
            const M4 world_from_camera = {r[0], new_up[0], dir[0], eye[0], r[1], new_up[1],
                                          dir[1], eye[1], r[2], new_up[2], dir[2], eye[2],
                                          0, 0, 0, 1};
            M4 camera_from_world;
            invert(world_from_camera, &camera_from_world);
            transform_by(camera_from_world);
        } else if (d == "Transform" || d == "ConcatTransform") {
            const std::vector<double> v = numbers_arg(d, 16);
            // Written column by column (pbrt transposes what it reads).
            M4 m;
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) m[i * 4 + j] = v[j * 4 + i];
            if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
                fail(place, d + ": a projective matrix (its last column must be 0 0 0 1)");
            if (d == "Transform") {
                if (active_ != Active::End) state().ctm = m;
            } else {
                transform_by(m);
            }
        } else if (d == "CoordinateSystem") {
            named_frames_[string_arg(d)] = state().ctm;
        } else if (d == "CoordSysTransform") {
            const std::string name = string_arg(d);
            auto it = named_frames_.find(name);
            if (it == named_frames_.end()) fail(place, "no coordinate system named \"" + name + "\"");
            if (active_ != Active::End) state().ctm = it->second;
        } else if (d == "ActiveTransform") {
            PbrtToken a;
            if (!reader_.next(&a) || a.kind != PbrtToken::Kind::Word ||
                (a.text != "StartTime" && a.text != "EndTime" && a.text != "All"))
                fail(place, "ActiveTransform takes StartTime, EndTime or All");
            active_ = a.text == "EndTime" ? Active::End : Active::Start;
            if (a.text != "All" && !motion_warned_) {
                warn(place, "motion blur is not supported; shapes are rendered at the start time");
                motion_warned_ = true;
            }
        } else if (d == "TransformTimes") {
            numbers_arg(d, 2);
        } else if (d == "ReverseOrientation") {
            state().reverse = !state().reverse;
        } else if (d == "Option") {
            PbrtParams p = params(d);
            for (const PbrtParam& q : p.list) warn(q.place, "Option \"" + q.name + "\" is not supported; ignored");
        } else if (d == "ColorSpace") {
            const std::string name = string_arg(d);
            if (name != "srgb") warn(place, "ColorSpace \"" + name + "\": wavetrace renders in linear sRGB");
        } else if (d == "Camera") {
            camera_directive(place);
        } else if (d == "Film") {
            film(place);
        } else if (d == "Sampler") {
            const std::string type = string_arg(d);
            PbrtParams p = params("Sampler \"" + type + "\"");
            out_["render"]["spp"] = p.integer("pixelsamples", 16, 1, kMaxSpp);
            // Independent and zsobol as they are; every other low-discrepancy sampler as our
            // Sobol one (pbrt-v4's paddedsobol is the same construction; the others order or
            // stratify otherwise).
            out_["render"]["sampler"] =
                type == "independent" || type == "zsobol" ? type : std::string("sobol");
            if (type != "independent" && type != "zsobol" && type != "sobol" &&
                type != "paddedsobol")
                warn(place, "Sampler \"" + type +
                                "\": wavetrace draws Owen-scrambled Sobol points per pixel");
            p.finish(pwarn(), {"seed", "randomization", "jitter", "dimensions", "xsamples", "ysamples"});
        } else if (d == "Integrator") {
            integrator(place);
        } else if (d == "PixelFilter") {
            pixel_filter(place);
        } else if (d == "Accelerator") {
            string_arg(d);
            params(d);  // wavetrace builds its own BVH
        } else if (d == "WorldBegin") {
            state().ctm = identity();
            named_frames_["world"] = identity();
        } else if (d == "WorldEnd") {
            // pbrt-v3's end of the scene: nothing to do.
        } else if (d == "MakeNamedMaterial") {
            const std::string name = string_arg(d);
            PbrtParams p = params("MakeNamedMaterial \"" + name + "\"");
            PbrtParam* type = p.get("type");
            if (!type || type->strings.size() != 1)
                fail(place, "MakeNamedMaterial \"" + name + "\" needs a \"string type\"");
            named_materials_[name] = material(type->strings[0], p, place, "\"" + name + "\"");
        } else if (d == "NamedMaterial") {
            const std::string name = string_arg(d);
            auto it = named_materials_.find(name);
            if (it == named_materials_.end()) fail(place, "no material named \"" + name + "\"");
            state().material = it->second;
        } else if (d == "Material") {
            const std::string type = string_arg(d);
            PbrtParams p = params("Material \"" + type + "\"");
            state().material = material(type, p, place, "");
        } else if (d == "Texture") {
            texture_directive(place);
        } else if (d == "AreaLightSource") {
            area_light(place);
        } else if (d == "LightSource") {
            light(place);
        } else if (d == "MakeNamedMedium") {
            named_medium(place);
        } else if (d == "MediumInterface") {
            state().inside = string_arg(d);
            PbrtToken o;
            if (reader_.next(&o)) {
                if (o.kind == PbrtToken::Kind::String) state().outside = o.text;
                else reader_.unget(std::move(o)), state().outside = state().inside;
            }
            for (const std::string* m : {&state().inside, &state().outside})
                if (!m->empty() && !media_names_.count(*m) && !skipped_media_.count(*m))
                    fail(place, "no medium named \"" + *m + "\"");
        } else if (d == "Shape") {
            shape(place);
        } else if (d == "ObjectBegin") {
            const std::string name = string_arg(d);
            if (defining_) fail(place, "ObjectBegin inside ObjectBegin");
            if (instances_.count(name)) fail(place, "a second object named \"" + name + "\"");
            if (states_.size() >= kMaxAttributeDepth)
                fail(place, d + " nested deeper than " + std::to_string(kMaxAttributeDepth));
            states_.push_back(state());  // ObjectBegin opens an attribute block
            transform_only_.push_back(false);
            defining_ = true;
            defining_depth_ = states_.size();
            defining_name_ = name;
            defining_place_ = place;
            instances_[name];
        } else if (d == "ObjectEnd") {
            if (!defining_) fail(place, "ObjectEnd without ObjectBegin");
            if (states_.size() != defining_depth_)
                fail(place, "ObjectEnd inside an AttributeBegin or TransformBegin of its object");
            defining_ = false;
            states_.pop_back();
            transform_only_.pop_back();
        } else if (d == "ObjectInstance") {
            const std::string name = string_arg(d);
            if (defining_) fail(place, "ObjectInstance inside ObjectBegin");
            auto it = instances_.find(name);
            if (it == instances_.end()) fail(place, "no object named \"" + name + "\"");
            json group = {{"type", "group"}, {"transform", matrix_step(state().ctm)},
                          {"objects", json::array()}};
            for (const json& o : it->second.objects) {
                count_placement(o, place);
                group["objects"].push_back(o);
            }
            if (!group["objects"].empty()) push(std::move(group), place);
        } else if (d == "Include" || d == "Import") {
            reader_.include(string_arg(d), place);
        } else if (d == "Attribute") {
            const std::string target = string_arg(d);
            PbrtParams p = params("Attribute \"" + target + "\"");
            warn(place, "Attribute \"" + target + "\" is not supported; its defaults are pbrt's own");
        } else {
            fail(place, "unknown directive " + d);
        }
    }

    std::function<void(const std::string&, const std::string&)> pwarn() {
        return [this](const std::string& place, const std::string& message) { warn(place, message); };
    }

    // ---- camera, film, integrator ----

    void camera_directive(const std::string& place) {
        const std::string type = string_arg("Camera");
        PbrtParams p = params("Camera \"" + type + "\"");
        if (type != "perspective" && type != "orthographic")
            warn(place, "Camera \"" + type + "\" is not supported; rendered as a perspective camera");
        orthographic_ = type == "orthographic";
        camera_seen_ = true;
        camera_ctm_ = state().ctm;
        camera_place_ = place;
        fov_ = p.number("fov", 90);
        if (!(fov_ > 0 && fov_ < 180)) fail(place, "Camera: fov must lie in (0, 180)");
        lens_radius_ = p.number("lensradius", 0);
        focal_distance_ = p.number("focaldistance", 1e6);
        if (lens_radius_ < 0) fail(place, "Camera: lensradius must be >= 0");
        if (!(focal_distance_ > 0)) fail(place, "Camera: focaldistance must be > 0");
        screen_window_.clear();
        if (const std::vector<double>* w = p.numbers("screenwindow", 4); w && orthographic_) {
            if (w->size() != 4 || !((*w)[1] > (*w)[0] && (*w)[3] > (*w)[2]))
                fail(place,
                     "Camera: screenwindow must be [xmin xmax ymin ymax], each max above its min");
            if ((*w)[0] + (*w)[1] != 0 || (*w)[2] + (*w)[3] != 0)
                warn(place, "Camera: an off-centre screenwindow is rendered centred");
            screen_window_ = *w;
        } else if (p.get("screenwindow")) {
            warn(place, "Camera: screenwindow is not supported; ignored");
        }
        if (p.get("frameaspectratio"))
            warn(place, "Camera: frameaspectratio is not supported; ignored");
        if (orthographic_ && lens_radius_ > 0) {
            warn(place, "Camera: an orthographic camera's lens is not supported; rendered sharp");
            lens_radius_ = 0;
        }
        p.finish(pwarn(), {"shutteropen", "shutterclose"});
        M4 inverse;
        if (!invert(camera_ctm_, &inverse)) fail(place, "Camera: the transform is singular");
        named_frames_["camera"] = inverse;
    }

    // pbrt's camera looks along +z of camera space, +y up, +x to the image's right; `fov` is
    // the field of view of the image's shorter side.
    void camera() {
        M4 world_from_camera = identity();
        if (camera_seen_ && !invert(camera_ctm_, &world_from_camera))
            fail(camera_place_, "Camera: the transform is singular");
        const V3 from = apply_point(world_from_camera, {0, 0, 0});
        const V3 forward = normalized(apply_vector(world_from_camera, {0, 0, 1}));
        const V3 up = apply_vector(world_from_camera, {0, 1, 0});
        const V3 right = apply_vector(world_from_camera, {1, 0, 0});
        const double width = out_["render"]["width"].get<double>();
        const double height = out_["render"]["height"].get<double>();
        double tan_v = std::tan(fov_ * kPiD / 360);
        if (width < height) tan_v *= height / width;
        json c = {{"look_from", to_json(from)},
                  {"look_at", to_json(add(from, forward))},
                  {"up", to_json(up)},
                  {"vfov", 2 * std::atan(tan_v) * 180 / kPiD}};
        // Our image's right is forward x up; pbrt's is camera +x.
        if (dot(cross(forward, up), right) < 0) c["mirror"] = true;
        c["filter"] = filter_;
        if (lens_radius_ > 0) {
            c["aperture"] = 2 * lens_radius_;
            c["focus_distance"] = focal_distance_;
        }
        if (orthographic_) {
            // pbrt's screen window, in camera space: [-aspect, aspect] x [-1, 1] for a wide image,
            // [-1, 1] x [-1 / aspect, 1 / aspect] for a tall one, unless the file gives it.
            const double aspect = width / height;
            double w = aspect > 1 ? 2 * aspect : 2, h = aspect > 1 ? 2 : 2 / aspect;
            if (screen_window_.size() == 4) {
                w = screen_window_[1] - screen_window_[0];
                h = screen_window_[3] - screen_window_[2];
            }
            c.erase("vfov");
            c["type"] = "orthographic";
            c["view_width"] = w * norm(right);
            c["view_height"] = h * norm(up);
        }
        out_["camera"] = c;
    }

    void film(const std::string& place) {
        const std::string type = string_arg("Film");
        PbrtParams p = params("Film \"" + type + "\"");
        if (type != "rgb") warn(place, "Film \"" + type + "\": rendered as an rgb film");
        const int w = p.integer("xresolution", 1280, 1, kMaxImageSide);
        const int h = p.integer("yresolution", 720, 1, kMaxImageSide);
        out_["render"]["width"] = w;
        out_["render"]["height"] = h;
        for (const char* n : {"cropwindow", "pixelbounds"})
            if (p.get(n)) warn(place, std::string("Film: ") + n + " is not supported; the whole image is rendered");
        if (p.number("iso", 100) != 100 || p.number("exposuretime", 1) != 1)
            warn(place, "Film: iso and exposuretime are not supported; the exposure is 1");
        // The command line's -o names the image, not `filename`.
        p.finish(pwarn(), {"filename", "savefp16", "diagonal", "sensor", "whitebalance"});
    }

    // pbrt's box (radius 0.5), triangle (2) and gaussian (1.5, sigma 0.5) filters are ours;
    // pbrt samples them by a table, we by their exact inverse distributions.
    void pixel_filter(const std::string& place) {
        const std::string type = string_arg("PixelFilter");
        PbrtParams p = params("PixelFilter \"" + type + "\"");
        const double fallback = type == "box" ? 0.5 : type == "triangle" ? 2.0 : 1.5;
        const double rx = p.number("xradius", fallback), ry = p.number("yradius", fallback);
        if (rx != ry) warn(place, "PixelFilter: xradius and yradius differ; their mean is used");
        const double r = 0.5 * (rx + ry);
        if (type == "box") {
            filter_ = {{"type", "box"}, {"radius", r}};
        } else if (type == "triangle") {
            filter_ = {{"type", "tent"}, {"radius", r}};
        } else if (type == "gaussian") {
            filter_ = {{"type", "gaussian"}, {"radius", r}, {"sigma", p.number("sigma", 0.5)}};
        } else {
            warn(place, "PixelFilter \"" + type + "\" is not supported; a box filter is used");
            filter_ = {{"type", "box"}, {"radius", 0.5}};
            for (PbrtParam& q : p.list) q.used = true;
        }
        p.finish(pwarn());
    }

    void integrator(const std::string& place) {
        const std::string type = string_arg("Integrator");
        PbrtParams p = params("Integrator \"" + type + "\"");
        // pbrt counts bounces (maxdepth 1: direct light); wavetrace, as Mitsuba, path
        // segments (max_depth 2: direct light).
        const int depth = p.integer("maxdepth", 5, 0, kMaxDepth - 1);
        if (depth == 0) warn(place, "Integrator: maxdepth 0 (emitters only) is rendered as 1 bounce");
        out_["render"]["max_depth"] = std::max(depth, 1) + 1;
        if (type != "path" && type != "volpath")
            warn(place, "Integrator \"" + type + "\": wavetrace path traces instead");
        if (p.boolean("regularize", false))
            warn(place, "Integrator: regularize is not supported; ignored");
        p.finish(pwarn(), {"lightsampler"});
    }

    // ---- colours, spectra, textures ----

    // pbrt's named illuminants: their colour, of unit luminance. D65 is sRGB's white, A the
    // black body of 2856 K by definition; D50 is approximated by the black body of its
    // correlated colour temperature.
    static std::optional<Color> named_illuminant(const std::string& name) {
        if (name == "stdillum-D65") return Color{1.0f, 1.0f, 1.0f};
        if (name == "stdillum-A") return blackbody(2856);
        if (name == "stdillum-D50") return blackbody(5003);
        return std::nullopt;
    }
    static Color blackbody(double kelvin) {
        std::vector<std::pair<double, double>> points;
        for (int nm = 360; nm <= 830; nm += 5) points.emplace_back(nm, planck(nm, kelvin));
        const Color c = spectrum_to_rgb(points, false);
        return c * static_cast<float>(1 / luminance(c));
    }

    // A spectrum parameter as RGB. `illuminant`: pbrt scales an emission spectrum to unit
    // luminance (its rgb is taken as it is); `bounded`: a reflectance, clamped to [0, 1].
    Color spectrum(PbrtParam& p, bool illuminant, bool bounded) {
        if (p.type == "rgb") {
            if (p.numbers.size() != 3) fail(p.place, "\"" + p.name + "\" should be three numbers");
            Color c(static_cast<float>(p.numbers[0]), static_cast<float>(p.numbers[1]),
                    static_cast<float>(p.numbers[2]));
            if (c.x < 0 || c.y < 0 || c.z < 0) fail(p.place, "\"" + p.name + "\" must not be negative");
            if (bounded && (c.x > 1 || c.y > 1 || c.z > 1)) {
                warn(p.place, "\"" + p.name + "\": a reflectance above 1 is clamped to 1");
                c = Color(std::min(c.x, 1.0f), std::min(c.y, 1.0f), std::min(c.z, 1.0f));
            }
            return c;
        }
        if (p.type == "float" && p.numbers.size() == 1) {
            if (p.numbers[0] < 0) fail(p.place, "\"" + p.name + "\" must not be negative");
            return Color(static_cast<float>(bounded ? std::min(p.numbers[0], 1.0) : p.numbers[0]));
        }
        if (p.type == "blackbody") {
            if (p.numbers.size() != 1 || !(p.numbers[0] > 0))
                fail(p.place, "\"" + p.name + "\": a blackbody takes one temperature > 0");
            return blackbody(p.numbers[0]);
        }
        if (p.type != "spectrum") fail(p.place, "\"" + p.name + "\" should be a spectrum or an rgb");
        std::vector<std::pair<double, double>> points;
        if (!p.strings.empty()) {
            if (auto c = named_illuminant(p.strings[0])) return *c;
            points = spectrum_file(p);
        } else {
            if (p.numbers.size() < 4 || p.numbers.size() % 2 != 0)
                fail(p.place, "\"" + p.name + "\": a spectrum is wavelength value pairs (two or more)");
            for (size_t i = 0; i < p.numbers.size(); i += 2) {
                if (i > 0 && !(p.numbers[i] > p.numbers[i - 2]))
                    fail(p.place, "\"" + p.name + "\": wavelengths must increase");
                points.emplace_back(p.numbers[i], p.numbers[i + 1]);
            }
        }
        Color c = spectrum_to_rgb(points, bounded);
        if (illuminant) {
            const double y = luminance(c);
            if (!(y > 0)) fail(p.place, "\"" + p.name + "\": the spectrum has no luminance");
            c = c * static_cast<float>(1 / y);
        }
        return c;
    }

    // A spectrum from a file of "wavelength value" pairs (a named spectrum we lack is an error
    // naming it).
    std::vector<std::pair<double, double>> spectrum_file(const PbrtParam& p) {
        const std::string& name = p.strings[0];
        const fs::path path = reader_.resolve(name);
        std::error_code ec;
        if (!fs::exists(path, ec))
            fail(p.place, "\"" + p.name + "\": no named spectrum or file \"" + name + "\"");
        try {
            check_input_file(path, uintmax_t(1) << 20, "spectrum files");
            reader_.confine(path);
        } catch (const std::runtime_error& e) {
            fail(p.place, "spectrum file '" + path.string() + "': " + e.what());
        }
        std::ifstream in(path);
        std::vector<std::pair<double, double>> points;
        std::string word;
        std::vector<double> values;
        while (in >> word) {
            if (word[0] == '#') {
                std::getline(in, word);
                continue;
            }
            values.push_back(number(p.place, word, "spectrum file '" + path.string() + "'"));
        }
        if (values.size() < 4 || values.size() % 2)
            fail(p.place, "spectrum file '" + path.string() + "': expected wavelength value pairs");
        for (size_t i = 0; i < values.size(); i += 2) {
            if (i > 0 && !(values[i] > values[i - 2]))
                fail(p.place, "spectrum file '" + path.string() + "': wavelengths must increase");
            points.emplace_back(values[i], values[i + 1]);
        }
        return points;
    }

    static json color_json(Color c) { return json::array({c.x, c.y, c.z}); }

    // A colour-valued material parameter: a spectrum, or a texture by name.
    json color_param(PbrtParams& ps, const std::string& name, json fallback, bool bounded) {
        PbrtParam* p = ps.get(name);
        if (!p) return fallback;
        if (p->type == "texture") {
            const std::string tex = p->strings.at(0);
            auto it = color_textures_.find(tex);
            if (it != color_textures_.end()) return it->second;
            auto f = float_textures_.find(tex);
            if (f != float_textures_.end()) return f->second;
            fail(p->place, "no texture named \"" + tex + "\"");
        }
        return color_json(spectrum(*p, false, bounded));
    }

    // A float parameter that our materials take as a number: a float, or a constant texture.
    double float_param(PbrtParams& ps, const std::string& name, double fallback) {
        PbrtParam* p = ps.get(name);
        if (!p) return fallback;
        if (p->type == "texture") {
            auto it = float_textures_.find(p->strings.at(0));
            if (it == float_textures_.end()) fail(p->place, "no float texture named \"" + p->strings.at(0) + "\"");
            if (it->second.is_number()) return it->second.get<double>();
            warn(p->place, ps.what + ": \"" + name + "\" as a texture is not supported; " +
                               std::to_string(fallback) + " is used");
            return fallback;
        }
        if (p->numbers.size() != 1) fail(p->place, ps.what + ": \"" + name + "\" should be one float");
        return p->numbers[0];
    }

    // pbrt's uv mapping: (su u + du, sv v + dv).
    static json uv_transform(PbrtParams& p) {
        const double su = p.number("uscale", 1), sv = p.number("vscale", 1);
        const double du = p.number("udelta", 0), dv = p.number("vdelta", 0);
        json t = json::object();
        if (su != 1 || sv != 1) t["scale"] = json::array({su, sv});
        if (du != 0 || dv != 0) t["offset"] = json::array({du, dv});
        return t;
    }

    void texture_directive(const std::string& place) {
        const std::string name = string_arg("Texture");
        const std::string kind = string_arg("Texture");
        const std::string type = string_arg("Texture");
        PbrtParams p = params("Texture \"" + name + "\" \"" + type + "\"");
        const bool is_float = kind == "float";
        if (!is_float && kind != "spectrum")
            fail(place, "Texture \"" + name + "\": the kind is \"float\" or \"spectrum\", got \"" + kind + "\"");
        json t;
        const std::string mapping = p.string("mapping", "uv");
        if (mapping != "uv") warn(place, "Texture: mapping \"" + mapping + "\" is not supported; uv is used");
        if (type == "imagemap") {
            const std::string file = p.string("filename", "");
            if (file.empty()) fail(place, "Texture \"" + name + "\": imagemap needs a filename");
            t = {{"type", "image"}, {"file", reader_.relative(file)}};
            const std::string encoding = p.string("encoding", "sRGB");
            if (encoding == "linear") t["raw"] = true;
            else if (encoding != "sRGB")
                warn(place, "Texture: encoding \"" + encoding + "\" is not supported; sRGB is used");
            const json uv = uv_transform(p);
            if (!uv.empty()) t["uv_transform"] = uv;
            const double scale = p.number("scale", 1);
            if (scale != 1) t["factor"] = scale;
            if (p.boolean("invert", false)) warn(place, "Texture: invert is not supported; ignored");
            const std::string wrap = p.string("wrap", "repeat");
            if (wrap == "clamp" || wrap == "black")
                t["wrap"] = wrap;
            else if (wrap != "repeat")
                warn(place, "Texture: wrap \"" + wrap + "\" is not supported; repeat is used");
            // pbrt-v4's filters: point (the texel), bilinear, and the mip-mapped trilinear and
            // EWA, which at a texel's footprint or less are bilinear.
            const std::string filter = p.string("filter", "bilinear");
            if (filter == "point") t["filter"] = "nearest";
            else if (filter != "bilinear")
                warn(place, "Texture: filter \"" + filter + "\" is not supported; bilinear is used");
            p.finish(pwarn(), {"maxanisotropy"});
        } else if (type == "checkerboard") {
            const int dimension = p.integer("dimension", 2, 2, 3);
            json even = texture_value(p, "tex1", 1.0, is_float);
            json odd = texture_value(p, "tex2", 0.0, is_float);
            if (dimension == 2) {
                t = {{"type", "uv_checker"}, {"scale", 1}, {"even", even}, {"odd", odd}};
                const json uv = uv_transform(p);
                if (!uv.empty()) t["uv_transform"] = uv;
            } else {
                // pbrt's solid checkerboard has unit cells in the texture's own space.
                t = {{"type", "checker"}, {"scale", 1}, {"even", even}, {"odd", odd}};
                const M4& m = state().ctm;
                if (m != identity())
                    warn(place, "Texture: a 3-D checkerboard's transform is not supported; "
                                "unit cells in world space");
            }
            p.finish(pwarn(), {"filter"});
        } else if (type == "constant") {
            t = texture_value(p, "value", 1.0, is_float);
            p.finish(pwarn());
        } else if (type == "scale") {
            json tex = texture_value(p, "tex", 1.0, is_float);
            json scale = texture_value(p, "scale", 1.0, true);
            t = scale_texture(tex, scale);
            p.finish(pwarn());
        } else {
            warn(place, "Texture \"" + type + "\" is not supported; a constant 0.5 stands in");
            t = 0.5;
        }
        (is_float ? float_textures_ : color_textures_)[name] = t;
    }

    // A texture's parameter that is a value or another texture.
    json texture_value(PbrtParams& p, const std::string& name, double fallback, bool is_float) {
        PbrtParam* q = p.get(name);
        if (!q) return fallback;
        if (q->type == "texture") {
            const std::string& tex = q->strings.at(0);
            auto& table = is_float ? float_textures_ : color_textures_;
            auto it = table.find(tex);
            if (it == table.end()) fail(q->place, "no " + std::string(is_float ? "float" : "spectrum") + " texture named \"" + tex + "\"");
            return it->second;
        }
        if (q->type == "float") {
            if (q->numbers.size() != 1) fail(q->place, "\"" + name + "\" should be one float");
            return q->numbers[0];
        }
        return color_json(spectrum(*q, false, false));
    }

    // tex times scale: folded into a number, a colour or an image's factor where one is a
    // number, else a product texture.
    json scale_texture(json tex, const json& scale) {
        auto times = [](const json& c, double s) {
            if (c.is_number()) return json(c.get<double>() * s);
            json r = json::array();
            for (const json& x : c) r.push_back(x.get<double>() * s);
            return r;
        };
        if (scale.is_number()) {
            const double s = scale.get<double>();
            if (tex.is_number() || tex.is_array()) return times(tex, s);
            if (tex.is_object() && tex.value("type", "") == "image") {
                tex["factor"] = tex.contains("factor") ? times(tex["factor"], s) : json(s);
                return tex;
            }
        } else if (tex.is_number() && scale.is_object() && scale.value("type", "") == "image") {
            json r = scale;
            r["factor"] = times(r.contains("factor") ? r["factor"] : json(1.0), tex.get<double>());
            return r;
        }
        return {{"type", "product"}, {"factors", json::array({tex, scale})}};
    }

    // ---- materials ----

    std::string add_material(json m, const std::string& place, const std::string& name) {
        std::string key = name.empty() ? m["type"].get<std::string>() + " at " +
                                             fs::path(place).filename().string()
                                       : name;
        while (out_["materials"].contains(key)) key += "'";
        out_["materials"][key] = std::move(m);
        return key;
    }

    // pbrt-v4's roughness: alpha = sqrt(roughness) unless remaproughness is false. With
    // `anisotropic` (a material that takes them), unequal uroughness and vroughness go there as
    // (alpha_u, alpha_v) and the return value is -1; otherwise they are rendered as their mean.
    double alpha(PbrtParams& p, const std::string& place, const std::string& prefix = "",
                 std::pair<double, double>* anisotropic = nullptr) {
        const bool remap = p.boolean("remaproughness", true);
        auto to_alpha = [&](double r) {
            double a = remap ? std::sqrt(std::max(r, 0.0)) : r;
            if (a < 0) fail(place, p.what + ": roughness must not be negative");
            if (a > 1) {
                warn(place, p.what + ": alpha above 1 is clamped to 1");
                a = 1;
            }
            return a;
        };
        double r = float_param(p, prefix + "roughness", 0);
        const bool has_uv = p.get(prefix + "uroughness") || p.get(prefix + "vroughness");
        if (has_uv) {
            const double u = float_param(p, prefix + "uroughness", r),
                         v = float_param(p, prefix + "vroughness", r);
            if (u != v && anisotropic && (u > 0) == (v > 0)) {
                *anisotropic = {to_alpha(u), to_alpha(v)};
                return -1;
            }
            if (u != v) warn(place, p.what + ": anisotropic roughness is rendered with the mean");
            r = 0.5 * (u + v);
        }
        return to_alpha(r);
    }

    json ior(PbrtParams& p, const std::string& name, double fallback, const std::string& place) {
        PbrtParam* q = p.get(name);
        if (!q) return fallback;
        double eta = 0;
        if (q->type == "float") {
            eta = q->numbers.size() == 1 ? q->numbers[0] : 0;
        } else if (q->type == "spectrum" && !q->strings.empty()) {
            eta = named_glass(q->strings[0]);
            if (eta == 0) {
                const Color c = spectrum(*q, false, false);
                eta = (c.x + c.y + c.z) / 3;
            }
        } else if (q->type == "spectrum") {
            // pbrt disperses light by such a spectrum; ours has one index: its value at 587.6 nm.
            const auto& v = q->numbers;
            if (v.size() < 2 || v.size() % 2) fail(q->place, "\"" + name + "\": wavelength value pairs");
            eta = v[1];
            for (size_t i = 0; i + 2 < v.size(); i += 2)
                if (v[i] <= 587.6 && v[i + 2] >= 587.6)
                    eta = v[i + 1] + (v[i + 3] - v[i + 1]) * (587.6 - v[i]) / (v[i + 2] - v[i]);
            warn(q->place, "\"" + name + "\": no dispersion; the index at 587.6 nm is used");
        } else if (q->type == "texture") {
            eta = float_param(p, name, fallback);
        }
        if (!(eta > 0)) fail(place, p.what + ": \"" + name + "\" must be a positive index");
        return eta;
    }

    // Our material for pbrt's `type` with parameters p; returns the name in /materials.
    std::string material(const std::string& type, PbrtParams& p, const std::string& place,
                         const std::string& name) {
        p.what = name.empty() ? "Material \"" + type + "\"" : "MakeNamedMaterial " + name;
        json m;
        if (type == "diffuse" || type == "diffusetransmission") {
            if (type != "diffusetransmission") {
                m = {{"type", "lambertian"}, {"albedo", color_param(p, "reflectance", 0.5, true)}};
            } else {
                warn(place, p.what + ": transmission is not rendered; a diffuse reflector");
                m = {{"type", "lambertian"}, {"albedo", color_param(p, "reflectance", 0.25, true)}};
                p.get("transmittance");
            }
        } else if (type == "coateddiffuse") {
            // Our plastic: Mitsuba's model of a dielectric coating over a diffuse base, with
            // the base's inner reflections as a geometric series (nonlinear); pbrt simulates
            // the same layers stochastically, so the two differ in the multiple scattering
            // of rough coatings only.
            m = {{"type", "plastic"},
                 {"albedo", color_param(p, "reflectance", 0.5, true)},
                 {"ior", ior(p, "eta", 1.5, place)},
                 {"alpha", alpha(p, place)},
                 {"nonlinear", true}};
            const json albedo = color_param(p, "albedo", 0.0, true);
            if (albedo != json(0.0) && albedo != json::array({0.0, 0.0, 0.0}))
                warn(place, p.what + ": a scattering layer (albedo) is not rendered");
            for (const char* n : {"thickness", "g", "maxdepth", "nsamples"}) p.get(n);
        } else if (type == "conductor" || type == "coatedconductor") {
            if (type == "coatedconductor")
                warn(place, p.what + ": the coating is not rendered; a bare conductor");
            const std::string prefix = type == "coatedconductor" ? "conductor." : "";
            std::pair<double, double> uv;
            const double a = alpha(p, place, prefix, &uv);
            m = a >= 0 ? json{{"type", "conductor"}, {"alpha", a}}
                       : json{{"type", "conductor"}, {"alpha_u", uv.first}, {"alpha_v", uv.second}};
            conductor(p, prefix, m, place);
            if (type == "coatedconductor")
                for (const char* n : {"interface.roughness", "interface.uroughness",
                                      "interface.vroughness", "interface.eta", "thickness", "g",
                                      "albedo", "maxdepth", "nsamples"})
                    p.get(n);
        } else if (type == "dielectric") {
            m = {{"type", "dielectric"}, {"ior", ior(p, "eta", 1.5, place)},
                 {"alpha", alpha(p, place)}};
        } else if (type == "thindielectric") {
            m = {{"type", "thin_dielectric"}, {"ior", ior(p, "eta", 1.5, place)}};
        } else if (type == "interface" || type == "" || type == "none") {
            // No surface: the shape only bounds media (MediumInterface).
            p.finish(pwarn());
            return kInterface;
        } else if (type == "mix") {
            PbrtParam* q = p.get("materials");
            if (!q || q->strings.size() != 2) fail(place, p.what + ": needs two \"materials\"");
            // pbrt-v4's MixMaterial: the second with probability "amount", as our blend.
            m = {{"type", "blend"}, {"materials", json::array()}};
            for (const std::string& n : q->strings) {
                auto it = named_materials_.find(n);
                if (it == named_materials_.end()) fail(q->place, "no material named \"" + n + "\"");
                const json& c = it->second == kInterface ? json() : out_["materials"][it->second];
                if (it->second == kInterface || c.contains("opacity") ||
                    c["type"] == "thin_dielectric")
                    fail(q->place, p.what + ": \"" + n +
                                       "\" cannot be mixed (no surface, an alpha "
                                       "mask or a thindielectric)");
                m["materials"].push_back(it->second);
            }
            PbrtParam* amount = p.get("amount");
            if (amount && amount->type == "texture") {
                auto it = float_textures_.find(amount->strings.at(0));
                if (it == float_textures_.end())
                    fail(amount->place, "no float texture named \"" + amount->strings.at(0) + "\"");
                m["weight"] = it->second;
            } else {
                if (amount && amount->numbers.size() != 1)
                    fail(amount->place, p.what + ": \"amount\" should be one float");
                // pbrt takes an amount outside [0, 1] as its nearer end.
                m["weight"] = amount ? std::clamp<double>(amount->numbers[0], 0.0, 1.0) : 0.5;
            }
        } else {
            warn(place, p.what + ": material \"" + type + "\" is not supported; a grey diffuse stands in");
            m = {{"type", "lambertian"}, {"albedo", 0.5}};
            for (PbrtParam& q : p.list) q.used = true;
        }
        if (PbrtParam* n = p.get("normalmap")) {
            if (n->strings.size() != 1) fail(n->place, "\"normalmap\" should be a file name");
            m["normal_map"] = {{"type", "image"}, {"file", reader_.relative(n->strings[0])}, {"raw", true}};
        }
        if (PbrtParam* d = p.get("displacement")) {
            if (d->type != "texture") fail(d->place, "\"displacement\" should be a float texture");
            auto it = float_textures_.find(d->strings.at(0));
            if (it == float_textures_.end()) fail(d->place, "no float texture named \"" + d->strings[0] + "\"");
            if (it->second.is_object()) {
                m["bump_map"] = it->second;
            } else {
                warn(d->place, "\"displacement\": a constant displaces nothing; ignored");
            }
        }
        p.finish(pwarn());
        return add_material(std::move(m), place, name.empty() ? "" : name.substr(1, name.size() - 2));
    }

    // A conductor's eta and k: named spectra (metal-Au-eta), values, or a reflectance.
    void conductor(PbrtParams& p, const std::string& prefix, json& m, const std::string& place) {
        PbrtParam* eta = p.get(prefix + "eta");
        PbrtParam* k = p.get(prefix + "k");
        PbrtParam* r = p.get("reflectance");
        if (r && !eta && !k) {
            // pbrt: eta = 1, k = 2 sqrt(r) / sqrt(1 - r): the normal-incidence Fresnel is r.
            if (r->type == "texture") {
                warn(place, p.what + ": a reflectance texture is not supported; its mean is lost, Cu is used");
                m["metal"] = "Cu";
                return;
            }
            const Color c = spectrum(*r, false, true);
            auto kk = [](float x) {
                const double v = std::min(static_cast<double>(x), 0.9999);
                return 2 * std::sqrt(v) / std::sqrt(1 - v);
            };
            m["eta"] = 1;
            m["k"] = json::array({kk(c.x), kk(c.y), kk(c.z)});
            return;
        }
        auto metal_of = [](const PbrtParam* q, const char* suffix) -> std::string {
            if (!q || q->strings.size() != 1) return "";
            const std::string& s = q->strings[0];
            const std::string tail = std::string("-") + suffix;
            if (s.rfind("metal-", 0) != 0 || s.size() <= 6 + tail.size() ||
                s.compare(s.size() - tail.size(), tail.size(), tail) != 0)
                return "";
            return s.substr(6, s.size() - 6 - tail.size());
        };
        std::string me = eta ? metal_of(eta, "eta") : "Cu";
        std::string mk = k ? metal_of(k, "k") : "Cu";
        if (!me.empty() && me == mk) {
            if (me == "CuZn") {
                warn(place, p.what + ": brass (metal-CuZn) is not in our table; Cu is used");
                me = "Cu";
            }
            m["metal"] = me;
            return;
        }
        m["eta"] = eta ? color_json(spectrum(*eta, false, false)) : json(0.2);
        m["k"] = k ? color_json(spectrum(*k, false, false)) : json(3.9);
    }

    // ---- lights ----

    void area_light(const std::string& place) {
        const std::string type = string_arg("AreaLightSource");
        PbrtParams p = params("AreaLightSource \"" + type + "\"");
        if (type != "diffuse") fail(place, "AreaLightSource \"" + type + "\" (pbrt has diffuse only)");
        AreaLight a;
        PbrtParam* l = p.get("L");
        const Color radiance = l ? spectrum(*l, true, false) : Color(1.0f);
        const double scale = p.number("scale", 1);
        a.radiance = color_json(radiance * static_cast<float>(scale));
        a.two_sided = p.boolean("twosided", false);
        a.place = place;
        if (p.get("filename")) warn(place, "AreaLightSource: an image of emission is not supported; L is used");
        if (p.get("power")) warn(place, "AreaLightSource: power is not supported; L and scale are used");
        p.finish(pwarn());
        state().area = a;
    }

    void light(const std::string& place) {
        const std::string type = string_arg("LightSource");
        PbrtParams p = params("LightSource \"" + type + "\"");
        const M4& m = state().ctm;
        double scale = p.number("scale", 1);
        auto intensity = [&](const char* name) {
            PbrtParam* q = p.get(name);
            return q ? spectrum(*q, true, false) : Color(1.0f);
        };
        if (type == "point") {
            const Color i = intensity("I");
            const double power = p.number("power", -1);
            if (power > 0) scale *= power / (4 * kPiD);
            const V3 from = apply_point(m, p.triple("from", {0, 0, 0}));
            lights_.push_back({{"type", "point"}, {"position", to_json(from)},
                               {"intensity", color_json(i * static_cast<float>(scale))}});
        } else if (type == "spot") {
            const Color i = intensity("I");
            const double cone = p.number("coneangle", 30), delta = p.number("conedelta", 5);
            if (!(cone > 0 && cone <= 90)) fail(place, "LightSource spot: coneangle must lie in (0, 90]");
            const double start = std::clamp(cone - delta, 0.0, cone);
            const double power = p.number("power", -1);
            if (power > 0) {
                const double c0 = std::cos(start * kPiD / 180), c1 = std::cos(cone * kPiD / 180);
                scale *= power / (2 * kPiD * ((1 - c0) + (c0 - c1) / 2));
            }
            const V3 from = apply_point(m, p.triple("from", {0, 0, 0}));
            const V3 to = apply_point(m, p.triple("to", {0, 0, 1}));
            lights_.push_back({{"type", "spot"}, {"position", to_json(from)},
                               {"look_at", to_json(to)},
                               {"intensity", color_json(i * static_cast<float>(scale))},
                               {"cutoff", cone}, {"falloff_start", start},
                               {"falloff", "smoothstep"}});
        } else if (type == "projection") {
            // pbrt-v4's ProjectionLight: at the CTM's origin along its +z, the image's texel
            // (nearest) times scale is the intensity through a frustum of `fov` on the image's
            // shorter side. pbrt flips the light's y, so that the image's top lies towards +y
            // and its right towards +x, where our projector's right is axis x up = -x: the
            // image is looked up mirrored in u.
            const std::string file = p.string("filename", "");
            if (file.empty()) fail(place, "LightSource projection: needs a \"filename\"");
            const V3 from = apply_point(m, {0, 0, 0});
            const V3 axis = normalized(apply_vector(m, {0, 0, 1}));
            if (p.get("power"))
                warn(place, "LightSource projection: power is not supported; scale is used");
            lights_.push_back({{"type", "projector"},
                               {"position", to_json(from)},
                               {"look_at", to_json(add(from, axis))},
                               {"up", to_json(apply_vector(m, {0, 1, 0}))},
                               {"intensity",
                                {{"type", "image"},
                                 {"file", reader_.relative(file)},
                                 {"filter", "nearest"},
                                 {"wrap", "clamp"},
                                 {"uv_transform", {{"scale", {-1, 1}}, {"offset", {1, 0}}}}}},
                               {"scale", scale},
                               {"fov", p.number("fov", 90)},
                               {"fov_axis", "smaller"}});
        } else if (type == "distant") {
            const Color l = intensity("L");
            const double e = p.number("illuminance", -1);
            if (e > 0) scale *= e;
            const V3 from = p.triple("from", {0, 0, 0}), to = p.triple("to", {0, 0, 1});
            const V3 dir = apply_vector(m, sub(to, from));
            if (!(norm(dir) > 0)) fail(place, "LightSource distant: from and to coincide");
            lights_.push_back({{"type", "directional"}, {"direction", to_json(dir)},
                               {"irradiance", color_json(l * static_cast<float>(scale))}});
        } else if (type == "infinite") {
            if (out_.contains("background")) {
                warn(place, "a second infinite light is ignored (wavetrace has one background)");
            } else if (PbrtParam* f = p.get("filename")) {
                doc_.background_place = place;
                infinite_map(p, *f, m, scale, place);
            } else {
                const Color l = intensity("L");
                const double e = p.number("illuminance", -1);
                if (e > 0) scale *= e / kPiD;
                doc_.background_place = place;
                out_["background"] = {{"type", "constant"},
                                      {"radiance", color_json(l * static_cast<float>(scale))}};
            }
            p.get("portal");
        } else {
            warn(place, "LightSource \"" + type + "\" is not supported; ignored");
            for (PbrtParam& q : p.list) q.used = true;
        }
        doc_.light_places.resize(lights_.size(), place);
        p.finish(pwarn());
    }

    // pbrt-v4's image infinite light: a square image in the equal-area octahedral mapping,
    // looked up in the light's frame (the CTM at the LightSource), which becomes the map's
    // `to_world`. A non-square image is refused when the JSON is loaded, as pbrt-v4 refuses it.
    void infinite_map(PbrtParams& p, const PbrtParam& f, const M4& m, double scale,
                      const std::string& place) {
        if (f.strings.size() != 1) fail(f.place, "\"filename\" should be one string");
        if (p.get("L")) warn(place, "LightSource infinite: L beside an image is ignored");
        std::array<V3, 3> axes;
        bool rigid;
        if (!affine::rotation_axes(m, &axes, &rigid))
            fail(place, "LightSource infinite: its transform is singular");
        if (!rigid)
            warn(place, "LightSource infinite: its transform is not a rotation (times a uniform "
                        "scale); the rotation of its x and y axes is used");
        json bg = {{"type", "environment"},
                   {"mapping", "equal_area"},
                   {"file", reader_.relative(f.strings[0])},
                   {"scale", json::array({scale, scale, scale})}};
        // pbrt-v4 sums the upper hemisphere's texels as if each spanned 2 pi / N sr, half an
        // equal-area texel's 4 pi / N, so its maps reach twice the illuminance asked for: kept,
        // so that its scenes render as pbrt-v4 renders them.
        const double illuminance = p.number("illuminance", -1);
        if (illuminance > 0) bg["illuminance"] = 2 * illuminance;
        const std::array<V3, 3> identity{V3{1, 0, 0}, V3{0, 1, 0}, V3{0, 0, 1}};
        if (axes != identity) bg["to_world"] = affine::axes_matrix(axes);
        out_["background"] = std::move(bg);
    }

    // ---- media ----

    void named_medium(const std::string& place) {
        const std::string name = string_arg("MakeNamedMedium");
        PbrtParams p = params("MakeNamedMedium \"" + name + "\"");
        const std::string type = p.string("type", "");
        if (type != "homogeneous" && type != "uniformgrid" && type != "rgbgrid") {
            warn(place, "medium \"" + type + "\" is not supported; \"" + name + "\" is left out");
            for (PbrtParam& q : p.list) q.used = true;
            skipped_media_.insert(name);
            return;
        }
        if (type == "rgbgrid") {
            rgb_grid_medium(p, place, name);
            return;
        }
        if (p.get("preset")) warn(place, "medium: presets are not supported; sigma_a and sigma_s are used");
        auto rgb = [&](const char* n, Color fallback) {
            PbrtParam* q = p.get(n);
            return q ? spectrum(*q, false, false) : fallback;
        };
        // pbrt-v4's defaults: measured ones for a homogeneous medium, 1 for a grid.
        const bool grid = type == "uniformgrid";
        const Color sa = rgb("sigma_a", grid ? Color(1.0f) : Color(0.0011f, 0.0024f, 0.014f));
        const Color ss = rgb("sigma_s", grid ? Color(1.0f) : Color(2.55f, 3.21f, 3.77f));
        const double scale = p.number("scale", 1);
        const Color st = sa + ss;
        if (!(std::max({st.x, st.y, st.z}) * scale > 0))
            fail(place, "medium \"" + name + "\": its extinction is zero");
        const json density = st.x == st.y && st.y == st.z
                                 ? json(st.x * scale)
                                 : json::array({st.x * scale, st.y * scale, st.z * scale});
        if (p.number("g", 0) != 0) warn(place, "medium: g is not supported; scattering is isotropic");
        if (p.get("Le")) warn(place, "medium: emission (Le) is not supported; ignored");
        auto ratio = [](float s, float t) { return t > 0 ? std::min(s / t, 1.0f) : 0.0f; };
        media_[name] = {{"density", density},
                        {"albedo", json::array({ratio(ss.x, st.x), ratio(ss.y, st.y), ratio(ss.z, st.z)})}};
        if (grid) media_[name]["density_grid"] = density_grid(p, place, name);
        media_names_.insert(name);
        p.finish(pwarn(), {"Lescale", "temperature", "temperaturescale"});
    }

    // A uniformgrid medium's density: nx x ny x nz samples, x fastest, trilinear between them
    // and 0 half a sample beyond the outermost (pbrt-v4's SampledGrid), over the box p0..p1 of
    // the medium's space (the transform at MakeNamedMedium); the medium is empty outside it.
    json density_grid(PbrtParams& p, const std::string& place, const std::string& name) {
        json g = grid_frame(p, place, name);
        const uint64_t voxels = grid_voxels(g);
        const std::vector<double>* d = p.numbers("density", 1);
        if (!d || d->size() != voxels)
            fail(place, "medium \"" + name +
                            "\": density needs nx ny nz = " + std::to_string(voxels) +
                            " values, got " + std::to_string(d ? d->size() : 0));
        if (p.get("temperature") || p.get("Lescale"))
            warn(place, "medium: emission is not supported; ignored");
        g["values"] = *d;
        return g;
    }

    // A grid medium's samples without their values: nx x ny x nz of them over p0..p1, black
    // beyond, placed by the transform at MakeNamedMedium.
    json grid_frame(PbrtParams& p, const std::string& place, const std::string& name) {
        const int nx = p.integer("nx", 1, 1, 1 << 20), ny = p.integer("ny", 1, 1, 1 << 20),
                  nz = p.integer("nz", 1, 1, 1 << 20);
        const std::array<double, 3> p0 = p.triple("p0", {0, 0, 0}), p1 = p.triple("p1", {1, 1, 1});
        const V3 size{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        if (!(size[0] > 0 && size[1] > 0 && size[2] > 0))
            fail(place, "medium \"" + name + "\": p1 must exceed p0 along every axis");
        return {{"resolution", {nx, ny, nz}},
                {"wrap", "black"},
                {"transform", json::array({json{{"scale", to_json(size)}},
                                           json{{"translate", json::array({p0[0], p0[1], p0[2]})}},
                                           matrix_step(state().ctm)[0]})}};
    }
    static uint64_t grid_voxels(const json& g) {
        const json& r = g["resolution"];
        return r[0].get<uint64_t>() * r[1].get<uint64_t>() * r[2].get<uint64_t>();
    }

    // An rgbgrid medium (pbrt-v4's RGBGridMedium): sigma_a and sigma_s as rgb samples of one
    // grid (either may be left out: 1 there), times `scale`. Its extinction becomes a
    // three-channel density grid and its albedo sigma_s / sigma_t a grid texture over the same
    // box. pbrt interpolates sigma_a and sigma_s and divides; here the albedo's samples are
    // interpolated, which is the same where it does not change between neighbouring samples.
    void rgb_grid_medium(PbrtParams& p, const std::string& place, const std::string& name) {
        json grid = grid_frame(p, place, name);
        const uint64_t voxels = grid_voxels(grid);
        auto samples = [&](const char* n) -> const std::vector<double>* {
            PbrtParam* q = p.get(n);
            if (!q) return nullptr;
            if (q->type != "rgb")
                fail(q->place, "\"" + q->name + "\" of an rgbgrid should be rgb values");
            const std::vector<double>* v = p.numbers(n, 3);
            if (v->size() != 3 * voxels)
                fail(q->place, "medium \"" + name + "\": " + n +
                                   " needs 3 nx ny nz = " + std::to_string(3 * voxels) +
                                   " values, got " + std::to_string(v->size()));
            return v;
        };
        const std::vector<double>*sa = samples("sigma_a"), *ss = samples("sigma_s");
        if (!sa && !ss) fail(place, "medium \"" + name + "\": an rgbgrid needs sigma_a or sigma_s");
        const double scale = p.number("scale", 1);
        if (!(scale >= 0)) fail(place, "medium \"" + name + "\": scale must not be negative");
        std::vector<double> extinction(3 * voxels), albedo(3 * voxels);
        double most = 0;
        for (size_t i = 0; i < 3 * voxels; ++i) {
            const double a = sa ? (*sa)[i] : 1, s = ss ? (*ss)[i] : 1;
            if (!(a >= 0 && s >= 0))
                fail(place, "medium \"" + name + "\": sigma_a and sigma_s must not be negative");
            extinction[i] = (a + s) * scale;
            albedo[i] = a + s > 0 ? std::min(s / (a + s), 1.0) : 0.0;
            most = std::max(most, extinction[i]);
        }
        if (!(most > 0)) fail(place, "medium \"" + name + "\": its extinction is zero");
        if (p.number("g", 0) != 0)
            warn(place, "medium: g is not supported; scattering is isotropic");
        if (p.get("Le") || p.get("Lescale"))
            warn(place, "medium: emission (Le) is not supported; ignored");
        json albedo_grid = grid;
        albedo_grid["type"] = "grid";
        albedo_grid["values"] = std::move(albedo);
        grid["values"] = std::move(extinction);
        media_[name] = {
            {"density", 1}, {"albedo", std::move(albedo_grid)}, {"density_grid", std::move(grid)}};
        media_names_.insert(name);
        p.finish(pwarn());
    }

    // ---- shapes ----

    // Counts a shape placed in the scene against the limits of instancing.
    void count_placement(const json& o, const std::string& place) {
        if (++placed_shapes_ > kMaxPlacedShapes)
            fail(place, "more than " + std::to_string(kMaxPlacedShapes) +
                            " shapes placed (instances count their shapes again)");
        if (o.contains("file")) {
            auto mesh = doc_.meshes.find(o["file"].get<std::string>());
            if (mesh != doc_.meshes.end()) placed_triangles_ += mesh->second.indices.size() / 3;
            if (placed_triangles_ > kMaxPlacedTriangles)
                fail(place, "more than 2^28 triangles placed (instances count theirs again)");
        }
    }

    void push(json o, const std::string& place) {
        if (!defining_) count_placement(o, place);
        if (defining_) {
            instances_[defining_name_].objects.push_back(std::move(o));
            return;
        }
        out_["objects"].push_back(std::move(o));
        doc_.object_places.push_back(place);
    }

    std::string default_material() {
        const std::string name = "default diffuse";
        if (!out_["materials"].contains(name))
            out_["materials"][name] = {{"type", "lambertian"}, {"albedo", 0.5}};
        return name;
    }

    // The shape's surface: the state's material, emitting if an area light is active, cut
    // by `alpha`.
    std::string surface(PbrtParams& p, const std::string& place, bool* interface_only) {
        std::string name = state().material.empty() ? default_material() : state().material;
        *interface_only = name == kInterface;
        if (*interface_only) return "";
        if (state().area) {
            const AreaLight& a = *state().area;
            const std::string key = name + "\n" + a.place + "\n" + a.radiance.dump() + (a.two_sided ? "2" : "1");
            auto it = emitters_.find(key);
            if (it == emitters_.end()) {
                json m = {{"type", "diffuse_light"}, {"radiance", a.radiance}};
                if (a.two_sided) m["two_sided"] = true;
                const json& base = out_["materials"][name];
                if (base["type"] == "lambertian") {
                    const json& albedo = base["albedo"];
                    if (albedo != json(0) && albedo != json(0.0) &&
                        albedo != json::array({0.0, 0.0, 0.0}))
                        m["albedo"] = albedo;
                } else {
                    warn(place, "an area light's surface reflects only as a diffuse surface; "
                                "its material \"" + name + "\" is not rendered");
                }
                it = emitters_.emplace(key, add_material(std::move(m), a.place, "")).first;
            }
            name = it->second;
        }
        if (PbrtParam* a = p.get("alpha")) {
            json opacity;
            if (a->type == "texture") {
                auto it = float_textures_.find(a->strings.at(0));
                if (it == float_textures_.end()) fail(a->place, "no float texture named \"" + a->strings[0] + "\"");
                opacity = it->second;
            } else {
                if (a->numbers.size() != 1) fail(a->place, "\"alpha\" should be one float");
                opacity = std::clamp(a->numbers[0], 0.0, 1.0);
            }
            if (opacity.is_number() && opacity.get<double>() == 0) return "";  // not there at all
            if (!(opacity.is_number() && opacity.get<double>() == 1)) {
                json m = out_["materials"][name];
                m["opacity"] = opacity;
                name = add_material(std::move(m), place, name + " with alpha");
            }
        }
        return name;
    }

    void shape(const std::string& place) {
        const std::string type = string_arg("Shape");
        PbrtParams p = params("Shape \"" + type + "\"");
        bool interface_only = false;
        const std::string material = surface(p, place, &interface_only);
        const State& s = state();
        json o;
        if (type == "sphere") {
            const double r = p.number("radius", 1);
            if (!(r > 0)) fail(place, "Shape sphere: radius must be > 0");
            if (p.number("zmin", -r) > -r || p.number("zmax", r) < r || p.number("phimax", 360) < 360)
                warn(place, "Shape sphere: partial spheres are not supported; the whole sphere is rendered");
            if (s.reverse && s.area)
                warn(place, "Shape sphere: ReverseOrientation is not supported; it emits outwards");
            o = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", r}, {"uv_mapping", "z_up"}};
        } else if (type == "plymesh") {
            const std::string file = p.string("filename", "");
            if (file.empty()) fail(place, "Shape plymesh needs a filename");
            o = {{"type", "mesh"}, {"file", reader_.relative(file)}};
            if (s.reverse && s.area)
                warn(place, "Shape plymesh: ReverseOrientation is not supported; it emits on the side its triangles face");
            if (p.get("displacement")) warn(place, "Shape plymesh: displacement is not supported; ignored");
            p.get("edgelength");
        } else if (type == "trianglemesh" || type == "bilinearmesh" || type == "disk" ||
                   type == "cylinder" || type == "loopsubdiv") {
            PbrtMesh mesh = pbrt_shape_mesh(type, p, place);
            // pbrt orients a mesh by N where given, by ReverseOrientation only without; an
            // analytic shape (its normals ours) by ReverseOrientation.
            if (s.reverse && (mesh.normals.empty() || type == "cylinder")) {
                reverse_winding(&mesh);
                for (Normal3& n : mesh.normals) n = -n;
            }
            const std::string key = "@mesh/" + std::to_string(doc_.meshes.size());
            const bool has_normals = !mesh.normals.empty();
            doc_.meshes.emplace(key, std::move(mesh));
            o = {{"type", "mesh"}, {"file", key}};
            // A subdivision surface is smooth: its normals are the mesh's area-weighted ones.
            if (!has_normals && type == "loopsubdiv") o["normals"] = "smooth";
        } else {
            warn(place, "Shape \"" + type + "\" is not supported; skipped");
            return;
        }
        p.finish(pwarn(), {"emissionfilename"});
        if (material.empty() && !interface_only) return;  // alpha 0: no surface
        if (!interface_only) o["material"] = material;
        if (!s.inside.empty() && media_names_.count(s.inside)) o["interior"] = s.inside;
        if (interface_only && !o.contains("interior")) {
            warn(place, "Shape with the interface material and no inside medium: skipped");
            return;
        }
        o["transform"] = matrix_step(s.ctm);
        push(std::move(o), place);
    }

    enum class Active { Start, End };

    struct Instance {
        std::vector<json> objects;
    };

    Reader reader_;
    std::function<void(const std::string&)> warn_;
    json out_ = json::object();
    json lights_ = json::array();
    json media_ = json::object();
    PbrtDocument doc_;
    std::vector<State> states_;
    std::vector<bool> transform_only_;
    std::map<std::string, M4> named_frames_;
    std::map<std::string, std::string> named_materials_;
    std::map<std::string, json> color_textures_, float_textures_;
    std::set<std::string> media_names_, skipped_media_;
    std::map<std::string, std::string> emitters_;
    std::map<std::string, Instance> instances_;
    size_t placed_shapes_ = 0, placed_triangles_ = 0;
    bool defining_ = false;
    size_t defining_depth_ = 0;  // the attribute depth inside the object being defined
    std::string defining_name_, defining_place_;
    Active active_ = Active::Start;
    bool motion_warned_ = false;
    // pbrt's default filter: its Gaussian of radius 1.5 and deviation 0.5.
    json filter_ = {{"type", "gaussian"}, {"radius", 1.5}, {"sigma", 0.5}};
    bool camera_seen_ = false;
    M4 camera_ctm_ = identity();
    std::string camera_place_;
    double fov_ = 90, lens_radius_ = 0, focal_distance_ = 1e6;
    bool orthographic_ = false;
    std::vector<double> screen_window_;  // orthographic: as the file gives it, or empty
};

}  // namespace

PbrtDocument translate_pbrt(const fs::path& path,
                            const std::function<void(const std::string&)>& warn,
                            const fs::path& asset_root) {
    return Translator(path, warn, asset_root).translate();
}

}  // namespace wavetrace
