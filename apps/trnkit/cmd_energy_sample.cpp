// `trnkit energy sample --source hwmon:ina3221:1 --period-ms 10 --duration-s 30 -o power.log`:
// live power from Linux hwmon, RAPL powercap or NVML (power_sampler.hpp), written in trnkit's power-log format on
// CLOCK_REALTIME so markers from `trnkit frames` line up with the same clock.
#include <cstdio>

#include "commands.hpp"
#include "options.hpp"
#include "write_text.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/power_sampler.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

namespace trn::cli {

void add_energy_sample_command(CLI::App* energy) {
    struct Args {
        std::string source, out, root = "/sys", nvml_lib = "libnvidia-ml.so.1", vcgencmd = "/usr/bin/vcgencmd";
        double period_ms = 10, duration_s = 10;
        bool list = false;
    };
    auto a = std::make_shared<Args>();
    auto* c = energy->add_subcommand("sample", "Sample power live from hwmon (ina2xx, ina3221), RAPL powercap or NVML into a trnkit power log");
    c->add_option("--source", a->source, "hwmon:NAME[:CHANNEL], rapl:NAME, nvml:INDEX[:power|:energy] or pmic:vcgencmd (see --list)");
    c->add_flag("--list", a->list, "List the power sources found and exit");
    c->add_option("--period-ms", a->period_ms, "Polling period (ms)")->capture_default_str()->check(real_in(0, 60000, Open::low));
    c->add_option("--duration-s", a->duration_s, "How long to sample (s)")->capture_default_str()->check(real_in(0, 604800, Open::low));
    c->add_option("-o,--out", a->out, "Power log to write (default: standard output)");
    c->add_option("--sysfs-root", a->root, "sysfs root (for tests and containers)")->capture_default_str();
    c->add_option("--nvml-lib", a->nvml_lib, "NVML library to dlopen for nvml sources")->capture_default_str();
    c->add_option("--vcgencmd", a->vcgencmd, "vcgencmd program the pmic:vcgencmd source runs (absolute path)")->capture_default_str();
    c->callback([a] {
        energy::SamplerOptions so;
        so.sysfs_root = a->root, so.nvml_library = a->nvml_lib, so.vcgencmd = a->vcgencmd;
        if (a->list) {
            const auto all = energy::list_power_sources(so);
            if (all.empty() || (all.size() == 1 && all.back().rfind("nvml: not available", 0) == 0))
                std::printf("no hwmon power sensor or RAPL powercap zone under %s\n", a->root.c_str());
            for (const auto& s : all) std::printf("%s\n", s.c_str());
            return;
        }
        if (a->source.empty()) throw Error("energy sample: give --source (or --list to see the sources)");
        const auto sampler = energy::make_power_sampler(a->source, so);
        if (!a->out.empty()) io::check_output_file(a->out, "--out");  // before sampling for --duration-s
        const auto trace = energy::sample_for(*sampler, a->period_ms / 1000, a->duration_s, energy::SampleClock::Realtime);
        const std::string text = energy::format_trnkit_power(trace);
        if (a->out.empty()) {
            std::fputs(text.c_str(), stdout);  // checked at exit (main.cpp)
            return;
        }
        write_text_file(a->out, text);
        std::fprintf(stderr, "%s: %zu samples -> %s\n", sampler->describe().c_str(), trace.size(), a->out.c_str());
    });
}

}  // namespace trn::cli
