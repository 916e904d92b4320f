#include "kernels/kernels.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

void generate(const WaveInputs& in,
              uint32_t sample,
              uint32_t first_pixel,
              size_t begin,
              size_t end,
              PathQueue& paths,
              RayQueue& rays) {
    const uint32_t width = static_cast<uint32_t>(in.config.width);
    const PackedMedia media = PackedMedia::pack(in.camera_media);
    const bool has_media = !in.scene.media.empty();
    for (size_t i = begin; i < end; ++i) {
        const uint32_t pixel = first_pixel + static_cast<uint32_t>(i);
        const int x = static_cast<int>(pixel % width), y = static_cast<int>(pixel / width);
        const Ray ray = generate_camera_ray(in.camera, in.config.seed, pixel, sample, x, y);
        paths.pixel[i] = pixel;
        paths.bounce[i] = 0;
        paths.crossings[i] = 0;
        paths.beta[i] = Color(1.0f);
        paths.radiance[i] = Color(0.0f);
        set_previous_vertex(paths, i, PreviousVertex{ray.o});
        paths.media[i] = media;
        paths.flight[i] = has_media ? segment_flight(in.config.seed, pixel, sample, 0) : 0.0f;
        set_ray(rays, i, ray);
    }
}

}  // namespace wavetrace
