// `trnkit score`: NCC/CC/SSD of every pose in a CSV against one camera template, as CSV.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/image_io.hpp"
#include "trn/io/pose_csv.hpp"
#include "trn/registry.hpp"

namespace trn::cli {
namespace {

// "dense", "random:FRACTION[:SEED]"
Sampling parse_sampling(const std::string& text) {
    if (text == "dense") return Sampling::dense();
    if (text.rfind("random:", 0) == 0) {
        std::stringstream ss(text.substr(7));
        double fraction = 0;
        unsigned long long seed = 1;
        char colon = 0;
        if (!(ss >> fraction) || ((ss >> colon) && (colon != ':' || !(ss >> seed))) || !ss.eof())
            throw Error("--sampling '" + text + "': expected dense or random:FRACTION[:SEED]");
        return Sampling::random(fraction, seed);
    }
    throw Error("--sampling '" + text + "': expected dense or random:FRACTION[:SEED]");
}

}  // namespace

void add_score_command(CLI::App& app) {
    struct Args {
        std::string map, templ, poses, backend = "cpu", sampling = "dense", out;
        double min_valid = 0.9;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("score", "Score particle poses against a camera template on a map (CSV out)");
    cmd->add_option("--map", a->map, "Map image (grey or colour)")->required();
    cmd->add_option("--template", a->templ, "Camera frame / template image")->required();
    cmd->add_option("--poses", a->poses, "CSV with x,y,yaw,scale per line (map pixels, radians)")->required();
    cmd->add_option("-b,--backend", a->backend, "Backend: cpu-ref, cpu, opencl[:N|:name], vulkan[:N|:name]")->capture_default_str();
    cmd->add_option("--sampling", a->sampling, "dense or random:FRACTION[:SEED]")->capture_default_str();
    cmd->add_option("--min-valid", a->min_valid, "Smallest share of samples inside the map for a valid particle")->capture_default_str();
    cmd->add_option("-o,--out", a->out, "Output CSV (default: standard output)");
    cmd->callback([a] {
        ScoreOptions options;
        options.sampling = parse_sampling(a->sampling);
        options.min_valid_fraction = a->min_valid;
        const GrayImage map = load_gray(a->map);
        const GrayImage templ = load_gray(a->templ);
        const std::vector<Pose> poses = read_poses_csv(a->poses);
        if (!a->out.empty()) io::check_output_file(a->out, "--out");
        auto backend = default_registry().create(a->backend);
        const MapHandle handle = backend->upload_map(map.view());
        std::vector<ParticleScore> scores(poses.size());
        PhaseTimes t;
        backend->score(handle, templ.view(), poses, options, scores, &t);

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
