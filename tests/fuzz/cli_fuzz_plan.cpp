#include "cli_fuzz_plan.hpp"

namespace trn::fuzz {

std::map<std::string, CommandPlan> command_plans(const std::string& fx, const std::string& t0, const std::string& t1) {
    std::map<std::string, CommandPlan> p;
    p["devices"] = {{}, {}, {}, 1};
    p["sobel"] = {{{"image", fx + "/small.png"}, {"--backend", "cpu"}, {"--out", "out"}}, {}, {}, 3};
    p["score"] = {{{"--map", fx + "/map.png"}, {"--template", fx + "/templ.png"}, {"--poses", fx + "/poses.csv"}, {"--backend", "cpu"},
                   {"--out", "scores.csv"}},
                  {}, {}, 4};
    p["demo"] = {{{"--backend", "cpu"}, {"--distance-km", "0.05"}, {"--rate", "2"}, {"--template-width", "32"}, {"--no-plots", ""},
                  {"--out", "demo"}},
                 {"--distance-km", "--rate", "--template-width", "--map-year", "--flight-year", "--scenario", "--sparse", "--backend"}, {}, 1};
    p["frames"] = {{{"--kernel", "sobel"}, {"--size", "480p"}, {"--particles", "10"}, {"--backend", "cpu"}, {"--frames", "2"},
                    {"--idle-ms", "1"}, {"--lead-idle-ms", "1"}, {"--sync-unit-ms", "1"}, {"--out", "markers.csv"}},
                   {"--frames", "--idle-ms", "--lead-idle-ms", "--sync-unit-ms", "--particles", "--size", "--kernel", "--backend"}, {}, 3};
    p["energy inspect"] = {{{"log", fx + "/power.csv"}}, {}, {}, 3};
    p["energy integrate-span"] = {{{"log", fx + "/power.csv"}, {"--start", t0}, {"--end", t1}}, {}, {}, 3};
    p["energy integrate"] = {{{"log", fx + "/power.csv"}, {"--markers", fx + "/markers.csv"}, {"--json", "run.json"}, {"--csv", "frames.csv"}},
                             {"--search", "--plot"}, {}, 5};
    p["energy compare"] = {{{"runs", fx + "/run.json"}, {"--out", "compare"}, {"--no-plots", ""}}, {}, {}, 3};
    p["energy sample"] = {{{"--sysfs-root", fx + "/sysfs"}, {"--source", "hwmon:ina3221:1"}, {"--duration-s", "0.05"}, {"--period-ms", "10"},
                           {"--out", "power.csv"}},
                          {"--duration-s", "--period-ms"}, {}, 2};
    p["energy bench"] = {{{"--sysfs-root", fx + "/sysfs"}, {"--source", "hwmon:ina3221:1"}, {"--backend", "cpu"}, {"--size", "480p"}, {"--frames", "2"},
                          {"--idle-ms", "1"}, {"--lead-idle-ms", "5"}, {"--period-ms", "1"}, {"--min-samples", "0"}, {"--no-plots", ""}, {"--out", "bench"}},
                         {"--frames", "--repeat", "--idle-ms", "--lead-idle-ms", "--particles", "--size", "--kernel", "--backend"},
                         {},
                         2};
    p["simulate"] = {{{"--scenario", "FL-200"}, {"--frames", "2"}, {"--size-m", "400"}, {"--out", "flight"}},
                     {"--frames", "--seconds", "--size-m", "--map-year", "--base-year", "--fov", "--scenario", "--map", "--mpp", "--procedural"},
                     {}, 3};
    p["check"] = {{{"--particles", "8"}, {"--map", fx + "/small.png"}}, {"--particles", "--map"}, {}, 1};
    p["localize"] = {{{"--dataset", fx + "/flight"}, {"--backend", "cpu"}, {"--min-particles", "10"}, {"--max-particles", "40"},
                      {"--particles", "40"}, {"--template-width", "32"}, {"--no-plots", ""}, {"--out", "localize"}},
                     {"--particles", "--min-particles", "--max-particles", "--rate", "--template-width", "--map", "--mpp", "--sampling", "--backend"},
                     {}, 3};
    // The fixture folder holds no photos: every run ends in a refusal naming a file or an option.
    p["import-photos"] = {{{"DIR", fx + "/a_dir"}, {"--out", "air"}, {"--altitude-agl", "60"}, {"--width", "32"}},
                          {"--width"}, {}, 1};
    p["experiment"] = {{{"name", "metrics"}, {"--quick", ""}, {"--list-jobs", ""}, {"--out", "experiment"}}, {}, {"--list-jobs"}, 1};
    return p;
}

NastyValues nasty_values(const std::string& fx, bool long_run) {
    NastyValues v;
    // numbers at and past the edges
    v.numbers = {
        "-1", "0", "1", "2", "0.5", "-0.5", "nan", "-nan", "inf", "-inf", "1e300", "-1e300", "1e-300", "99999999999999999999",
        "2147483647", "2147483648", "-2147483649", "4294967296", "9223372036854775807", "18446744073709551616", "0x10", "1,5", "3e",
        "--1", "1e", "+", "", " 1", "1 ", "1.5.5"};
    // text that must stay text
    v.texts = {
        "", " ", "\n", "a\nb", "line1\nline2\n", "\t", "%s%s%s%n", "$(touch PWNED)", "`touch PWNED`", "; touch PWNED",
        "| touch PWNED > PWNED", "' \"", std::string(4096, 'x'), "-", "--", "--help", "-h", "=", "key=value", "rail=sum", "=x", "x=",
        "columns=a,b", "\xff\xfe", "\xc3\xa9t\xc3\xa9"};
    // words the options know, right and wrong
    v.words = {
        "cpu", "cpu-ref", "opencl", "opencl:99", "opencl:-1", "vulkan", "vulkan:nonexistent", "fastest", "cuda", "auto", "sobel", "ncc",
        "480p", "1080p", "99999p", "0p", "FL-200", "UC-300", "XX-999", "forest", "urban", "linear", "softmax", "rectifying:0.5",
        "rectifying:-1", "logistic:0.2", "logistic:nan", "kld", "importance", "rejection", "random:0.5", "random:2", "random:0.5:-1",
        "dense", "net", "gross", "real", "mono", "metrics", "conversion", "0/1", "1/0", "2/2", "-1/3", "hwmon:ina3221:1",
        "hwmon:ina3221:99", "rapl:package-0", "trnkit", "tegrastats", "pmt", "nvidia-smi"};
    // files: inputs of every kind, folders, and outputs that cannot be written
    v.files = {
        fx + "/small.png", fx + "/map.png", fx + "/templ.png", fx + "/corrupt.png", fx + "/empty.txt", fx + "/garbage.bin",
        fx + "/poses.csv", fx + "/markers.csv", fx + "/power.csv", fx + "/run.json", fx + "/flight", fx + "/flight/metadata.csv",
        fx + "/flight/flight.json", fx + "/sysfs", fx + "/a_dir", fx + "/missing.png", fx + "/empty.txt/below", fx + "/dev-full",
        fx + "/dev-null", fx + "/dev-full/below", ".", "..", "out/new.png", "deep/a/b/c/out", "newdir/",
    };
    if (long_run) v.files.push_back(fx + "/dev-zero");  // endless input: readers should stop at a size limit
    return v;
}

std::vector<std::string> NastyValues::all() const {
    std::vector<std::string> a = numbers;
    for (const auto* part : {&texts, &words, &files}) a.insert(a.end(), part->begin(), part->end());
    return a;
}

bool is_output_option(const std::string& name) {
    return name == "--out" || name == "-o" || name == "--json" || name == "--csv" || name == "--plot";
}

}  // namespace trn::fuzz
