// The media a path is inside, innermost last. Crossing into a shape pushes its interior
// medium (kNone for a shape without one: a glass ball in fog is fog-free inside); crossing out
// pops (under the scene's Nested rule; see MediumBoundaries for the other). Media nest at most kMaxNesting deep; deeper nesting is clamped (the innermost wins).
#pragma once

#include <cstdint>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"
#include "wavetrace/scene/medium.h"

namespace wavetrace {

struct MediumStack {
    static constexpr int kMaxNesting = 4;
    MediumId entries[kMaxNesting] = {kNone, kNone, kNone, kNone};
    int8_t size = 0;

    MediumId current() const { return size > 0 ? entries[size - 1] : kNone; }
    void push(MediumId m) {
        if (size < kMaxNesting)
            entries[size++] = m;
        else
            entries[kMaxNesting - 1] = m;
    }
    void pop() {
        if (size > 0) --size;
    }
    // Crossing a surface with interior `m`: entering from its front pushes, leaving pops; with
    // Interface boundaries entering makes m the only medium and leaving empties the stack.
    void cross(MediumId m, bool entering, MediumBoundaries rule) {
        if (rule == MediumBoundaries::Interface) size = 0;
        if (entering)
            push(m);
        else
            pop();
    }
};

// The media a light sample's shadow ray from a vertex (direction wi) starts in, the path having
// arrived along wo in `media`: those across the vertex's surface (geometric normal ng, inside
// medium `interior`) where wi leaves through its other side (a rough dielectric's transmission;
// crossing as continue_path crosses), else the path's. In a medium (ng zero) the path's.
inline MediumStack shadow_media(
    MediumBoundaries rule, MediumStack media, MediumId interior, Normal3 ng, Vec3 wo, Vec3 wi) {
    const float side_o = dot(wo, ng), side_i = dot(wi, ng);
    if ((side_o < 0.0f && side_i > 0.0f) || (side_o > 0.0f && side_i < 0.0f))
        media.cross(interior, side_i < 0.0f, rule);
    return media;
}

}  // namespace wavetrace
