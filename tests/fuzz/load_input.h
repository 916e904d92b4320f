#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "wavetrace/wavetrace.h"

// What every scene fuzz target does with an input: writes it as `scene_file` (its extension
// picks the reader), loads it and builds the BVH of what loaded. Errors (SceneError,
// ImageError) are the expected outcome of bad input; a crash, a hang, a leak or a sanitizer
// report is a finding.
inline void load_input(const std::filesystem::path& scene_file, const uint8_t* data, size_t size) {
    {
        std::ofstream out(scene_file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    wavetrace::LoadOptions options;
    options.warn = [](const std::string&) {};
    try {
        wavetrace::Scene scene = wavetrace::load_scene(scene_file, options);
        // Keep the build small: the loaders' limits allow far bigger scenes than a fuzzer
        // should spend its time on.
        if (scene.primitive_count() <= 100000) (void)wavetrace::Bvh::build(scene);
    } catch (const wavetrace::SceneError&) {
    } catch (const wavetrace::ImageError&) {
    }
}
