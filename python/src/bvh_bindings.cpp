// Rays from NumPy: batches of rays traced in parallel through the scene's BVH.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <cmath>

#include "casters.h"
#include "py_scene.h"

namespace wavetrace::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

struct PyBvh {
    std::shared_ptr<PyScene> scene;
    std::shared_ptr<const Bvh> bvh;
    uint64_t version = 0;

    const Bvh& current() const {
        if (scene->version != version)
            throw std::runtime_error("the scene changed after this BVH was built: build another");
        return *bvh;
    }
};

// A batch of rays as the arrays came: origins and directions (n, 3), tmin and tmax each a number
// or one per ray.
struct RayArrays {
    FloatArray origins, directions, tmin, tmax;
    size_t n = 0;
    // Their data, read once per ray: a bound's step is 0 when one number serves every ray.
    const float *o_ = nullptr, *d_ = nullptr, *lo_ = nullptr, *hi_ = nullptr;
    size_t lo_step_ = 0, hi_step_ = 0;

    RayArrays(const py::handle& o, const py::handle& d, const py::handle& lo, const py::handle& hi)
        : origins(FloatArray::ensure(o)), directions(FloatArray::ensure(d)) {
        if (!origins || origins.ndim() != 2 || origins.shape(1) != 3)
            throw py::value_error("origins: expected an array of shape (n, 3)");
        n = size_t(origins.shape(0));
        if (!directions || directions.ndim() != 2 || directions.shape(1) != 3 ||
            size_t(directions.shape(0)) != n)
            throw py::value_error("directions: expected an array of shape (n, 3), as origins");
        tmin = bounds(lo, 0.0f, "tmin");
        tmax = bounds(hi, kInfinity, "tmax");
        o_ = origins.data();
        d_ = directions.data();
        lo_ = tmin.data();
        hi_ = tmax.data();
        lo_step_ = tmin.size() == 1 ? 0 : 1;
        hi_step_ = tmax.size() == 1 ? 0 : 1;
    }

    FloatArray bounds(const py::handle& h, float fallback, const char* name) const {
        FloatArray a = h.is_none() ? FloatArray(py::ssize_t(1)) : FloatArray::ensure(h);
        if (h.is_none()) a.mutable_at(0) = fallback;
        if (!a || !((a.ndim() == 0) || (a.ndim() == 1 && (size_t(a.shape(0)) == n || a.shape(0) == 1))))
            throw py::value_error(std::string(name) + ": expected a number or an array of shape (n,)");
        return a;
    }

    Ray ray(size_t i) const {
        const float* o = o_ + 3 * i;
        const float* d = d_ + 3 * i;
        return Ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, lo_[lo_step_ * i], hi_[hi_step_ * i]};
    }

    // Whether the traversal can take the ray: a finite origin, a finite non-zero direction,
    // bounds that are numbers.
    static bool valid(const Ray& r) {
        return std::isfinite(r.o.x) && std::isfinite(r.o.y) && std::isfinite(r.o.z) &&
               std::isfinite(r.d.x) && std::isfinite(r.d.y) && std::isfinite(r.d.z) &&
               (r.d.x != 0 || r.d.y != 0 || r.d.z != 0) && !std::isnan(r.tmin) &&
               !std::isnan(r.tmax);
    }
};

// Calls trace(rays, first) for consecutive blocks of at most kBlock rays, in parallel, the GIL
// released: a block's rays are copied from the arrays into a small buffer the traversal reads,
// and checked on the way (ValueError naming the first ray the traversal cannot take).
constexpr size_t kBlock = 256;
template <class Trace>
void for_blocks(PyBvh& b, const RayArrays& rays, Trace&& trace) {
    InUse use(*b.scene);
    std::atomic<size_t> first_bad{rays.n};
    {
        py::gil_scoped_release release;
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, rays.n, kBlock), [&](const tbb::blocked_range<size_t>& r) {
                std::array<Ray, kBlock> buffer;
                for (size_t first = r.begin(); first < r.end(); first += kBlock) {
                    const size_t count = std::min(kBlock, r.end() - first);
                    bool ok = true;
                    for (size_t i = 0; i < count; ++i) {
                        buffer[i] = rays.ray(first + i);
                        ok &= RayArrays::valid(buffer[i]);
                    }
                    if (!ok) {
                        for (size_t i = 0; i < count; ++i) {
                            if (RayArrays::valid(buffer[i])) continue;
                            size_t seen = first_bad.load();
                            while (first + i < seen && !first_bad.compare_exchange_weak(seen, first + i)) {
                            }
                            break;
                        }
                        continue;
                    }
                    trace(std::span<const Ray>(buffer.data(), count), first);
                }
            });
    }
    if (first_bad.load() < rays.n)
        throw py::value_error("ray " + std::to_string(first_bad.load()) +
                              ": needs a finite origin, a finite non-zero direction and bounds "
                              "that are numbers");
}

