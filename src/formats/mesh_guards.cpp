#include "formats/mesh_guards.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace wavetrace {
namespace {

size_t ply_type_size(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" ||
        t == "float32")
        return 4;
    if (t == "double" || t == "float64") return 8;
    throw std::runtime_error("PLY header: unknown property type '" + t + "'");
}

// How Assimp reads a number of a PLY type in an ASCII body: strtoul10, strtol10 or
// fast_atoreal_move.
enum class PlyNumber { Unsigned, Signed, Real };
PlyNumber ply_number(const std::string& t) {
    if (t == "float" || t == "float32" || t == "double" || t == "float64") return PlyNumber::Real;
    if (t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32")
        return PlyNumber::Signed;
    return PlyNumber::Unsigned;
}

// One property of a PLY element as the header declares it: a scalar of `size` bytes, or a
// list whose count takes `count_size` bytes and whose items take `size` each; `type` and
// `count_type` say how Assimp reads them in ASCII.
struct PlyProperty {
    bool list = false;
    size_t count_size = 0;
    size_t size = 0;
    PlyNumber count_type = PlyNumber::Unsigned;
    PlyNumber type = PlyNumber::Real;
};
struct PlyElement {
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

// Whether Assimp 5.2 reads all of `token` as a number of `type`, so that the next property
// starts at the next token: its readers stop at the first character they do not take and the
// next property is read from there, which a walk by tokens would not follow. Assimp takes
// more forms than these (a trailing '.', a ',' for the decimal point), but every number a PLY
// writer prints is one of them: digits for unsigned types, a sign and digits for signed ones,
// and for reals a sign, digits with a fraction and an exponent, or nan / inf / infinity. A
// real's integer part must not overflow 64 bits: fast_atoreal_move then returns 0 where it is,
// so the next property reads the same digits again, and a list count read from them wraps to
// 32 bits ("99999999999999999999999" before a list: std::bad_alloc; a 55-digit one took 13 GB
// in 15 s: found by tests/fuzz/fuzz_mesh at seed 50).
bool assimp_reads_whole(std::string_view t, PlyNumber type) {
    size_t k = 0;
    bool wrapped = false;  // the last run of digits overflows 64 bits, as strtoul10_64 reads it
    auto sign = [&] {
        if (k < t.size() && (t[k] == '+' || t[k] == '-')) ++k;
    };
    auto digits = [&] {
        const size_t start = k;
        uint64_t value = 0;  // an overflow is a value that falls
        wrapped = false;
        for (; k < t.size() && t[k] >= '0' && t[k] <= '9'; ++k) {
            const uint64_t next = value * 10 + uint64_t(t[k] - '0');
            wrapped = wrapped || next < value;
            value = next;
        }
        return k - start;
    };
    if (type == PlyNumber::Unsigned) return digits() > 0 && k == t.size();
    sign();
    if (type == PlyNumber::Signed) return digits() > 0 && k == t.size();
    std::string word(t.substr(k));
    for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (word == "nan" || word == "inf" || word == "infinity") return true;
    size_t mantissa = digits();
    if (wrapped) return false;
    if (k < t.size() && t[k] == '.') {
        ++k;
        const size_t fraction = digits();
        if (fraction == 0) return false;
        mantissa += fraction;
    }
    if (mantissa == 0) return false;
    if (k < t.size() && (t[k] == 'e' || t[k] == 'E')) {
        ++k;
        sign();
        if (digits() == 0) return false;
    }
    return k == t.size();
}

// Assimp 5.2's PLY reader allocates what a list's count asks for before reading its items, so
// a face announcing 2^30 indices made it allocate 8 GB in a file of 150 bytes (binary), and one
// announcing 10^54 in ASCII ran out of memory (found by tests/fuzz/fuzz_mesh at seed 34). The
// body is walked here as the reader will walk it, and a list refused where the rest of the file
// cannot hold its items (an item takes its size in a binary file, and a digit and a separator
// in an ASCII one). An ASCII body's first line is line `first_line` of the file; `after_crlf`:
// the end_header line ended with "\r\n" (where Assimp's stream then stands matters, below).
void check_ply_lists(std::string_view body,
                     bool ascii,
                     bool big_endian,
                     const std::vector<PlyElement>& elements,
                     bool after_crlf,
                     size_t first_line) {
    auto refuse = [](uint64_t count, uint64_t left) {
        const std::string items = count == UINT64_MAX
                                      ? "a list of a negative or endless count"
                                      : "a list of " + std::to_string(count) + " items";
        throw std::runtime_error("PLY body: " + items + " where " + std::to_string(left) +
                                 " bytes are left (damaged?)");
    };
    size_t pos = 0;
    if (ascii) {
        // Assimp reads an ASCII element from one line (IOStreamBuffer::getNextLine, taken
        // here as it is): at a line end it first skips to past the next '\n', so one blank
        // line is passed over and a second is read as an element; and past the last line it
        // reads what its line buffer held before (the previous line again: a face count of
        // 2222222222222222 there took 21 GB in 60 s, fuzz_mesh at seed 40), so the body must
        // hold a line for every element. Within a line it skips spaces and tabs and reads each
        // property where the previous one stopped, so every number it reads must be one it
        // reads whole (assimp_reads_whole). check_ply has refused control characters other
        // than tabs and line ends.
        uint64_t announced = 0;
        for (const PlyElement& e : elements) announced += e.count;
        uint64_t read = 0;
        auto is_end = [&](size_t at) { return body[at] == '\n' || body[at] == '\r'; };
        // After "end_header\r\n" Assimp stands on the '\n', and its first skip passes it.
        bool skips = !after_crlf;
        auto next_line = [&](size_t& begin, size_t& end) {
            if (skips && pos < body.size() && is_end(pos)) {
                while (pos < body.size() && body[pos] != '\n') ++pos;
                ++pos;
            }
            skips = true;
            begin = pos;
            while (pos < body.size() && !is_end(pos)) ++pos;
            end = pos;
            if (begin >= body.size())
                throw std::runtime_error(
                    "PLY body: the file ends " + std::to_string(announced - read) +
                    " element lines short of the " + std::to_string(announced) +
                    " its header announces (truncated?)");
            ++pos;
            return end >= body.size();  // the file's last line, without its line end
        };
        // The leading integer of a count, with its sign: Assimp reads "-2147483647" into an
        // unsigned count (8.6 GB allocated), so a negative count is as good as infinite here.
        auto parse_count = [](std::string_view token) {
            size_t k = 0;
            bool negative = false;
            if (!token.empty() && (token[0] == '+' || token[0] == '-'))
                negative = token[k++] == '-';
            uint64_t count = 0;
            for (; k < token.size() && token[k] >= '0' && token[k] <= '9'; ++k)
                count = count > (UINT64_MAX - 9) / 10 ? UINT64_MAX
                                                      : count * 10 + uint64_t(token[k] - '0');
            return negative && count != 0 ? UINT64_MAX : count;
        };
        for (const PlyElement& e : elements)
            for (uint64_t i = 0; i < e.count; ++i) {
                size_t at = 0, end = 0;
                const bool cut = next_line(at, end);
                ++read;
                const size_t line_begin = at;
                auto where = [&] {
                    return "PLY body, line " +
                           std::to_string(first_line + std::count(body.begin(),
                                                                  body.begin() + line_begin,
                                                                  '\n')) +
                           ": ";
                };
                auto token = [&](PlyNumber type) {
                    while (at < end && (body[at] == ' ' || body[at] == '\t')) ++at;
                    const size_t start = at;
                    while (at < end && body[at] != ' ' && body[at] != '\t') ++at;
                    const std::string_view t(body.data() + start, at - start);
                    // What a line lacks Assimp reads as defaults, but in the file's last line
                    // without its line end it would read on into its buffer's older contents.
                    if (t.empty() && cut)
                        throw std::runtime_error(where() +
                                                 "the file's last line is cut short (truncated?)");
                    if (!t.empty() && !assimp_reads_whole(t, type))
                        throw std::runtime_error(where() + "'" + std::string(t.substr(0, 40)) +
                                                 "' is not a number the reader takes whole (" +
                                                 (type == PlyNumber::Real ? "a real"
                                                  : type == PlyNumber::Signed
                                                      ? "a signed integer"
                                                      : "an unsigned integer") +
                                                 ")");
                    return t;
                };
                for (const PlyProperty& p : e.properties) {
                    if (!p.list) {
                        if (token(p.type).empty()) break;  // the rest of the line: defaults
                        continue;
                    }
                    const std::string_view count_token = token(p.count_type);
                    if (count_token.empty()) break;
                    const uint64_t count = parse_count(count_token);
                    const uint64_t left = body.size() - at;
                    if (count > left / 2) refuse(count, left);
                    for (uint64_t k = 0; k < count; ++k)
                        if (token(p.type).empty()) break;
                }
            }
        return;
    }
    const bool swap = big_endian != (std::endian::native == std::endian::big);
    for (const PlyElement& e : elements) {
        bool lists = false;
        size_t row = 0;
        for (const PlyProperty& p : e.properties) {
            lists = lists || p.list;
            row += p.size;
        }
        if (!lists) {  // fixed-size rows: skip them all at once
            pos += static_cast<size_t>(std::min<uint64_t>(e.count * row, body.size() - pos));
            continue;
        }
        for (uint64_t i = 0; i < e.count; ++i)
            for (const PlyProperty& p : e.properties) {
                if (!p.list) {
                    pos += p.size;
                    continue;
                }
                if (pos + p.count_size > body.size()) return;  // truncated: checked above
                uint64_t count = 0;
                for (size_t b = 0; b < p.count_size; ++b) {
                    const size_t byte = swap ? b : p.count_size - 1 - b;  // most significant first
                    count = count << 8 | static_cast<unsigned char>(body[pos + byte]);
                }
                pos += p.count_size;
                const uint64_t left = body.size() - std::min(pos, body.size());
                if (count > left / p.size) refuse(count, left);  // no overflow: size >= 1
                pos += static_cast<size_t>(count * p.size);
            }
    }
}

}  // namespace

// Assimp 5.2's PLY reader hangs on a file that holds only the header's first lines, and reads
// past the end of a binary body that was cut short (a segfault). So the header is read here
// first: it must end with end_header, and a binary body must be at least as long as the
// element counts in the header say (faces of at least 3 indices each).
void check_ply(const std::filesystem::path& path) {
    // Assimp's PLY reader ends a header line at '\n', '\r', '\0' or '\f' (IsLineEnd in its
    // ParsingUtils.h), and hangs or crashes where such ends follow one another oddly ("1.0\0\0"
    // or "1.0\r\r" before end_header hang it, a NUL after a property line crashes it; an
    // element line hidden behind a NUL made it allocate 26 GB: all found by tests/fuzz/fuzz_mesh).
    // A PLY header is text, so it is refused here with any control character but a tab, and any
    // line end but "\n" and "\r\n"; the lines are cut where Assimp cuts them, so that the
    // end_header it would find is the one found here.
    // The whole file, read once: the header is looked for in its first 64 KiB, and the body
    // is walked for its lists (check_ply_lists).
    std::ifstream in(path, std::ios::binary);
    const std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t header_window = std::min<size_t>(raw.size(), 65536);
    static const std::string kLineEnds("\n\r\0\f", 4);
    std::string header_lines;
    size_t header_bytes = 0;  // up to the end of the end_header line, its \r\n included
    auto refuse_byte = [&](size_t at, bool body = false) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02x", static_cast<unsigned char>(raw[at]));
        throw std::runtime_error(std::string(body ? "PLY body" : "PLY header") +
                                 ": control character " + hex + " at byte " + std::to_string(at) +
                                 (body ? " (an ASCII body is text)" : " (a header is text)"));
    };
    // Text, header or ASCII body: no control character but a tab, lines ended by "\n" or "\r\n".
    auto is_text = [&](size_t k) {
        const char c = raw[k];
        return static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n' ||
               (c == '\r' && k + 1 < raw.size() && raw[k + 1] == '\n');
    };
    for (size_t pos = 0; pos < header_window;) {
        const size_t end = raw.find_first_of(kLineEnds, pos);
        if (end == std::string::npos || end >= header_window) break;  // no end: truncated
        for (size_t k = pos; k <= end; ++k)
            if (!is_text(k)) refuse_byte(k);
        const std::string_view line(raw.data() + pos, end - pos);
        pos = end + (raw[end] == '\r' ? 2 : 1);
        if (line == "end_header") {
            header_bytes = pos;
            break;
        }
        header_lines.append(line);
        header_lines += '\n';
    }
    if (header_bytes == 0)
        throw std::runtime_error(
            "PLY header has no end_header line in its first 64 KiB (truncated?)");
    std::istringstream lines(header_lines);
    std::string line;
    const uint64_t file_size = raw.size();
    bool binary = false, big_endian = false;
    uint64_t min_body = 0, count = 0;
    std::vector<PlyElement> elements;
    // Assimp 5.2's PLY reader sizes its vertex array from the first `vertex` element and its
    // face array from the first `face` or `tristrips` one, then fills them from every such
    // element: a second, longer one writes past the end of the heap block (found by
    // tests/fuzz/fuzz_mesh at seed 29; the heap damage ASan kept reporting far from its cause).
    // An element is known by its name, so a name declared twice is refused, and so are faces
    // given both as `face` and as `tristrips`.
    std::map<std::string, int> element_lines;  // name -> header line
    int line_number = 0;                       // of the line read last; "ply" is line 1
    bool in_properties = false;                // the lines since the last element line
    while (std::getline(lines, line)) {
        ++line_number;
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (word == "format") {
            std::string format;
            words >> format;
            binary = format != "ascii";
            big_endian = format == "binary_big_endian";
        } else if (word == "element") {
            std::string name;
            words >> name >> count;
            // Assimp takes the leading digits of a first word that starts with one for the
            // count, wrapped to 32 bits ("element 111111111111111111111111114 4" asked it for
            // 1.9 billion elements: found by tests/fuzz/fuzz_mesh), so such a name counts too.
            const size_t digits = std::min(name.find_first_not_of("0123456789"), name.size());
            if (digits > 0)
                count = digits > 12
                            ? UINT64_MAX
                            : std::max<uint64_t>(count, std::stoull(name.substr(0, digits)));
            if (!words || count > (uint64_t(1) << 31))
                throw std::runtime_error("PLY header: bad element line '" + line + "'");
            // Assimp allocates ~24 bytes per element before reading any, properties or not;
            // every real element takes at least a byte of the file.
            if (count > file_size)
                throw std::runtime_error("PLY header announces " + std::to_string(count) +
                                         " elements, more than a file of " +
                                         std::to_string(file_size) + " bytes can hold");
            const std::string semantic = name == "tristrips" ? "face" : name;
            if (const auto [it, fresh] = element_lines.try_emplace(semantic, line_number); !fresh)
                throw std::runtime_error("PLY header: element '" + name + "' at line " +
                                         std::to_string(line_number) +
                                         (semantic == name && name != "face"
                                              ? " is declared again (first at line "
                                              : " gives faces again (faces first at line ") +
                                         std::to_string(it->second) + ")");
            elements.push_back({count, {}});
            in_properties = true;
        } else if (word == "property") {
            std::string type, count_type, index_type, name;
            words >> type;
            PlyProperty property;
            // Assimp ends an element's properties at the first line it cannot parse and skips
            // the property lines after it, so the body it reads would not be the one walked
            // below ("property float" without a name, then "property float z": found by
            // tests/fuzz/fuzz_mesh at seed 40, where the walks missed a count of 2.2e15).
            // A property needs a type and a name.
            if (type == "list") {
                words >> count_type >> index_type >> name;
                if (!words)
                    throw std::runtime_error("PLY header: bad property line '" + line +
                                             "' at line " + std::to_string(line_number));
                bool indices = name == "vertex_indices" || name == "vertex_index";
                min_body += count * (ply_type_size(count_type) +
                                     (indices ? 3 * ply_type_size(index_type) : 0));
                property = {true, ply_type_size(count_type), ply_type_size(index_type),
                            ply_number(count_type), ply_number(index_type)};
            } else {
                if (!(words >> name))
                    throw std::runtime_error("PLY header: bad property line '" + line +
                                             "' at line " + std::to_string(line_number));
                min_body += count * ply_type_size(type);
                property.size = ply_type_size(type);
                property.type = ply_number(type);
            }
            // Assimp reads an element's properties from the lines right after it, and skips a
            // property line anywhere else (after a comment line too: Assimp 5.2 then fails
            // with "Vertices should be declared before faces").
            if (!in_properties)
                throw std::runtime_error("PLY header: property line '" + line + "' at line " +
                                         std::to_string(line_number) +
                                         " does not follow an element line or its properties");
            elements.back().properties.push_back(property);
        } else {
            in_properties = false;
        }
    }
    const std::string_view body = std::string_view(raw).substr(header_bytes);
    if (binary && body.size() < min_body)
        throw std::runtime_error("binary PLY body is " + std::to_string(body.size()) +
                                 " bytes, but its header announces at least " +
                                 std::to_string(min_body) + " (truncated?)");
    if (!binary)
        for (size_t k = header_bytes; k < raw.size(); ++k)
            if (!is_text(k)) refuse_byte(k, true);
    const bool after_crlf = raw[header_bytes - 2] == '\r';
    check_ply_lists(body, !binary, big_endian, elements, after_crlf,
                    static_cast<size_t>(line_number) + 2);
}

