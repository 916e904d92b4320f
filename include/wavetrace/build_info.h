// What this build of wavetrace is: its version, how it was compiled, the SIMD target its
// kernels run, and the versions of the libraries it was built against and runs with.
#pragma once

#include <string>

namespace wavetrace {

struct BuildInfo {
    std::string version;      // wavetrace's own, from CMakeLists.txt
    std::string build_type;   // CMAKE_BUILD_TYPE
    std::string simd;         // the SIMD target the traversal and shading kernels dispatch to
    std::string tbb;          // oneTBB: the runtime library's version
    std::string openimageio;  // OpenImageIO: the runtime library's version
    std::string assimp;       // Assimp: the runtime library's version
    std::string embree;       // Embree: found at configure time; only tests and benchmarks link it
};

BuildInfo build_info();

}  // namespace wavetrace
