// libFuzzer target: a mesh file through read_mesh_file (Assimp plus our own checks), and a glTF
// file through our reader of its cameras and lights too. The first byte picks the format (the
// extension Assimp dispatches on), the rest is the file; format 6 is an OBJ's material library:
// the rest is m.mtl, read through a fixed m.obj that names it and two of its materials; format 7
// a Mitsuba .serialized file (our own reader), its first and second shapes.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "formats/gltf_json.h"
#include "formats/serialized_mesh.h"
#include "loaders/mesh_file.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* kExtensions[] = {".ply", ".obj", ".stl",  ".gltf",
                                        ".glb", ".off", ".mtl", ".serialized"};
    static const fs::path dir = [] {
        fs::path d =
            fs::temp_directory_path() / ("wavetrace-fuzz-mesh-" + std::to_string(::getpid()));
        fs::create_directories(d);
        std::ofstream(d / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                      "vt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n"
                                      "usemtl b\nf 2 4 3\n";
        return d;
    }();
    const char* extension = kExtensions[data[0] % 8];
    const fs::path written = dir / (std::string("m") + extension);
    {
        std::ofstream out(written, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    }
    const fs::path file = std::string(extension) == ".mtl" ? dir / "m.obj" : written;
    if (std::string(extension) == ".serialized") {
        for (uint32_t shape : {0u, 1u}) {
            try {
                wavetrace::MeshFile mesh = wavetrace::read_serialized_mesh(file, shape);
                (void)wavetrace::smooth_normals(mesh.positions, mesh.indices);
            } catch (const std::runtime_error&) {
            }
        }
        fs::remove(written);
        return 0;
    }
    try {
        wavetrace::MeshFile mesh = wavetrace::read_mesh_file(file);
        (void)wavetrace::smooth_normals(mesh.positions, mesh.indices);
    } catch (const std::runtime_error&) {
    }
    // glTF's own JSON reader (cameras, lights, strengths), also where Assimp refused the file.
    const std::string ext = file.extension().string();
    if (ext == ".gltf" || ext == ".glb") {
        try {
            (void)wavetrace::gltf_placements(file, ext == ".glb");
        } catch (const std::runtime_error&) {
        }
    }
    fs::remove(written);
    return 0;
}
