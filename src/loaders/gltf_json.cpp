#include "loaders/gltf_json.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "loaders/json_reader.h"

namespace wavetrace {
namespace {

uint32_t le32(const std::string& s, size_t at) {
    uint32_t v;
    std::memcpy(&v, s.data() + at, 4);
    return v;  // glTF is little-endian, as every platform we build for
}

// The JSON text of a .gltf, or of a .glb's first chunk: the 12-byte header (magic "glTF",
// version 2, total length) and a chunk of type "JSON" whose length fits in the file (glTF 2.0
// specification, "Binary glTF Layout").
std::string json_text(const std::filesystem::path& path, bool binary) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw std::runtime_error("cannot read the file");
    if (!binary) return bytes;
    if (bytes.size() < 20 || le32(bytes, 0) != 0x46546C67u || le32(bytes, 4) != 2)
        throw std::runtime_error("not a binary glTF 2.0 file (header)");
    const uint32_t length = le32(bytes, 12), type = le32(bytes, 16);
    if (type != 0x4E4F534Au || length > bytes.size() - 20)
        throw std::runtime_error("binary glTF: the first chunk is no JSON chunk within the file");
    return bytes.substr(20, length);
}

}  // namespace

std::vector<float> gltf_emissive_strengths(const std::filesystem::path& path, bool binary) {
    const auto doc = json_reader::parse(json_text(path, binary), "glTF JSON");
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

}  // namespace wavetrace
