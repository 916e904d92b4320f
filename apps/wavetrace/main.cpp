// wavetrace: render a scene, describe it, merge renders of sample ranges, compare a render with
// a reference, or convert a scene file into our JSON.
#include <iostream>
#include <new>

#include "commands.h"
#include "wavetrace/build_info.h"

int main(int argc, char** argv) {
    using namespace wavetrace::cli;
    using wavetrace::BuildInfo, wavetrace::build_info;
    CLI::App app{"wavetrace: a physically based path tracer with a wavefront engine"};
    app.set_version_flag("--version", [] {
        BuildInfo b = build_info();
        return "wavetrace " + b.version + " (" + b.build_type + " build)\n" +
               "  SIMD:        " + b.simd + "\n" + "  oneTBB:      " + b.tbb + "\n" +
               "  OpenImageIO: " + b.openimageio + "\n" + "  Assimp:      " + b.assimp + "\n" +
               "  Embree:      " + b.embree +
               " (reference intersector of the tests and benchmarks)";
    });
    app.require_subcommand(1);
    RenderOptions render;
    InfoOptions info;
    CompareOptions compare;
    MergeOptions merge;
    ConvertOptions convert;
    add_render_command(app, render);
    add_info_command(app, info);
    add_compare_command(app, compare);
    add_merge_command(app, merge);
    add_convert_command(app, convert);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? kExitOk : kExitBadInput;
    }
    try {
        if (app.got_subcommand("render")) return run_render(render);
        if (app.got_subcommand("compare")) return run_compare(compare);
        if (app.got_subcommand("merge")) return run_merge(merge);
        if (app.got_subcommand("convert")) return run_convert(convert);
        return run_info(info);
    } catch (const std::bad_alloc&) {
        // The render reports what it was allocating; this catches the rest (e.g. a scene's
        // own arrays), so that running out of memory is an error message, not SIGABRT.
        std::cerr << "wavetrace: error: out of memory\n";
        return kExitBadInput;
    }
}
