#pragma once

#include <cstdint>

namespace wavetrace {

// Indices into the scene's arrays. kNone marks an absent reference (no medium, no texture).
using TextureId = uint32_t;
using MaterialId = uint32_t;
using MediumId = uint32_t;
using ImageId = uint32_t;
using VolumeGridId = uint32_t;
inline constexpr uint32_t kNone = 0xffffffffu;

// Primitive kinds that the BVH holds side by side.
enum class PrimKind : uint32_t { Triangle = 0, Quad = 1, Sphere = 2 };

// A primitive reference: its kind in the top two bits, its index in that kind's array below.
struct PrimRef {
    uint32_t bits = kNone;

    static constexpr PrimRef make(PrimKind kind, uint32_t index) {
        return {(static_cast<uint32_t>(kind) << 30) | index};
    }
    constexpr PrimKind kind() const { return static_cast<PrimKind>(bits >> 30); }
    constexpr uint32_t index() const { return bits & 0x3fffffffu; }
    constexpr bool valid() const { return bits != kNone; }
    constexpr bool operator==(const PrimRef&) const = default;
};
inline constexpr uint32_t kMaxPrimsPerKind = 0x3fffffffu;

}  // namespace wavetrace