// Assimp 5.2's OFF reader allocates what the header's vertex and face counts ask for before
// reading any of them, so a short file claiming 10^10 vertices allocates tens of GiB (found
// by tests/fuzz/fuzz_mesh). Every vertex and face takes at least two bytes of text, which
// bounds the counts a file of its size can hold.
void check_off(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string word;
    std::vector<std::pair<double, std::string>> counts;  // value, as written
    bool magic = false;
    while (counts.size() < 2 && in >> word) {
        if (word[0] == '#') {
            std::getline(in, word);
            continue;
        }
        if (!magic) {
            magic = true;
            if (word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0) continue;
        }
        char* end = nullptr;
        double v = std::strtod(word.c_str(), &end);
        if (*end != '\0' || !(v >= 0))
            throw std::runtime_error("OFF header: bad count '" + word + "'");
        counts.push_back({v, word});
    }
    std::error_code ec;
    const double size = double(std::filesystem::file_size(path, ec));
    for (const auto& [count, text] : counts)
        if (count > size / 2)
            throw std::runtime_error("OFF header announces " + text +
                                     " elements, more than a file of " +
                                     std::to_string(uint64_t(size)) + " bytes can hold");
}

}  // namespace wavetrace

namespace wavetrace {

// Assimp 5.2's OBJ reader makes a mesh and a material for every name `usemtl` gives, and its
// post-processing then takes time that grows faster than their count (100,000 names in 5 MB:
// over 40 s and 3.7 GB); its triangulation clips ears in time quadratic in a polygon's
// vertices (five polygons of 32,767 vertices in 1.7 MB: over a minute). Both are bounded
// here: at most kMaxObjMaterials names, and at most kMaxObjPolygonWork for the sum of n^2
// over the polygons of n >= 5 vertices (quads and triangles cost nothing to split).
// Assimp 5.2's MTL reader applies a statement before the first `newmtl` to a material that
// does not exist: a texture there (`map_Kd t.png`) writes through a null pointer (a segfault
// on a two-line file, found by fuzz_mesh). Every statement must follow a `newmtl`.
void check_mtl(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    size_t line_number = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        std::istringstream words(line);
        std::string key;
        if (!(words >> key) || key[0] == '#') continue;
        if (key == "newmtl") return;
        throw std::runtime_error("material library " + path.filename().string() + " line " +
                                 std::to_string(line_number) + ": '" + key +
                                 "' before the first newmtl");
    }
}

