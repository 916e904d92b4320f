#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::cli {
namespace fs = std::filesystem;

void add_convert_command(CLI::App& app, ConvertOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "convert", "write a scene file (Mitsuba 3 XML, JSON) as our JSON scene, to edit it");
    cmd->add_option("scene", o.scene, "scene file (Mitsuba 3 XML or JSON)")->required();
    cmd->add_option("-o,--output", o.output, "the JSON file to write")->required();
    cmd->add_option("-D,--define", o.defines,
                    "Mitsuba scenes: NAME=VALUE for a $NAME parameter (overrides <default>)");
}

int run_convert(const ConvertOptions& o) {
    std::string text;
    try {
        std::error_code ec;
        if (fs::equivalent(o.scene, o.output, ec))
            throw SceneError("-o " + o.output + ": that is the scene file itself");
        LoadOptions load;
        load.params = parse_defines(o.defines);
        const fs::path folder = fs::path(o.output).parent_path();
        text = convert_to_json(o.scene, folder.empty() ? fs::path(".") : folder, load);
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    }
    std::ofstream out(o.output, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
        std::cerr << "wavetrace: error: " << o.output << ": cannot write: " << std::strerror(errno)
                  << "\n";
        return kExitFailure;
    }
    return kExitOk;
}

}  // namespace wavetrace::cli
