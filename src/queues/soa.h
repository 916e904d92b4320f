// Structure-of-arrays queues declared once. A queue's fields are listed in one X-macro
// (FIELDS(F) expands F(type, name, comment) per field); WAVETRACE_SOA expands that list into
// the struct's arrays, its allocation, its per-entry byte count, an Entry struct with per-entry
// load(i) / store(i, entry), and the moves that compaction and sorting use, so adding a field
// is one edit (the habit of Cycles' state_template.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#define WAVETRACE_SOA_MEMBER_(type, name, comment) std::vector<type> name;
#define WAVETRACE_SOA_ENTRY_(type, name, comment) type name;
#define WAVETRACE_SOA_RESIZE_(type, name, comment) name.resize(n);
#define WAVETRACE_SOA_BYTES_(type, name, comment) +sizeof(type)
#define WAVETRACE_SOA_LOAD_(type, name, comment) e.name = name[i];
#define WAVETRACE_SOA_STORE_(type, name, comment) name[i] = e.name;
#define WAVETRACE_SOA_GATHER_(type, name, comment)                         \
    {                                                                      \
        type* field = name.data();                                         \
        for (size_t j = 0; j < count; ++j) field[to + j] = field[from[j]]; \
    }
#define WAVETRACE_SOA_COPY_(type, name, comment)                      \
    {                                                                 \
        const type* in = src.name.data();                             \
        type* out = name.data();                                      \
        for (size_t j = 0; j < count; ++j) out[to + j] = in[from[j]]; \
    }
#define WAVETRACE_SOA_SWAP_(type, name, comment) std::swap(name[a], name[b]);

#define WAVETRACE_SOA(Name, FIELDS)                                                 \
    struct Name {                                                                   \
        struct Entry {                                                              \
            FIELDS(WAVETRACE_SOA_ENTRY_)                                            \
        };                                                                          \
        FIELDS(WAVETRACE_SOA_MEMBER_)                                               \
        size_t capacity = 0;                                                        \
        void resize(size_t n) {                                                     \
            FIELDS(WAVETRACE_SOA_RESIZE_)                                           \
            capacity = n;                                                           \
        }                                                                           \
        static constexpr size_t kBytesPerEntry = 0 FIELDS(WAVETRACE_SOA_BYTES_);    \
        Entry load(size_t i) const {                                                \
            Entry e;                                                                \
            FIELDS(WAVETRACE_SOA_LOAD_)                                             \
            return e;                                                               \
        }                                                                           \
        void store(size_t i, const Entry& e) { FIELDS(WAVETRACE_SOA_STORE_) }       \
        /* entries from[0..count) to to, to + 1, ...: one field at a time, in       \
           place, from[j] >= to + j increasing */                                   \
        void gather(size_t to, const uint32_t* from, size_t count) {                \
            FIELDS(WAVETRACE_SOA_GATHER_)                                           \
        }                                                                           \
        /* entries from[0..count) of another queue to to, to + 1, ... */            \
        void copy(size_t to, const Name& src, const uint32_t* from, size_t count) { \
            FIELDS(WAVETRACE_SOA_COPY_)                                             \
        }                                                                           \
        void swap(size_t a, size_t b) { FIELDS(WAVETRACE_SOA_SWAP_) }               \
    }

// A vector field as three rows (name_x, name_y, name_z), where a kernel copies or loads a block
// of entries' vectors as whole rows; WAVETRACE_XYZ_AT reads entry i's as a Vec3.
#define WAVETRACE_XYZ_FIELD(F, name, comment) \
    F(float, name##_x, comment) F(float, name##_y, "") F(float, name##_z, "")
#define WAVETRACE_XYZ_AT(queue, name, i) \
    (Vec3{(queue).name##_x[i], (queue).name##_y[i], (queue).name##_z[i]})