void check_obj(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    // The material libraries Assimp will read: those `mtllib` names, else the OBJ's own name
    // with .mtl.
    const std::filesystem::path folder = path.parent_path();
    std::vector<std::filesystem::path> libraries = {path.parent_path() /
                                                    (path.stem().string() + ".mtl")};
    std::set<std::string> names;
    uint64_t work = 0;
    size_t line_number = 0;
    std::string line, logical;
    while (std::getline(in, line)) {
        ++line_number;
        // A backslash at the end of a line continues it, for Assimp as for the format.
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty() && line.back() == '\\') {
            logical += line.substr(0, line.size() - 1) + " ";
            continue;
        }
        logical += line;
        std::istringstream words(logical);
        logical.clear();
        std::string key;
        if (!(words >> key)) continue;
        if (key == "mtllib") {
            std::string name;
            std::getline(words >> std::ws, name);
            libraries.push_back(folder / name);
        } else if (key == "usemtl") {
            std::string name;
            std::getline(words >> std::ws, name);
            names.insert(name);
            if (names.size() > kMaxObjMaterials)
                throw std::runtime_error("line " + std::to_string(line_number) +
                                         ": more than " + std::to_string(kMaxObjMaterials) +
                                         " material names (usemtl)");
        } else if (key == "f") {
            uint64_t n = 0;
            for (std::string v; words >> v;) ++n;
            if (n >= 5) work += n * n;
            if (work > kMaxObjPolygonWork)
                throw std::runtime_error(
                    "line " + std::to_string(line_number) + ": polygons too large to triangulate " +
                    "(the sum of their vertex counts squared passes " +
                    std::to_string(kMaxObjPolygonWork) + "); split them into smaller ones");
        }
    }
    for (const std::filesystem::path& library : libraries) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(library, ec)) check_mtl(library);
    }
}

}  // namespace wavetrace
