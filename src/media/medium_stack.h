// The media a path is inside, innermost last. Crossing into a shape pushes its interior
// medium (kNone for a shape without one: a glass ball in fog is fog-free inside); crossing out
// pops (under the scene's Nested rule; see MediumBoundaries for the other). Media nest at most kMaxNesting deep; deeper nesting is clamped (the innermost wins).
#pragma once

#include <cstdint>

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

}  // namespace wavetrace
