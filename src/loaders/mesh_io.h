// The file system Assimp reads a mesh through. Every file a mesh pulls in (an OBJ's mtllib, a
// glTF's buffers and images) passes the checks the mesh itself passed: a regular file (a FIFO
// or a device would hang or flood memory) within the size limit for meshes, inside the mesh's
// folder and the asset root, if any (files/confinement.h).
#pragma once

#include <assimp/DefaultIOSystem.h>

#include <filesystem>
#include <string>
#include <vector>

#include "files/confinement.h"

namespace wavetrace {

class MeshIO : public Assimp::DefaultIOSystem {
  public:
    // `mesh`: the mesh file Assimp is asked to read; `asset_root`: empty, or the folder every
    // file must lie in.
    MeshIO(const std::filesystem::path& mesh, const std::filesystem::path& asset_root);

    bool Exists(const char* file) const override;
    Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;

    // What was refused ("FILE: reason") and what a reference named but is not there, in the
    // order Assimp asked; Assimp itself carries on without a missing MTL file, for instance.
    const std::vector<std::string>& refused() const { return refused_; }
    const std::vector<std::string>& missing() const { return missing_; }

  private:
    // Why `file` may not be read, or "" if it may; "no such file" for a missing one.
    std::string problem(const std::filesystem::path& file) const;
    void note(const std::filesystem::path& file, const std::string& why) const;

    Confinement confinement_;
    mutable std::vector<std::string> refused_, missing_;
};

}  // namespace wavetrace
