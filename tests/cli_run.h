// Runs the wavetrace CLI as a user would, through the shell, and captures what it prints.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "temp_dir.h"
#include "test_paths.h"

// Whether this build runs under AddressSanitizer, which reserves terabytes of shadow memory:
// no `ulimit -v` leaves it room to start.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

struct CliResult {
    int code;  // exit status, -1 if killed by a signal
    std::string out, err;
};

// `wavetrace ARGS`, run by bash; `prefix` comes first in the same shell (e.g. "ulimit -f 4;"),
// `wrapper` right before the program (e.g. "timeout 20"). stdout and stderr land in `dir`.
inline CliResult run_cli(const TempDir& dir,
                         const std::string& args,
                         const std::string& prefix = "",
                         const std::string& wrapper = "") {
    const std::string out = (dir.path() / "stdout").string(),
                      err = (dir.path() / "stderr").string();
    const std::string cmd = prefix + " " + wrapper + " '" + cli_path().string() + "' " + args +
                            " > '" + out + "' 2> '" + err + "'";
    int status = std::system(("bash -c \"" + cmd + "\"").c_str());
    auto slurp = [](const std::string& p) {
        std::stringstream s;
        s << std::ifstream(p).rdbuf();
        return s.str();
    };
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}
