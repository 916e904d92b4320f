#include "files/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>

namespace wavetrace {
namespace {

std::string size_text(uintmax_t bytes) {
    char buf[32];
    if (bytes >= (uintmax_t(1) << 30))
        std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(uintmax_t(1) << 30));
    else
        std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / double(1 << 20));
    return buf;
}

}  // namespace

void check_input_file(const std::filesystem::path& path, uintmax_t max_bytes, const char* kind) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw std::runtime_error(errno == ENOENT ? "no such file" : std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw std::runtime_error("is a directory");
    if (!S_ISREG(st.st_mode)) {
        const char* what = S_ISFIFO(st.st_mode)                         ? "a FIFO"
                           : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                           : S_ISSOCK(st.st_mode)                       ? "a socket"
                                                                        : "not a file";
        throw std::runtime_error(std::string("not a regular file (") + what + ")");
    }
    if (uintmax_t(st.st_size) > max_bytes)
        throw std::runtime_error("is " + size_text(uintmax_t(st.st_size)) + "; the limit for " +
                                 kind + " is " + size_text(max_bytes));
}

std::string read_input_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw std::runtime_error(std::strerror(errno));
    const std::streamoff size = in.tellg();
    if (size < 0) throw std::runtime_error("cannot tell its size");
    std::string bytes;
    try {
        bytes.resize(static_cast<size_t>(size));
    } catch (const std::bad_alloc&) {
        throw std::runtime_error("out of memory reading its " + size_text(uintmax_t(size)));
    }
    in.seekg(0);
    in.read(bytes.data(), size);
    if (in.gcount() != size)
        throw std::runtime_error("read " + std::to_string(in.gcount()) + " of its " +
                                 std::to_string(size) + " bytes");
    return bytes;
}

}  // namespace wavetrace
