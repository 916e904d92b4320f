// Structure-of-arrays queues declared once. A queue's fields are listed in one X-macro
// (FIELDS(F) expands F(type, name, comment) per field); WAVETRACE_SOA expands that list into
// the struct's arrays, its allocation, its per-entry byte count and the copy that compaction
// uses, so adding a field is one edit (the habit of Cycles' state_template.h).
#pragma once

#include <cstddef>
#include <vector>

#define WAVETRACE_SOA_MEMBER_(type, name, comment) std::vector<type> name;
#define WAVETRACE_SOA_RESIZE_(type, name, comment) name.resize(n);
#define WAVETRACE_SOA_BYTES_(type, name, comment) +sizeof(type)
#define WAVETRACE_SOA_COPY_(type, name, comment) name[to] = src.name[from];

#define WAVETRACE_SOA(Name, FIELDS)                                                             \
    struct Name {                                                                               \
        FIELDS(WAVETRACE_SOA_MEMBER_)                                                           \
        size_t capacity = 0;                                                                    \
        void resize(size_t n) {                                                                 \
            FIELDS(WAVETRACE_SOA_RESIZE_)                                                       \
            capacity = n;                                                                       \
        }                                                                                       \
        static constexpr size_t kBytesPerEntry = 0 FIELDS(WAVETRACE_SOA_BYTES_);                \
        void copy_from(size_t to, const Name& src, size_t from) { FIELDS(WAVETRACE_SOA_COPY_) } \
    }
