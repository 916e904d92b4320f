// A scene as Python holds it: the C++ Scene, what films of its renders are keyed by, and its
// BVH, rebuilt when a builder has changed the geometry since.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "wavetrace/accel/bvh.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace::python {

struct PyScene {
    Scene scene;
    std::string path;          // the file it was loaded from; empty: built in Python
    uint64_t fingerprint = 0;  // fnv1a_64 of that file, as the CLI's films record it; 0: none
    uint64_t version = 0;      // bumped by every builder call
    // Renders and ray batches running on it without the GIL; builders (which hold the GIL)
    // refuse to change the scene under them. Read and written with the GIL held.
    int users = 0;

    // What a builder calls first.
    void begin_change() {
        if (users > 0)
            throw std::runtime_error("the scene cannot change while it is rendered or traced");
        ++version;
    }

    // The BVH of the current version, checked (check_scene) and built on first use. A BVH
    // points into the scene's arrays, which a builder may reallocate: a stale one must not be
    // used.
    std::shared_ptr<const Bvh> bvh() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!bvh_ || bvh_version_ != version) {
            check_scene(scene);
            bvh_ = std::make_shared<Bvh>(Bvh::build(scene));
            bvh_version_ = version;
        }
        return bvh_;
    }

  private:
    std::mutex mutex_;
    std::shared_ptr<const Bvh> bvh_;
    uint64_t bvh_version_ = 0;
};

// Marks a scene in use for its lifetime: created and destroyed with the GIL held, around the
// code that releases it.
class InUse {
  public:
    explicit InUse(PyScene& s) : scene_(s) { ++scene_.users; }
    ~InUse() { --scene_.users; }
    InUse(const InUse&) = delete;
    InUse& operator=(const InUse&) = delete;

  private:
    PyScene& scene_;
};

}  // namespace wavetrace::python
