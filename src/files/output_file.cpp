#include "files/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <string>

namespace wavetrace {
namespace fs = std::filesystem;
namespace {

// The temporary file being written, for the signal handler below: a signal that would end the
// process during the write removes it first, so that no temporary file is ever left behind.
char g_temp_path[4096];
volatile std::sig_atomic_t g_temp_active = 0;

constexpr int kGuarded = 4;
constexpr int kGuardedSignals[kGuarded] = {SIGINT, SIGTERM, SIGHUP, SIGXFSZ};
// The handlers the guard displaced, which it hands the signal on to.
using Handler = void (*)(int);
Handler g_previous[kGuarded] = {};

bool is_function(Handler h) {
    return h != SIG_DFL && h != SIG_IGN && h != SIG_ERR && h != nullptr;
}

// A program's own handler (the CLI's: stop at the next pass boundary) still handles the signal:
// the write goes on. A signal that ends the process (the default action, or a handler that
// restores it to die) first removes the temporary file.
extern "C" void on_signal_during_write(int sig) {
    int i = 0;
    while (i < kGuarded && kGuardedSignals[i] != sig) ++i;
    if (i < kGuarded && is_function(g_previous[i])) {
        g_previous[i](sig);
        struct sigaction now {};
        if (::sigaction(sig, nullptr, &now) == 0 && now.sa_handler != SIG_DFL) return;
    }
    if (g_temp_active) ::unlink(g_temp_path);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

// Registers `path` for removal on SIGINT, SIGTERM, SIGHUP or SIGXFSZ (the file-size limit
// exceeded mid-write) while alive.
class TempFileGuard {
  public:
    explicit TempFileGuard(const fs::path& path) {
        std::string s = path.string();
        if (s.size() >= sizeof g_temp_path) return;
        std::memcpy(g_temp_path, s.c_str(), s.size() + 1);
        g_temp_active = 1;
        for (int i = 0; i < kGuarded; ++i) {
            g_previous[i] = std::signal(kGuardedSignals[i], on_signal_during_write);
            // An ignored signal (nohup, `trap '' XFSZ`) stays ignored.
            if (g_previous[i] == SIG_IGN) std::signal(kGuardedSignals[i], SIG_IGN);
        }
    }
    ~TempFileGuard() {
        if (!g_temp_active) return;
        for (int i = 0; i < kGuarded; ++i) std::signal(kGuardedSignals[i], g_previous[i]);
        g_temp_active = 0;
    }
    TempFileGuard(const TempFileGuard&) = delete;
    TempFileGuard& operator=(const TempFileGuard&) = delete;
};

// Writes all of `bytes` to a new file at `path` and flushes it to disk; returns the error, or
// "" on success. A short write (a full disk) is an error, never a truncated file.
std::string write_all(const fs::path& path, const std::vector<unsigned char>& bytes) {
    int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return std::strerror(errno);
    size_t done = 0;
    while (done < bytes.size()) {
        ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            std::string err = n < 0 ? std::strerror(errno) : "short write";
            ::close(fd);
            return err;
        }
        done += static_cast<size_t>(n);
    }
    if (::fsync(fd) != 0) {
        std::string err = std::strerror(errno);
        ::close(fd);
        return err;
    }
    if (::close(fd) != 0) return std::strerror(errno);
    return "";
}

}  // namespace

fs::path temporary_path(const fs::path& path) {
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    return dir / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()));
}

void write_file_atomically(const fs::path& path, const std::vector<unsigned char>& bytes) {
    // A temporary name in the same folder; rename() then replaces the target atomically, so a
    // failed write keeps the previous file.
    const fs::path tmp = temporary_path(path);
    TempFileGuard guard(tmp);
    std::string err = write_all(tmp, bytes);
    if (err.empty() && ::rename(tmp.c_str(), path.c_str()) != 0) err = std::strerror(errno);
    if (!err.empty()) {
        ::unlink(tmp.c_str());
        throw std::runtime_error("cannot write: " + err);
    }
}

}  // namespace wavetrace
