// Writes the sample images of docs/SIMULATOR.md: procedural maps of both styles, an aged map and
// camera frames. Usage: trn_sim_samples OUT_DIR [.jpg|.png] or trn_sim_samples --time EDGE_M. Not a test; kept so the samples can be remade.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "trn/sim/map_ageing.hpp"
#include "trn/sim/procedural_map.hpp"
#include "trn/sim/render.hpp"

using namespace trn::sim;

int main(int argc, char** argv) {
    if (argc > 2 && std::string(argv[1]) == "--time") {  // trn_sim_samples --time EDGE_M: generation speed
        for (TerrainStyle style : {TerrainStyle::Forest, TerrainStyle::Urban}) {
            ProceduralMapOptions o;
            o.style = style;
            o.width_m = o.height_m = std::stod(argv[2]);
            const auto t0 = std::chrono::steady_clock::now();
            const Map map = generate_procedural_map(o);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::printf("%s %dx%d px: %.2f s (%.1f Mpx/s)\n", to_string(style), map.image.width, map.image.height, s,
                        map.image.width * double(map.image.height) / 1e6 / s);
        }
        return 0;
    }
    const std::string out = argc > 1 ? argv[1] : ".";
    const std::string ext = argc > 2 ? argv[2] : ".jpg";  // .png for lossless samples
    std::filesystem::create_directories(out);
    for (TerrainStyle style : {TerrainStyle::Forest, TerrainStyle::Urban}) {
        for (int year : {2008, 2014}) {
            ProceduralMapOptions o;
            o.style = style;
            o.seed = 7;
            o.year = year;
            o.width_m = o.height_m = 1280;  // overview: 1.28 km at 2 m/px
            o.metres_per_pixel = 2;
            const auto t0 = std::chrono::steady_clock::now();
            const Map map = generate_procedural_map(o);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::printf("%s %d: %dx%d in %.2f s\n", to_string(style), year, map.image.width, map.image.height, s);
            const std::string name = out + "/procedural_" + to_string(style) + "_" + std::to_string(year);
            trn::save_gray(name + ext, map.image.view());
            if (year != 2008) continue;
            // A closer look: 160 m at 0.25 m/px.
            o.metres_per_pixel = 0.25;
            const trn::GrayImage zoom = generate_procedural_region(o, 1000, 1000, 640, 640);
            trn::save_gray(name + "_zoom" + ext, zoom.view());
            // A camera frame at 200 m over the same place, from the 1 m/px map.
            o.metres_per_pixel = 1;
            o.width_m = o.height_m = 800;
            const Map fine = generate_procedural_map(o);
            const CameraPose pose{400, 400, 200, 0.5, 0, 0};
            trn::save_gray(out + "/frame_" + to_string(style) + ext, render_frame(fine, Camera{}, pose).view());
        }
    }
    return 0;
}
