// `wavetrace compare OURS REF`: how a render differs from a reference, and whether the
// difference is noise (see docs/cli.md for the pass rule).
#include <fmt/core.h>

#include <cmath>
#include <iostream>
#include <optional>

#include "commands.h"
#include "wavetrace/image/compare.h"
#include "wavetrace/image/image.h"

namespace wavetrace::cli {

void add_compare_command(CLI::App& app, CompareOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "compare a render with a reference: mean difference, relative MSE and, given variance "
        "images, per-block z-tests; exit 0 pass, 1 differs, 2 bad input");
    cmd->add_option("ours", o.ours, "the render (linear: EXR, HDR, PFM)")->required();
    cmd->add_option("ref", o.ref, "the reference image")->required();
    cmd->add_option("--ours-var", o.ours_var,
                    "variance of the render's pixel means (render --variance)");
    cmd->add_option("--ref-var", o.ref_var, "variance of the reference's pixel means");
    cmd->add_option("--block", o.block, "z-tests on squares of N x N pixels")
        ->capture_default_str();
    cmd->add_option("--alpha", o.alpha,
                    "probability that a correct render fails the z-tests, over all blocks")
        ->capture_default_str();
    cmd->add_option("--max-mean-diff", o.max_mean_diff,
                    "without variances: most relative difference of the image means")
        ->capture_default_str();
    cmd->add_option("--z-map", o.z_map,
                    "write each block's |z| as an image (needs a variance): black 0, white at the "
                    "failing level, red where a block fails");
    cmd->add_option("--max-rel-mse", o.max_rel_mse, "without variances: most relative MSE")
        ->capture_default_str();
}

namespace {

// x with erfc(x) = p, for p in (0, 1], by bisection (erfc falls monotonically).
double erfc_inverse(double p) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

Image read_linear(const std::string& path) {
    ImageData data = read_image(path);
    Image image(data.width, data.height);
    image.pixels = std::move(data.texels);
    return image;
}

}  // namespace

int run_compare(const CompareOptions& o) {
    auto bad_input = [](const std::string& message) {
        std::cerr << "wavetrace: error: " << message << "\n";
        return kExitBadInput;
    };
    if (o.block < 1 || o.block > 4096)
        return bad_input(fmt::format("--block: expected 1..4096, got {}", o.block));
    if (!(o.alpha > 0 && o.alpha < 1))
        return bad_input(fmt::format("--alpha: expected a probability in (0, 1), got {}", o.alpha));
    if (!(o.max_mean_diff >= 0) || !(o.max_rel_mse >= 0))
        return bad_input("--max-mean-diff and --max-rel-mse: expected numbers >= 0");
    ImageComparison c;
    try {
        const Image ours = read_linear(o.ours), ref = read_linear(o.ref);
        std::optional<Image> ours_var, ref_var;
        if (!o.ours_var.empty()) ours_var = read_linear(o.ours_var);
        if (!o.ref_var.empty()) ref_var = read_linear(o.ref_var);
        wavetrace::CompareOptions options;
        options.block = o.block;
        options.alpha = o.alpha;
        options.max_mean_rel_diff = o.max_mean_diff;
        options.max_rel_mse = o.max_rel_mse;
        try {
            c = compare_images(ours, ref, ours_var ? &*ours_var : nullptr,
                               ref_var ? &*ref_var : nullptr, options);
        } catch (const std::invalid_argument& e) {
            // The sizes or variances of the files as given: name them.
            std::string files = o.ours + " vs " + o.ref;
            for (const std::string* v : {&o.ours_var, &o.ref_var})
                if (!v->empty()) files += ", " + *v;
            throw std::invalid_argument(files + ": " + e.what());
        }
    } catch (const std::exception& e) {
        return bad_input(e.what());
    }
    fmt::print("mean      ours {:.6g}, reference {:.6g}: relative difference {:.3e}\n", c.mean_ours,
               c.mean_ref, c.mean_rel_diff);
    fmt::print("rel. MSE  {:.3e}\n", c.rel_mse);
    if (c.z_tested) {
        fmt::print(
            "z-tests   {} ({}x{} blocks and the whole image, x 3 channels) at level {:.3e} "
            "(alpha {}, Sidak): {} failed\n",
            c.tests, o.block, o.block, c.level, o.alpha, c.failed);
        fmt::print("          whole image z = {:.3f} {:.3f} {:.3f} (R G B)\n", c.image_z[0],
                   c.image_z[1], c.image_z[2]);
        fmt::print("          worst block at ({}, {}) channel {}: z = {:.3f}, p = {:.3e}\n",
                   c.worst.x, c.worst.y, "RGB"[c.worst.channel], c.worst.z, c.worst.p);
    } else {
        fmt::print("z-tests   none (no variance image); bounds: mean {}, rel. MSE {}\n",
                   o.max_mean_diff, o.max_rel_mse);
    }
    if (!o.z_map.empty()) {
        if (!c.z_tested) return bad_input("--z-map needs a variance image (--ours-var, --ref-var)");
        // |z| over the |z| at which a test fails, per channel averaged to grey; failing red.
        const double z_fail = std::sqrt(2.0) * erfc_inverse(c.level);
        Image map(c.block_z.width, c.block_z.height);
        for (size_t i = 0; i < map.pixels.size(); ++i) {
            const Color z = c.block_z.pixels[i];
            const float worst = max_component(z);
            map.pixels[i] =
                worst >= z_fail ? Color(1, 0, 0) : Color(float((z.x + z.y + z.z) / (3 * z_fail)));
        }
        try {
            write_image(o.z_map, map);
        } catch (const std::exception& e) {
            return bad_input(e.what());
        }
    }
    fmt::print("result    {}\n", c.pass ? "pass" : "differs");
    return c.pass ? kExitOk : kExitFailure;
}

}  // namespace wavetrace::cli
