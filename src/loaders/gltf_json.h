// What Assimp 5.2 does not read from a glTF 2.0 file, read from its JSON beside Assimp.
#pragma once

#include <filesystem>
#include <vector>

namespace wavetrace {

// Per material, in the file's order (Assimp's too): KHR_materials_emissive_strength's
// emissiveStrength, 1 where the material does not give one. `binary`: a .glb, whose JSON is
// its first chunk. Throws std::runtime_error (without the path) for a malformed container or
// JSON, or a strength that is negative or not finite.
std::vector<float> gltf_emissive_strengths(const std::filesystem::path& path, bool binary);

}  // namespace wavetrace
