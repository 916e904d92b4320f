// Images through the CLI's own OpenImageIO code, and `compare`'s statistics.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "casters.h"
#include "wavetrace/image/compare.h"

namespace wavetrace::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

std::optional<Image> optional_image(const std::optional<FloatArray>& a, const char* what) {
    if (!a) return std::nullopt;
    return to_image(*a, what);
}

py::dict compare(const FloatArray& ours,
                 const FloatArray& ref,
                 const std::optional<FloatArray>& ours_variance,
                 const std::optional<FloatArray>& ref_variance,
                 int block,
                 double alpha,
                 double max_mean_rel_diff,
                 double max_rel_mse) {
    const Image a = to_image(ours, "ours"), b = to_image(ref, "ref");
    const std::optional<Image> va = optional_image(ours_variance, "ours_variance"),
                               vb = optional_image(ref_variance, "ref_variance");
    if (!(alpha > 0 && alpha < 1)) throw py::value_error("alpha: expected a probability in (0, 1)");
    CompareOptions options{block, alpha, max_mean_rel_diff, max_rel_mse};
    ImageComparison c;
    {
        py::gil_scoped_release release;
        c = compare_images(a, b, va ? &*va : nullptr, vb ? &*vb : nullptr, options);
    }
    py::dict d;
    d["pass"] = c.pass;
    d["mean_ours"] = c.mean_ours;
    d["mean_ref"] = c.mean_ref;
    d["mean_rel_diff"] = c.mean_rel_diff;
    d["rel_mse"] = c.rel_mse;
    d["z_tested"] = c.z_tested;
    d["tests"] = c.tests;
    d["failed"] = c.failed;
    d["level"] = c.level;
    d["image_z"] = py::make_tuple(c.image_z[0], c.image_z[1], c.image_z[2]);
    py::dict worst;
    worst["x"] = c.worst.x;
    worst["y"] = c.worst.y;
    worst["channel"] = c.worst.channel;
    worst["z"] = c.worst.z;
    worst["p"] = c.worst.p;
    d["worst"] = worst;
    d["block_z"] = c.z_tested ? py::object(to_array(std::move(c.block_z))) : py::none();
    return d;
}

}  // namespace

void bind_image(py::module_& m) {
    m.def(
        "write_image",
        [](const std::filesystem::path& path, const FloatArray& pixels, float exposure) {
            Image image = to_image(pixels, "pixels");
            py::gil_scoped_release release;
            WriteOptions options;
            options.exposure = exposure;
            write_image(path, image, options);
        },
        py::arg("path"), py::arg("pixels"), py::arg("exposure") = 0.0f,
        "Writes linear RGB (height, width, 3) or grey (height, width) by extension: .png/.jpg "
        "as 8-bit sRGB scaled by 2^exposure, .exr/.hdr/.pfm as float; atomically.");
    m.def(
        "read_image",
        [](const std::filesystem::path& path) {
            ImageData data;
            {
                py::gil_scoped_release release;
                data = read_image(path);
            }
            Image image;
            image.width = data.width;
            image.height = data.height;
            image.pixels = std::move(data.texels);
            return to_array(std::move(image));
        },
        py::arg("path"),
        "Reads an image as linear RGB float32 (height, width, 3): 8- and 16-bit files are "
        "decoded from sRGB, float files taken as they are.");
    m.def("compare", &compare, py::arg("ours"), py::arg("ref"), py::arg("ours_variance") = py::none(),
          py::arg("ref_variance") = py::none(), py::arg("block") = 8, py::arg("alpha") = 0.01,
          py::arg("max_mean_rel_diff") = 1e-2, py::arg("max_rel_mse") = 1e-2,
          "Compares an image with a reference as `wavetrace compare` does: image means, relative "
          "MSE and, given variances of the pixel means, per-block z-tests at level alpha (Sidak-"
          "corrected). Returns the numbers as a dict; 'pass' says whether they pass.");
}

}  // namespace wavetrace::python
