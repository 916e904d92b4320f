// A MediumStack in 8 bytes for the queues: four 15-bit medium ids and a 3-bit depth (the
// stack is 20 bytes unpacked). Media ids stay below kMaxMedia (scene.h), so 15 bits hold any
// id and the all-ones pattern stands for kNone.
#pragma once

#include <cstdint>

#include "media/medium_stack.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

static_assert(kMaxMedia < 0x7fff, "medium ids must fit 15 bits, with 0x7fff for kNone");
static_assert(MediumStack::kMaxNesting == 4, "the packing holds four entries");

struct PackedMedia {
    uint64_t bits = 0;  // the empty stack

    static PackedMedia pack(const MediumStack& s) {
        uint64_t b = static_cast<uint64_t>(s.size);
        for (int k = 0; k < MediumStack::kMaxNesting; ++k) {
            const uint64_t id = s.entries[k] == kNone ? 0x7fff : s.entries[k];
            b |= id << (3 + 15 * k);
        }
        return {b};
    }
    // unpack().current(), without unpacking the rest.
    MediumId current() const {
        const uint32_t size = static_cast<uint32_t>(bits & 7);
        if (size == 0) return kNone;
        const uint32_t id = static_cast<uint32_t>(bits >> (3 + 15 * (size - 1))) & 0x7fff;
        return id == 0x7fff ? kNone : id;
    }
    MediumStack unpack() const {
        MediumStack s;
        s.size = static_cast<int8_t>(bits & 7);
        for (int k = 0; k < MediumStack::kMaxNesting; ++k) {
            const uint32_t id = static_cast<uint32_t>(bits >> (3 + 15 * k)) & 0x7fff;
            s.entries[k] = id == 0x7fff ? kNone : id;
        }
        return s;
    }
};

}  // namespace wavetrace
