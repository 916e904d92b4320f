#include "formats/ply_mesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "files/input_file.h"

namespace wavetrace {
namespace {
// Its own namespace: the library is built in unity batches, where other files' anonymous
// namespaces meet this one.
namespace ply {

[[noreturn]] void fail(const std::string& message) {
    throw std::runtime_error(message);
}

enum class Format { Ascii, Little, Big };
enum class Type : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };

std::optional<Type> type_named(std::string_view t) {
    static constexpr std::pair<std::string_view, Type> kNames[] = {
        {"char", Type::I8},    {"int8", Type::I8},     {"uchar", Type::U8},
        {"uint8", Type::U8},   {"short", Type::I16},   {"int16", Type::I16},
        {"ushort", Type::U16}, {"uint16", Type::U16},  {"int", Type::I32},
        {"int32", Type::I32},  {"uint", Type::U32},    {"uint32", Type::U32},
        {"float", Type::F32},  {"float32", Type::F32}, {"double", Type::F64},
        {"float64", Type::F64}};
    for (const auto& [name, type] : kNames)
        if (name == t) return type;
    return std::nullopt;
}

size_t type_size(Type t) {
    switch (t) {
        case Type::I8:
        case Type::U8:
            return 1;
        case Type::I16:
        case Type::U16:
            return 2;
        case Type::I32:
        case Type::U32:
        case Type::F32:
            return 4;
        case Type::F64:
            return 8;
    }
    return 0;
}

bool is_integer(Type t) {
    return t != Type::F32 && t != Type::F64;
}

struct Property {
    std::string name;
    Type type = Type::F32;
    bool list = false;
    Type count_type = Type::U8;  // a list's
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;

    int find(std::string_view property) const {
        for (size_t i = 0; i < properties.size(); ++i)
            if (!properties[i].list && properties[i].name == property) return static_cast<int>(i);
        return -1;
    }
    // The smallest number of bytes one record takes: in binary its scalars and list counts, in
    // ASCII a character and a separator per value.
    uint64_t min_record_bytes(Format format) const {
        uint64_t bytes = 0;
        for (const Property& p : properties)
            bytes += format == Format::Ascii ? 2 : type_size(p.list ? p.count_type : p.type);
        return std::max<uint64_t>(bytes, 1);
    }
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t body = 0;  // offset of the body's first byte
};

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

Header read_header(std::string_view file) {
    Header h;
    size_t at = 0;
    int line_number = 0;
    bool has_format = false;
    for (;;) {
        const size_t end = file.find('\n', at);
        if (end == std::string_view::npos) fail("PLY header has no end_header line");
        std::string_view line = file.substr(at, end - at);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        at = end + 1;
        ++line_number;
        const std::string where = "PLY header, line " + std::to_string(line_number) + ": ";
        for (const char c : line)
            if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
                fail(where + "a control character in the header");
        const std::vector<std::string_view> w = words(line);
        if (line_number == 1) {
            if (w.size() != 1 || w[0] != "ply") fail(where + "expected \"ply\"");
            continue;
        }
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "end_header") break;
        if (w[0] == "format") {
            if (w.size() != 3 || w[2] != "1.0" || has_format)
                fail(where +
                     "expected one \"format ascii|binary_little_endian|"
                     "binary_big_endian 1.0\"");
            if (w[1] == "ascii")
                h.format = Format::Ascii;
            else if (w[1] == "binary_little_endian")
                h.format = Format::Little;
            else if (w[1] == "binary_big_endian")
                h.format = Format::Big;
            else
                fail(where + "unknown format '" + std::string(w[1]) + "'");
            has_format = true;
        } else if (w[0] == "element") {
            uint64_t count = 0;
            if (w.size() != 3 ||
                std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ec != std::errc{})
                fail(where + "expected \"element NAME COUNT\"");
            for (const Element& e : h.elements)
                if (e.name == w[1]) fail(where + "a second element '" + std::string(w[1]) + "'");
            h.elements.push_back({std::string(w[1]), count, {}});
        } else if (w[0] == "property") {
            if (h.elements.empty()) fail(where + "a property before any element");
            Property p;
            if (w.size() == 5 && w[1] == "list") {
                const std::optional<Type> count = type_named(w[2]), item = type_named(w[3]);
                if (!count || !item || !is_integer(*count))
                    fail(where +
                         "expected \"property list COUNT_TYPE ITEM_TYPE NAME\" with an "
                         "integer count type");
                p = {std::string(w[4]), *item, true, *count};
            } else if (w.size() == 3) {
                const std::optional<Type> type = type_named(w[1]);
                if (!type) fail(where + "unknown property type '" + std::string(w[1]) + "'");
                p = {std::string(w[2]), *type, false, Type::U8};
            } else {
                fail(where + "expected \"property TYPE NAME\" or \"property list ...\"");
            }
            for (const Property& q : h.elements.back().properties)
                if (q.name == p.name) fail(where + "a second property '" + p.name + "'");
            h.elements.back().properties.push_back(std::move(p));
        } else {
            fail(where + "unknown keyword '" + std::string(w[0]) + "'");
        }
    }
    if (!has_format) fail("PLY header has no format line");
    h.body = at;
    return h;
}

// Which value of the body is read: property `property` of record `record` of element `element`
// (a list's count if `count`), for messages, which are the only place it is spelled out.
struct Place {
    const Element& element;
    uint64_t record;
    const Property& property;
    bool count = false;

