#include "kernels/kernels.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

void generate(
    const WaveInputs& in, WaveQueues& q, uint64_t first_global, size_t begin, size_t end) {
    const uint64_t pixels = static_cast<uint64_t>(in.config.width) * in.config.height;
    PathState& ps = q.paths;
    for (size_t slot = begin; slot < end; ++slot) {
        const uint64_t global = first_global + slot;
        const uint32_t pixel = static_cast<uint32_t>(global % pixels);
        const uint32_t sample = static_cast<uint32_t>(in.config.first_sample + global / pixels);
        const int x = static_cast<int>(pixel % in.config.width),
                  y = static_cast<int>(pixel / in.config.width);
        Ray ray = generate_camera_ray(in.camera, in.config.seed, pixel, sample, x, y);
        ps.pixel[slot] = pixel;
        ps.sample[slot] = sample;
        ps.bounce[slot] = 0;
        ps.beta[slot] = Color(1.0f);
        ps.radiance[slot] = Color(0.0f);
        ps.prev[slot] = PreviousVertex{ray.o};
        ps.media[slot] = in.camera_media;
        ps.flight[slot] = segment_flight(in.config.seed, pixel, sample, 0);
        ps.crossings[slot] = 0;
        q.rays.origin[slot] = ray.o;
        q.rays.dir[slot] = ray.d;
        q.rays.tmin[slot] = ray.tmin;
        q.rays.path[slot] = static_cast<uint32_t>(slot);
    }
}

}  // namespace wavetrace
