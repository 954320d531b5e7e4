// `trnkit frames`: the dissertation's Algorithm 3 as a tool. Runs K frames of Sobel (480p, 720p,
// 1080p) or NCC scoring (N particles) on one backend, with idle gaps and a sync pattern first,
// and writes the marker file `trnkit energy integrate` reads.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "backend_env.hpp"
#include "commands.hpp"
#include "frame_workload.hpp"
#include "options.hpp"
#include "trn/energy/frame_runner.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/limits.hpp"
#include "trn/registry.hpp"

namespace trn::cli {

void add_frames_command(CLI::App& app) {
    struct Args {
        std::string kernel = "sobel", size = "480p", backend = "cpu", out = "frames.csv";
        int frames = 100, particles = 1000;
        double idle_ms = 100, lead_idle_ms = 1000, sync_unit_ms = 100;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("frames", "Run a kernel K times with idle gaps and a sync pattern, writing frame markers (energy studies)");
    cmd->add_option("--kernel", a->kernel, "sobel or ncc")->capture_default_str()->check(CLI::IsMember({"sobel", "ncc"}));
    cmd->add_option("--size", a->size, "Sobel image size: 480p, 720p or 1080p")->capture_default_str()->check(CLI::IsMember(kFrameSizeNames));
    cmd->add_option("--particles", a->particles, "NCC: particles scored per frame")->capture_default_str()->transform(whole_in(1, kMaxParticles));
    cmd->add_option("-b,--backend", a->backend, "Backend: cpu-ref, cpu, opencl[:N|:name], vulkan[:N|:name]")->capture_default_str();
    cmd->add_option("-k,--frames", a->frames, "Frames (K)")->capture_default_str()->transform(whole_in(1, 1000000));
    cmd->add_option("--idle-ms", a->idle_ms, "Idle gap after each frame (ms)")->capture_default_str()->check(real_in(0, 600000));
    cmd->add_option("--lead-idle-ms", a->lead_idle_ms, "Idle before the sync pattern and after the last frame (ms)")
        ->capture_default_str()
        ->check(real_in(0, 600000));
    cmd->add_option("--sync-unit-ms", a->sync_unit_ms, "Sync pattern unit u: bursts of 3u,1u,2u (ms; 0 = none)")
        ->capture_default_str()
        ->check(real_in(0, 60000));
    cmd->add_option("-o,--out", a->out, "Marker file to write")->capture_default_str();
    cmd->callback([a] {
        io::check_output_file(a->out, "--out");  // before the run, which takes minutes
        limits::check_count("--particles", a->particles, limits::kMaxParticles, limits::kParticleBytes);
        auto backend = default_registry().create(a->backend, backend_options_from_environment());
        energy::FrameRunConfig cfg;
        cfg.frames = a->frames, cfg.idle_s = a->idle_ms / 1000, cfg.lead_idle_s = a->lead_idle_ms / 1000, cfg.sync_unit_s = a->sync_unit_ms / 1000;
        FrameWorkload work = make_frame_workload(*backend, a->kernel, a->size, a->particles);
        cfg.meta = work.meta;
        const energy::MarkerFile markers = energy::run_frames(work.kernel, cfg);
        io::write_file_atomic(a->out, energy::format_markers(markers));
        std::size_t frames = 0;
        double exec = 0;
        for (const auto& r : markers.rows)
            if (r.kind == "frame") ++frames, exec += r.exec_ms;
        std::printf("%s: %zu frames of %s on %s, mean exec %.3f ms -> %s\n", a->backend.c_str(), frames, a->kernel.c_str(),
                    backend->info().name.c_str(), exec / std::max<std::size_t>(frames, 1), a->out.c_str());
    });
}

}  // namespace trn::cli
