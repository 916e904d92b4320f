#include <filesystem>
#include <iostream>

#include "commands.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::cli {
namespace fs = std::filesystem;

void add_convert_command(CLI::App& app, ConvertOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "convert", "write a scene file (Mitsuba 3 XML, pbrt-v4, JSON) as our JSON scene, to edit it");
    cmd->add_option("scene", o.scene, "scene file (Mitsuba 3 XML, pbrt-v4 or JSON)")->required();
    cmd->add_option("-o,--output", o.output, "the JSON file to write")->required();
    cmd->add_option("-D,--define", o.defines,
                    "Mitsuba scenes: NAME=VALUE for a $NAME parameter (overrides <default>)");
    cmd->add_option("--asset-root", o.asset_root,
                    "every file the scene reads (meshes, textures, includes, and what meshes name) "
                    "must lie inside this folder, symbolic links resolved");
}

int run_convert(const ConvertOptions& o) {
    try {
        std::error_code ec;
        if (fs::equivalent(o.scene, o.output, ec))
            throw SceneError("-o " + o.output + ": that is the scene file itself");
        LoadOptions load;
        load.params = parse_defines(o.defines);
        load.asset_root = o.asset_root;
        for (const fs::path& written : convert_scene(o.scene, o.output, load))
            std::cout << written.string() << "\n";
    } catch (const SceneError& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitFailure;
    }
    return kExitOk;
}

}  // namespace wavetrace::cli
