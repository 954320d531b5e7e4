// `trnkit sobel IMAGE --backend B --out DIR`: Gx and Gy of an image as PNGs (128 = zero).
#include <filesystem>
#include <iostream>
#include <vector>

#include "backend_env.hpp"
#include "commands.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/image_io.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/limits.hpp"
#include "trn/registry.hpp"

namespace trn::cli {

void add_sobel_command(CLI::App& app) {
    struct Args {
        std::string image, backend = "cpu", out = ".";
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("sobel", "3x3 Sobel gradients of an image, written as gx.png and gy.png");
    cmd->add_option("image", a->image, "Input image (any format OpenCV reads; colour is converted to grey)")->required();
    cmd->add_option("-b,--backend", a->backend, "Backend: cpu-ref, cpu, opencl[:N|:name], vulkan[:N|:name]")->capture_default_str();
    cmd->add_option("-o,--out", a->out, "Output folder (created if missing)")->capture_default_str();
    cmd->callback([a] {
        const GrayImage img = load_gray(a->image);
        // Two fixed file names, each replaced whole: checked like single output files, and the
        // folder (often ".") is not claimed as sobel's own.
        const std::string px = a->out + "/gx.png", py = a->out + "/gy.png";
        io::check_output_folder(a->out, "sobel", /*force=*/true);
        if (std::filesystem::exists(a->out)) io::check_output_file(px, "--out"), io::check_output_file(py, "--out");
        limits::check_image(a->image + ": Sobel of image", img.width, img.height, limits::kMaxMapPixels, limits::kSobelBytesPerPixel);
        auto backend = default_registry().create(a->backend, backend_options_from_environment());
        std::vector<std::int16_t> gx(img.pixels.size()), gy(img.pixels.size());
        PhaseTimes t;
        backend->sobel(img.view(), {gx.data(), img.width, img.height, img.width}, {gy.data(), img.width, img.height, img.width}, &t);
        std::error_code ec;
        std::filesystem::create_directories(a->out, ec);
        if (ec) throw Error(a->out + ": cannot create folder (" + ec.message() + ")");
        save_gradient(px, {gx.data(), img.width, img.height, img.width});
        save_gradient(py, {gy.data(), img.width, img.height, img.width});
        std::cout << backend->info().name << ": " << img.width << "x" << img.height << " upload " << t.upload_ms
                  << " ms, execute " << t.execute_ms << " ms, download " << t.download_ms << " ms\n"
                  << px << "\n" << py << "\n";
    });
}

}  // namespace trn::cli