py::tuple intersect(PyBvh& b, const py::handle& o, const py::handle& d, const py::handle& tmin,
                    const py::handle& tmax) {
    const Bvh& bvh = b.current();
    RayArrays rays(o, d, tmin, tmax);
    const py::ssize_t n = py::ssize_t(rays.n);
    py::array_t<float> t(n), u(n), v(n);
    py::array_t<int8_t> kind(n);
    py::array_t<int32_t> prim(n);
    float *pt = t.mutable_data(), *pu = u.mutable_data(), *pv = v.mutable_data();
    int8_t* pk = kind.mutable_data();
    int32_t* pp = prim.mutable_data();
    for_blocks(b, rays, [&](std::span<const Ray> block, size_t first) {
        std::array<Hit, kBlock> hits;
        bvh.intersect_each(block, std::span<Hit>(hits.data(), block.size()));
        for (size_t i = 0; i < block.size(); ++i) {
            const Hit& h = hits[i];
            const size_t j = first + i;
            pt[j] = h.t;
            pu[j] = h.u;
            pv[j] = h.v;
            pk[j] = h.found() ? int8_t(h.prim.kind()) : int8_t(-1);
            pp[j] = h.found() ? int32_t(h.prim.index()) : -1;
        }
    });
    return py::make_tuple(t, kind, prim, u, v);
}

py::array_t<bool> occluded(PyBvh& b, const py::handle& o, const py::handle& d,
                           const py::handle& tmin, const py::handle& tmax) {
    const Bvh& bvh = b.current();
    RayArrays rays(o, d, tmin, tmax);
    py::array_t<bool> out(py::ssize_t(rays.n));
    bool* po = out.mutable_data();
    for_blocks(b, rays, [&](std::span<const Ray> block, size_t first) {
        bvh.occluded_each(block, std::span<bool>(po + first, block.size()));
    });
    return out;
}

}  // namespace

void bind_bvh(py::module_& m) {
    py::class_<PyBvh>(m, "Bvh",
                      "The scene's BVH, for tracing batches of rays from NumPy arrays (in "
                      "parallel, the GIL released). It stays valid while the scene's geometry "
                      "does not change.")
        .def(py::init([](const std::shared_ptr<PyScene>& s) {
                 PyBvh b{s, nullptr, s->version};
                 InUse use(*s);
                 py::gil_scoped_release release;
                 b.bvh = s->bvh();
                 return b;
             }),
             py::arg("scene"))
        .def("_intersect", &intersect, py::arg("origins"), py::arg("directions"),
             py::arg("tmin") = py::none(), py::arg("tmax") = py::none())
        .def(
            "intersect_one",
            [](PyBvh& b, Vec3 o, Vec3 d, float tmin, float tmax) {
                const Hit h = b.current().intersect(Ray{o, d, tmin, tmax});
                return py::make_tuple(h.t, h.found() ? int(h.prim.kind()) : -1,
                                      h.found() ? int64_t(h.prim.index()) : int64_t(-1), h.u, h.v);
            },
            py::arg("origin"), py::arg("direction"), py::arg("tmin") = 0.0f,
            py::arg("tmax") = kInfinity,
            "One ray's closest hit through Bvh::intersect: (t, kind, prim, u, v) as in Hits.")
        .def("occluded", &occluded, py::arg("origins"), py::arg("directions"),
             py::arg("tmin") = py::none(), py::arg("tmax") = py::none(),
             "Whether anything is hit in [tmin, tmax] along each ray: a bool array (n,). "
             "origins, directions: (n, 3); tmin, tmax: a number or one per ray (default 0, inf).")
        .def_property_readonly("stats", [](const PyBvh& b) {
            const BvhStats& st = b.current().stats();
            py::dict d;
            d["nodes"] = st.nodes;
            d["leaves"] = st.leaves;
            d["depth"] = st.depth;
            d["sah_cost"] = st.sah_cost;
            d["build_ms"] = st.build_ms;
            d["bytes"] = st.bytes + st.wide_bytes;
            return d;
        });
}

}  // namespace wavetrace::python
