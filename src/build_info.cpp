#include "wavetrace/build_info.h"

#include <OpenImageIO/imageio.h>
#include <assimp/version.h>
#include <oneapi/tbb/version.h>

#include "wavetrace/accel/bvh.h"

namespace wavetrace {

BuildInfo build_info() {
    BuildInfo info;
    info.version = WAVETRACE_VERSION;
    info.build_type = WAVETRACE_BUILD_TYPE;
    info.simd = std::string(simd_target()) + " (BVH traversal; chosen at run time)";
    info.tbb = TBB_runtime_version();
    int oiio = OIIO::openimageio_version();  // 10000 major + 100 minor + patch
    info.openimageio = std::to_string(oiio / 10000) + "." + std::to_string(oiio / 100 % 100) + "." +
                       std::to_string(oiio % 100);
    info.assimp = std::to_string(aiGetVersionMajor()) + "." + std::to_string(aiGetVersionMinor()) +
                  "." + std::to_string(aiGetVersionPatch());
    info.embree = WAVETRACE_EMBREE_VERSION;
    return info;
}

}  // namespace wavetrace
