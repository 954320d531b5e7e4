// `trnkit score`: NCC/CC/SSD of every pose in a CSV against one camera template, as CSV.
#include <cstdio>
#include <iostream>
#include <optional>
#include <string_view>

#include "backend_env.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/image_io.hpp"
#include "trn/io/map_pixels.hpp"
#include "trn/io/pose_csv.hpp"
#include "trn/parse_number.hpp"
#include "trn/registry.hpp"

namespace trn::cli {
namespace {

// "dense", "random:FRACTION[:SEED]": FRACTION a finite share in (0, 1], SEED plain decimal digits
// (parsed strictly, so "random:nan" or a seed of -1 is refused instead of read as something else).
Sampling parse_sampling(const std::string& text) {
    if (text == "dense") return Sampling::dense();
    const std::string why = "--sampling '" + text + "': expected dense or random:FRACTION[:SEED] with FRACTION in (0, 1]";
    if (text.rfind("random:", 0) != 0) throw Error(why);
    const std::string_view rest = std::string_view(text).substr(7);
    const std::size_t colon = rest.find(':');
    const auto fraction = parse_finite_real(rest.substr(0, colon));
    const auto seed = colon == std::string_view::npos ? std::optional<std::uint64_t>(1) : parse_whole_number(rest.substr(colon + 1));
    if (!fraction || !(*fraction > 0 && *fraction <= 1) || !seed) throw Error(why);
    return Sampling::random(*fraction, *seed);
}

}  // namespace

void add_score_command(CLI::App& app) {
    struct Args {
        std::string map, templ, poses, backend = "cpu", sampling = "dense", out;
        double min_valid = 0.9;
        int nodata = -1;  // -1: only the map's alpha
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("score", "Score particle poses against a camera template on a map (CSV out)");
    cmd->add_option("--map", a->map, "Map image (grey or colour)")->required();
    cmd->add_option("--nodata", a->nodata,
                    "Map grey level (0..255) marking no-data where every colour channel has it; transparent map pixels are "
                    "no-data anyway. Samples on no-data are left out, as samples off the map are")
        ->transform(whole_in(0, 255));
    cmd->add_option("--template", a->templ, "Camera frame / template image")->required();
    cmd->add_option("--poses", a->poses, "CSV with x,y,yaw,scale per line (map pixels, radians)")->required();
    cmd->add_option("-b,--backend", a->backend, "Backend: cpu-ref, cpu, opencl[:N|:name], vulkan[:N|:name]")->capture_default_str();
    cmd->add_option("--sampling", a->sampling, "dense or random:FRACTION[:SEED]")->capture_default_str();
    cmd->add_option("--min-valid", a->min_valid, "Smallest share of samples inside the map for a valid particle")
        ->capture_default_str()
        ->check(real_in(0, 1));
    cmd->add_option("-o,--out", a->out, "Output CSV (default: standard output)");
    cmd->callback([a] {
        // Never the output over an input: `--poses X -o X` would replace the poses with their scores.
        if (!a->out.empty()) io::check_output_is_not_input(a->out, "--out", {{"--map", a->map}, {"--template", a->templ}, {"--poses", a->poses}});
        ScoreOptions options;
        options.sampling = parse_sampling(a->sampling);
        options.min_valid_fraction = a->min_valid;
        // Pixels and no-data as localize reads them (a GeoTIFF's mask and nodata value too).
        const io::MapPixels map_pixels = io::load_map_pixels(a->map, a->nodata >= 0 ? std::optional<int>(a->nodata) : std::nullopt);
        const GrayImage& map = map_pixels.image;
        const GrayImage& valid = map_pixels.valid;
        const GrayImage templ = load_gray(a->templ);
        const std::vector<Pose> poses = read_poses_csv(a->poses);
        if (poses.empty()) throw Error(a->poses + ": no poses to score");
        if (!a->out.empty()) io::check_output_file(a->out, "--out");
        auto backend = default_registry().create(a->backend, backend_options_from_environment());
        std::vector<ParticleScore> scores(poses.size());
        PhaseTimes t;
        try {
            const MapHandle handle = backend->upload_map(map.view(), validity_view(valid));
            backend->score(handle, templ.view(), poses, options, scores, &t);
        } catch (const BackendUnavailable&) {
            throw;
        } catch (const Error& e) {  // the library names poses by index and images by role; name the files
            throw Error("--map " + a->map + ", --template " + a->templ + ", --poses " + a->poses + ": " + e.what());
        }

        std::string csv = "index,x,y,yaw,scale,ncc,cc,ssd,valid_samples,flags\n";
        char buf[256];
        for (std::size_t i = 0; i < poses.size(); ++i) {
            const Pose& p = poses[i];
            const ParticleScore& s = scores[i];
            std::snprintf(buf, sizeof buf, "%zu,%.9g,%.9g,%.9g,%.9g,%.7f,%.7f,%.7f,%u,%u\n", i, p.x, p.y, p.yaw, p.scale, s.ncc,
                          s.cc, s.ssd, s.valid_samples, s.flags);
            csv += buf;
        }
        if (a->out.empty()) std::cout << csv;  // checked at exit (main.cpp)
        else io::write_file_atomic(a->out, csv);
        std::cerr << backend->info().name << ": " << poses.size() << " poses, execute " << t.execute_ms << " ms\n";
    });
}

}  // namespace trn::cli
