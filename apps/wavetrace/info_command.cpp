#include <fmt/core.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::cli {

void add_info_command(CLI::App& app, InfoOptions& o) {
    CLI::App* cmd = app.add_subcommand("info", "describe a scene: counts, bounds, BVH, memory");
    cmd->add_option("scene", o.scene, "scene file (JSON, Mitsuba 3 XML, or glTF: .gltf, .glb)")
        ->required();
    cmd->add_option("-D,--define", o.defines,
                    "Mitsuba scenes: NAME=VALUE for a $NAME parameter (overrides <default>)");
    cmd->add_option("--asset-root", o.asset_root,
                    "every file the scene reads (meshes, textures, includes, and what meshes name) "
                    "must lie inside this folder, symbolic links resolved");
    cmd->add_option("--threads", o.threads, "worker threads for the BVH build (default: all)");
}

namespace {

std::string mib(size_t bytes) {
    return fmt::format("{:.2f} MiB", bytes / (1024.0 * 1024.0));
}

template <class T>
size_t bytes_of(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

// The meshes' attributes (Scene::mesh_attributes), one entry per name and layout, e.g.
// "vertex_color (per vertex, 3 channels, 2 meshes)"; empty without any.
std::string attribute_list(const Scene& scene) {
    struct Entry {
        const MeshAttribute* first;
        size_t meshes;
    };
    std::vector<Entry> entries;
    for (const MeshAttribute& a : scene.mesh_attributes) {
        auto same = [&](const Entry& e) {
            return e.first->name == a.name && e.first->per_face == a.per_face &&
                   e.first->channels == a.channels;
        };
        if (auto it = std::find_if(entries.begin(), entries.end(), same); it != entries.end())
            ++it->meshes;
        else
            entries.push_back({&a, 1});
    }
    std::string list;
    for (const Entry& e : entries)
        list += fmt::format("{}{} (per {}, {} channel{}, {} mesh{})", list.empty() ? "" : ", ",
                            e.first->name, e.first->per_face ? "face" : "vertex", e.first->channels,
                            e.first->channels == 1 ? "" : "s", e.meshes, e.meshes == 1 ? "" : "es");
    return list;
}

}  // namespace

int run_info(const InfoOptions& o) {
    if (o.threads < 0) {
        std::cerr << "wavetrace: error: --threads: expected a positive count\n";
        return kExitBadInput;
    }
    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    Scene scene;
    try {
        LoadOptions load;
        load.params = parse_defines(o.defines);
        load.asset_root = o.asset_root;
        scene = load_scene(o.scene, load);
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    }
    Bvh bvh = Bvh::build(scene);
    const BvhStats& st = bvh.stats();
    Aabb b = scene.bounds();
    std::vector<PrimRef> emitters = collect_emitters(scene);
    size_t geometry = bytes_of(scene.spheres) + bytes_of(scene.quads) + bytes_of(scene.triangles) +
                      bytes_of(scene.positions) + bytes_of(scene.normals) + bytes_of(scene.uvs);
    for (const MeshAttribute& a : scene.mesh_attributes) geometry += bytes_of(a.values);
    size_t texels = 0;
    for (const ImageData& img : scene.images) texels += bytes_of(img.texels);
    const Background& bg = scene.background;
    std::string background =
        bg.kind == Background::Kind::Constant
            ? fmt::format("constant [{} {} {}]", bg.radiance.x, bg.radiance.y, bg.radiance.z)
            : fmt::format("environment {}", scene.images[bg.image].path);

    fmt::print("scene        {}\n", o.scene);
    fmt::print("primitives   {} ({} triangles, {} quads, {} spheres)\n", scene.primitive_count(),
               scene.triangles.size(), scene.quads.size(), scene.spheres.size());
    fmt::print("meshes       {} ({} vertices)\n", scene.meshes.size(), scene.positions.size());
    if (const std::string list = attribute_list(scene); !list.empty())
        fmt::print("attributes   {}\n", list);
    fmt::print("lights       {} emissive primitives, {} point, spot or directional; background {}\n",
               emitters.size(), scene.lights.size(), background);
    fmt::print("materials    {}, textures {}, images {}, media {}\n", scene.materials.size(),
               scene.textures.size(), scene.images.size(), scene.media.size());
    fmt::print("bounds       [{:.4g} {:.4g} {:.4g}] .. [{:.4g} {:.4g} {:.4g}]\n", b.lo.x, b.lo.y,
               b.lo.z, b.hi.x, b.hi.y, b.hi.z);
    fmt::print("camera       from [{} {} {}] at [{} {} {}], vfov {}, {}x{}\n",
               scene.camera.look_from.x, scene.camera.look_from.y, scene.camera.look_from.z,
               scene.camera.look_at.x, scene.camera.look_at.y, scene.camera.look_at.z,
               scene.camera.vfov, scene.render.width, scene.render.height);
    fmt::print(
        "bvh          {} binary nodes ({} leaves), depth {}, SAH cost {:.2f}; {} 8-wide nodes "
        "for traversal; build {:.1f} ms\n",
        st.nodes, st.leaves, st.depth, st.sah_cost, st.wide_nodes, st.build_ms);
    fmt::print("simd         {} (chosen at run time)\n", simd_target());
    fmt::print(
        "memory       geometry {}, bvh {} (binary tree {}, traversal layout {}), textures {}\n",
        mib(geometry), mib(st.bytes + st.wide_bytes), mib(st.bytes), mib(st.wide_bytes),
        mib(texels));
    const size_t per_path = wavefront_bytes_per_path(), wave = WavefrontOptions{}.wave_size;
    fmt::print(
        "wavefront    {} B of queues per path in flight; waves of {} paths, one per thread: {} "
        "per thread\n",
        per_path, wave, mib(per_path * wave));
    return kExitOk;
}

}  // namespace wavetrace::cli