    std::string str() const {
        return element.name + " " + std::to_string(record) + "'s " + property.name +
               (count ? " count" : "");
    }
};

// Reads the body's numbers one after another, in its format.
class Body {
  public:
    // `lines_before`: the header's lines, for an ASCII body's line numbers.
    Body(std::string_view bytes, Format format, size_t lines_before)
        : bytes_(bytes), format_(format), lines_before_(lines_before) {}

    size_t left() const { return bytes_.size() - at_; }
    bool at_end() {
        if (format_ == Format::Ascii) skip_space();
        return at_ == bytes_.size();
    }

    double number(Type type, const Place& where) {
        return format_ == Format::Ascii ? text(type, where) : binary(type, where);
    }

    // An ASCII body's line in the file, for messages.
    std::string place() const {
        if (format_ != Format::Ascii) return "";
        return " (line " +
               std::to_string(lines_before_ + 1 +
                              std::count(bytes_.begin(), bytes_.begin() + at_, '\n')) +
               ")";
    }

  private:
    void skip_space() {
        while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    }

    double text(Type type, const Place& where) {
        skip_space();
        size_t end = at_;
        while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
        const char* first = bytes_.data() + at_;
        const char* last = bytes_.data() + end;
        if (first == last) fail("PLY body: the file ends inside " + where.str());
        const char* digits = first;
        // from_chars takes no '+', which writers print (printf's "%+g") and strtod reads.
        if (*digits == '+' && last - digits > 1 && *(digits + 1) != '-') ++digits;
        double value = 0;
        std::from_chars_result r{};
        if (is_integer(type)) {
            long long i = 0;
            r = std::from_chars(digits, last, i);
            value = static_cast<double>(i);
        } else {
            r = std::from_chars(digits, last, value);
        }
        if (r.ec != std::errc{} || r.ptr != last)
            fail("PLY body: '" + std::string(first, std::min<size_t>(last - first, 32)) +
                 "' is not a number, in " + where.str() + place());
        at_ = end;
        return value;
    }

    double binary(Type type, const Place& where) {
        const size_t n = type_size(type);
        if (left() < n) fail("PLY body: the file ends inside " + where.str());
        unsigned char b[8];
        std::memcpy(b, bytes_.data() + at_, n);
        at_ += n;
        if (format_ == Format::Big) std::reverse(b, b + n);  // to the little-endian we build for
        switch (type) {
            case Type::I8:
                return static_cast<int8_t>(b[0]);
            case Type::U8:
                return b[0];
            case Type::I16:
                return as<int16_t>(b);
            case Type::U16:
                return as<uint16_t>(b);
            case Type::I32:
                return as<int32_t>(b);
            case Type::U32:
                return as<uint32_t>(b);
            case Type::F32:
                return as<float>(b);
            case Type::F64:
                return as<double>(b);
        }
        return 0;
    }

    template <class T>
    static double as(const unsigned char* b) {
        T v;
        std::memcpy(&v, b, sizeof v);
        return static_cast<double>(v);
    }

