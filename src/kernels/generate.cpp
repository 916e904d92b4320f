#include <algorithm>

#include "blocks/lane_kernels.h"
#include "kernels/kernels.h"
#include "shading/path_vertex.h"

namespace wavetrace {

namespace {
constexpr uint32_t kTileW = 4, kTileH = 2;
}  // namespace

uint32_t pixel_in_pass_order(uint32_t k, uint32_t width, uint32_t height) {
    const uint32_t band = k / (kTileH * width), offset = k % (kTileH * width);
    const uint32_t band_h = std::min(kTileH, height - kTileH * band);
    // Every tile before the band's last is full, kTileW wide.
    const uint32_t tile = offset / (kTileW * band_h), in_tile = offset % (kTileW * band_h);
    const uint32_t tile_w = std::min(kTileW, width - kTileW * tile);
    const uint32_t x = kTileW * tile + in_tile % tile_w, y = kTileH * band + in_tile / tile_w;
    return y * width + x;
}

PassOrderWalk::PassOrderWalk(uint32_t k, uint32_t width, uint32_t height)
    : width_(width), height_(height) {
    const uint32_t pixel = pixel_in_pass_order(k, width, height);
    const uint32_t x = pixel % width, y = pixel / width;
    band_ = y / kTileH;
    tile_ = x / kTileW;
    band_h_ = std::min(kTileH, height - kTileH * band_);
    tile_w_ = std::min(kTileW, width - kTileW * tile_);
    dx_ = x % kTileW;
    dy_ = y % kTileH;
}

// Row by row within a tile, tile by tile along a band, band by band down the image.
void PassOrderWalk::next() {
    if (++dx_ < tile_w_) return;
    dx_ = 0;
    if (++dy_ < band_h_) return;
    dy_ = 0;
    if (kTileW * ++tile_ >= width_) {
        tile_ = 0;
        ++band_;
        band_h_ = std::min(kTileH, height_ - std::min(height_, kTileH * band_));
    }
    tile_w_ = std::min(kTileW, width_ - kTileW * tile_);
}

void generate(const WaveInputs& in,
              WaveSamples samples,
              uint32_t first_index,
              size_t begin,
              size_t end,
              PathQueue& paths,
              RayQueue& rays) {
    const uint32_t width = static_cast<uint32_t>(in.width),
                   height = static_cast<uint32_t>(in.height);
    const PackedMedia media = PackedMedia::pack(in.camera_media);
    const bool flights = !in.scene.media.empty();
    // Chunk by chunk: the pixels, their camera rays in SIMD lanes, then the path entries.
    alignas(64) uint32_t pixel[kShadeChunk], sample[kShadeChunk];
    alignas(64) float x[kShadeChunk], y[kShadeChunk];
    CameraRayBlock camera;
    if (begin >= end) return;
    const uint32_t per_pixel = samples.per_pixel;
    PassOrderWalk walk(first_index + static_cast<uint32_t>(begin / per_pixel), width, height);
    uint32_t j = static_cast<uint32_t>(begin % per_pixel);  // the entry's sample of its pixel
    for (size_t c = begin; c < end; c += kShadeChunk) {
        const size_t n = std::min(kShadeChunk, end - c);
        for (size_t k = 0; k < n; ++k) {
            pixel[k] = walk.y() * width + walk.x();
            sample[k] = samples.first + j;
            x[k] = static_cast<float>(walk.x());
            y[k] = static_cast<float>(walk.y());
            if (++j == per_pixel) {
                j = 0;
                walk.next();
            }
        }
        draw_camera_rays(in.camera, in.sampler, sample, pixel, x, y, n, flights, camera);
        for (size_t k = 0; k < n; ++k) {
            const size_t i = c + k;
            const Ray ray{{camera.o[0][k], camera.o[1][k], camera.o[2][k]},
                          {camera.d[0][k], camera.d[1][k], camera.d[2][k]}};
            paths.pixel[i] = pixel[k];
            paths.sample[i] = sample[k];
            paths.slot[i] = static_cast<uint32_t>(i);
            paths.bounce[i] = 0;
            paths.depth[i] = 0;
            paths.crossings[i] = 0;
            paths.beta[i] = Color(1.0f);
            paths.eta_scale[i] = 1.0f;
            paths.radiance[i] = Color(0.0f);
            set_previous_vertex(paths, i, PreviousVertex{ray.o});
            paths.media[i] = media;
            paths.flight[i] = flights ? camera.flight[k] : 0.0f;  // as segment_flight()
            set_ray(rays, i, ray);
        }
    }
}

}  // namespace wavetrace
