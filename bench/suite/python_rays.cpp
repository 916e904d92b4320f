// Rays from NumPy against the same rays in C++: 10^6 incoherent rays on the dragon, traced by
// Bvh::intersect_each over blocks in parallel (the best the C++ API offers), and by the Python
// module's Bvh.intersect from float32 arrays (bench/python_rays.py, a child process). The
// difference is what the binding costs: converting the arrays, checking the rays, writing the
// hit arrays. Each round times C++ and Python (each the median of three tries).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>

#include "sampling/sampler.h"
#include "sections.h"

namespace wavetrace::bench {
namespace {

// From points on a sphere about the scene's bounds towards points inside them.
std::vector<Ray> incoherent_rays(const Scene& scene, size_t n) {
    const Aabb b = scene.bounds();
    const Point3 centre = 0.5f * (b.lo + b.hi);
    const float radius = length(b.hi - b.lo);
    std::vector<Ray> rays(n);
    for (size_t i = 0; i < n; ++i) {
        auto u = [&](int d) { return sample_1d(11, uint32_t(i), 0, d); };
        const float z = 1 - 2 * u(0), phi = 2 * kPi * u(1),
                    s = std::sqrt(std::max(0.0f, 1 - z * z));
        const Point3 o = centre + radius * Vec3(s * std::cos(phi), s * std::sin(phi), z);
        const Point3 target = b.lo + Vec3(u(2), u(3), u(4)) * (b.hi - b.lo);
        rays[i] = Ray{o, target - o};
    }
    return rays;
}

double cpp_seconds(const Bvh& bvh, const std::vector<Ray>& rays, std::vector<Hit>& hits) {
    constexpr size_t kBlock = 256;
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kBlock),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t first = r.begin(); first < r.end(); first += kBlock) {
                              const size_t count = std::min(kBlock, r.end() - first);
                              bvh.intersect_each(std::span(rays).subspan(first, count),
                                                 std::span(hits).subspan(first, count));
                          }
                      });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void bench_python_rays(const Options& o, Results& r) {
    r.table("python_rays", {"scene", "rays", "cpp_ms", "python_ms", "python_over_cpp", "ratio_min",
                            "ratio_max", "hits_equal"});
#ifndef WAVETRACE_PYTHON_PATH
    std::printf("python_rays: skipped (built without the Python module)\n");
    return;
#else
    const std::string name = o.quick ? "cornell" : "dragon";
    const std::filesystem::path scene_path = o.scenes / (name + ".json");
    Scene scene = load_scene(scene_path);
    Bvh bvh = Bvh::build(scene);
    const size_t n = o.quick ? 10000 : 1000000;
    const std::vector<Ray> rays = incoherent_rays(scene, n);
    std::vector<Hit> hits(n);
    const std::filesystem::path dir = std::filesystem::temp_directory_path();
    const std::filesystem::path ray_file = dir / "wavetrace-bench-rays.f32",
                                hit_file = dir / "wavetrace-bench-hits.f32";
    {
        static_assert(sizeof(Ray) == 8 * sizeof(float));
        std::ofstream out(ray_file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(rays.data()), std::streamsize(n * sizeof(Ray)));
    }
    std::vector<double> cpp, py, ratios;
    for (int rep = 0; rep < o.repetitions(); ++rep) {
        std::vector<double> tries;
        for (int k = 0; k < 3; ++k) tries.push_back(cpp_seconds(bvh, rays, hits));
        const double c = spread(tries).median;
        const std::string command = "PYTHONPATH='" WAVETRACE_PYTHON_PATH "' '" WAVETRACE_PYTHON
                                    "' '" WAVETRACE_BENCH_DIR "/python_rays.py' '" +
                                    scene_path.string() + "' '" + ray_file.string() + "' '" +
                                    hit_file.string() + "'";
        FILE* p = popen(command.c_str(), "r");
        double seconds = -1;
        if (p) {
            if (std::fscanf(p, "%lf", &seconds) != 1) seconds = -1;
            pclose(p);
        }
        if (seconds <= 0) {
            std::printf("python_rays: %s failed\n", command.c_str());
            return;
        }
        cpp.push_back(c);
        py.push_back(seconds);
        ratios.push_back(seconds / c);
    }
    // The hits Python wrote (t per ray) against ours, bit for bit.
    std::vector<float> t(n);
    std::ifstream in(hit_file, std::ios::binary);
    in.read(reinterpret_cast<char*>(t.data()), std::streamsize(n * sizeof(float)));
    bool equal = bool(in);
    for (size_t i = 0; equal && i < n; ++i) equal = t[i] == hits[i].t;
    std::filesystem::remove(ray_file);
    std::filesystem::remove(hit_file);
    const Spread ratio = spread(ratios);
    r.row("python_rays", {name, n, spread(cpp).median * 1e3, spread(py).median * 1e3, ratio.median,
                          ratio.min, ratio.max, equal});
    std::printf(
        "python_rays %s: %zu rays, C++ %.1f ms, Python %.1f ms, ratio %.3f [%.3f, %.3f]%s\n",
        name.c_str(), n, spread(cpp).median * 1e3, spread(py).median * 1e3, ratio.median, ratio.min,
        ratio.max, equal ? "" : ", HITS DIFFER");
#endif
}

}  // namespace wavetrace::bench