    std::string_view bytes_;
    Format format_;
    size_t lines_before_;
    size_t at_ = 0;
};

// One attribute as a PLY element's properties make it (see read_ply_mesh).
struct AttributeColumns {
    std::string name;
    std::vector<int> columns;  // 1 or 3 property indices
};

std::vector<AttributeColumns> attributes_of(const Element& e,
                                            const std::string& prefix,
                                            const std::vector<std::string_view>& reserved) {
    std::vector<AttributeColumns> out;
    std::vector<bool> taken(e.properties.size(), false);
    for (const std::string_view r : reserved)
        if (const int i = e.find(r); i >= 0) taken[i] = true;
    for (const auto& rgb : {std::array<const char*, 3>{"r", "g", "b"},
                            std::array<const char*, 3>{"red", "green", "blue"}}) {
        const int r = e.find(rgb[0]), g = e.find(rgb[1]), b = e.find(rgb[2]);
        if (r >= 0 && g >= 0 && b >= 0) {
            out.push_back({prefix + "color", {r, g, b}});
            taken[r] = taken[g] = taken[b] = true;
            break;
        }
    }
    // Runs of PREFIX_c with c stepping through one of these sequences from its start.
    static constexpr std::string_view kSequences[] = {"xyzw", "rgba", "0123", "1234"};
    auto split = [&](size_t i) -> std::pair<std::string_view, char> {
        const Property& p = e.properties[i];
        const size_t u = p.name.rfind('_');
        if (p.list || taken[i] || u == std::string::npos || u == 0 || u + 2 != p.name.size())
            return {{}, 0};
        return {std::string_view(p.name).substr(0, u), p.name.back()};
    };
    for (size_t i = 0; i < e.properties.size();) {
        const auto [stem, c] = split(i);
        int sequence = -1;
        for (int s = 0; s < 4 && !stem.empty(); ++s)
            if (kSequences[s][0] == c) sequence = s;
        if (sequence < 0) {
            ++i;
            continue;
        }
        size_t n = 1;
        while (i + n < e.properties.size() && n < 4) {
            const auto [next_stem, next_c] = split(i + n);
            if (next_stem != stem || next_c != kSequences[sequence][n]) break;
            ++n;
        }
        if (n == 1 || n == 3) {
            AttributeColumns a{prefix + std::string(stem) + (sequence == 1 ? "_color" : ""), {}};
            for (size_t k = 0; k < n; ++k) a.columns.push_back(static_cast<int>(i + k));
            const bool repeated =
                std::any_of(out.begin(), out.end(),
                            [&](const AttributeColumns& o) { return o.name == a.name; });
            if (!repeated) out.push_back(std::move(a));
        }
        i += n;
    }
    return out;
}

// A double as a float, beyond the float range an infinity (a conversion there is undefined),
// which the mesh builder then skips with its triangles.
float to_float(double v) {
    constexpr double kMax = std::numeric_limits<float>::max();
    return v > kMax    ? std::numeric_limits<float>::infinity()
           : v < -kMax ? -std::numeric_limits<float>::infinity()
                       : static_cast<float>(v);
}

Color attribute_value(const AttributeColumns& a, const std::vector<double>& record) {
    if (a.columns.size() == 1) return Color(to_float(record[a.columns[0]]));
    return {to_float(record[a.columns[0]]), to_float(record[a.columns[1]]),
            to_float(record[a.columns[2]])};
}

}  // namespace ply
}  // namespace

MeshFile read_ply_mesh(const std::filesystem::path& path) {
    using namespace ply;
    const std::string bytes = read_input_file(path);
    const Header header = read_header(bytes);
    Body body(std::string_view(bytes).substr(header.body), header.format,
              std::count(bytes.begin(), bytes.begin() + header.body, '\n'));

    const Element* vertex = nullptr;
    uint64_t vertices = 0;
    for (const Element& e : header.elements)
        if (e.name == "vertex") vertex = &e, vertices = e.count;
    if (!vertex) fail("PLY header has no vertex element");
    if (vertices > UINT32_MAX) fail("PLY header announces more than 2^32 - 1 vertices");
    const int xyz[3] = {vertex->find("x"), vertex->find("y"), vertex->find("z")};
    if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
        fail("PLY header: the vertex element has no x, y and z");
    const int nxyz[3] = {vertex->find("nx"), vertex->find("ny"), vertex->find("nz")};
    const bool has_normals = nxyz[0] >= 0 && nxyz[1] >= 0 && nxyz[2] >= 0;
    int uv[2] = {-1, -1};
    std::vector<std::string_view> vertex_reserved = {"x", "y", "z", "nx", "ny", "nz"};
    for (const auto& [u, v] : {std::pair<const char*, const char*>{"u", "v"},
                               {"s", "t"},
                               {"texture_u", "texture_v"},
                               {"texture_s", "texture_t"}}) {
        if (uv[0] < 0 && vertex->find(u) >= 0 && vertex->find(v) >= 0) {
            uv[0] = vertex->find(u), uv[1] = vertex->find(v);
            vertex_reserved.insert(vertex_reserved.end(), {u, v});
        }
    }

    MeshFile out;
    std::vector<AttributeColumns> vertex_columns =
        attributes_of(*vertex, "vertex_", vertex_reserved);
    std::vector<AttributeColumns> face_columns;
    std::vector<MeshAttribute> vertex_attributes, face_attributes;
    std::vector<double> record;
    for (const Element& e : header.elements) {
        // Nothing is allocated for a count the rest of the file cannot hold.
        if (e.count > body.left() / e.min_record_bytes(header.format))
            fail("PLY header announces " + std::to_string(e.count) + " " + e.name +
                 " records; the " + std::to_string(body.left()) + " bytes left hold fewer");
        const bool is_vertex = &e == vertex, is_face = e.name == "face";
        if (!is_vertex && !is_face && e.count > 0)
            out.warnings.push_back("has an element '" + e.name + "' (" + std::to_string(e.count) +
                                   " records) that is skipped: vertex and face are read");
        int indices = -1;
        if (is_face) {
            for (size_t i = 0; i < e.properties.size(); ++i)
                if (e.properties[i].list && (e.properties[i].name == "vertex_indices" ||
                                             e.properties[i].name == "vertex_index"))
                    indices = static_cast<int>(i);
            if (indices < 0) fail("PLY header: the face element has no vertex_indices list");
            if (!is_integer(e.properties[indices].type))
                fail("PLY header: the face element's vertex indices are not integers");
            face_columns = attributes_of(e, "face_", {});
        }
        if (is_vertex) {
            out.positions.reserve(e.count);
            if (has_normals) out.normals.reserve(e.count);
            if (uv[0] >= 0) out.uvs.reserve(e.count);
            for (const AttributeColumns& a : vertex_columns) {
                vertex_attributes.push_back({a.name, false, uint8_t(a.columns.size()), {}});
                vertex_attributes.back().values.reserve(e.count);
            }
        }
        if (is_face)
            for (const AttributeColumns& a : face_columns)
                face_attributes.push_back({a.name, true, uint8_t(a.columns.size()), {}});
        std::vector<uint32_t> polygon;
        record.assign(e.properties.size(), 0.0);
        for (uint64_t r = 0; r < e.count; ++r) {
            for (size_t i = 0; i < e.properties.size(); ++i) {
                const Property& p = e.properties[i];
                const Place where{e, r, p};
                if (!p.list) {
                    record[i] = body.number(p.type, where);
                    continue;
                }
                const double n = body.number(p.count_type, Place{e, r, p, true});
                const size_t item_bytes = header.format == Format::Ascii ? 2 : type_size(p.type);
                if (!(n >= 0))
                    fail("PLY body: " + where.str() + " has " + std::to_string(int64_t(n)) +
                         " items" + body.place());
                if (n > double(body.left() / item_bytes))
                    fail("PLY body: the file ends before the " + std::to_string(int64_t(n)) +
                         " items of " + where.str() + body.place());
                if (int(i) == indices) polygon.clear();
                for (uint64_t k = 0; k < uint64_t(n); ++k) {
                    const double x = body.number(p.type, where);
                    if (int(i) != indices) continue;
                    if (!(x >= 0 && x < double(vertices)))
                        fail("PLY body: " + where.str() + " names vertex " +
                             std::to_string(int64_t(x)) + " of " + std::to_string(vertices) +
                             body.place());
                    polygon.push_back(static_cast<uint32_t>(x));
                }
            }
            if (is_vertex) {
                out.positions.push_back(
                    {to_float(record[xyz[0]]), to_float(record[xyz[1]]), to_float(record[xyz[2]])});
                if (has_normals)
                    out.normals.push_back({to_float(record[nxyz[0]]), to_float(record[nxyz[1]]),
                                           to_float(record[nxyz[2]])});
                if (uv[0] >= 0)
                    out.uvs.push_back({to_float(record[uv[0]]), to_float(record[uv[1]])});
                for (size_t a = 0; a < vertex_columns.size(); ++a)
                    vertex_attributes[a].values.push_back(
                        attribute_value(vertex_columns[a], record));
            }
            // A polygon becomes a fan of triangles about its first vertex; fewer than three
            // vertices (points, lines) make none.
            if (is_face)
                for (size_t k = 1; k + 1 < polygon.size(); ++k) {
                    out.indices.insert(out.indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
                    for (size_t a = 0; a < face_columns.size(); ++a)
                        face_attributes[a].values.push_back(
                            attribute_value(face_columns[a], record));
                }
        }
    }
    if (!body.at_end())
        fail("PLY body: " + std::to_string(body.left()) + " bytes after the last element");
    if (out.indices.empty()) fail("the file holds no triangles");
    out.materials.push_back(FileMaterial{"(none)"});
    out.parts.push_back({0, out.indices.size() / 3, 0});
    out.attributes = std::move(vertex_attributes);
    for (MeshAttribute& a : face_attributes) out.attributes.push_back(std::move(a));
    return out;
}

}  // namespace wavetrace
