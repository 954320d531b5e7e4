#include "cli_fixtures.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "../common/test_images.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::fuzz {
namespace fs = std::filesystem;
namespace {

void put(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

// A power log on the wall clock around the markers: 5 W idle, 8 W while a sync burst or frame runs.
std::string power_log_for(const energy::MarkerFile& m, std::string& t0, std::string& t1) {
    energy::PowerTrace tr;
    tr.format = "trnkit", tr.quantity = "power", tr.wall_clock = true;
    const double begin = m.rows.front().real_start_ns * 1e-9 - 0.2, end = m.rows.back().real_end_ns * 1e-9 + 0.2;
    for (double t = begin; t <= end; t += 0.002) {
        bool busy = false;
        for (const auto& r : m.rows)
            busy = busy || (r.kind != "idle" && t >= r.real_start_ns * 1e-9 && t < r.real_end_ns * 1e-9);
        tr.t.push_back(t), tr.w.push_back(busy ? 8.0 : 5.0);
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", begin + 0.1), t0 = buf;
    std::snprintf(buf, sizeof buf, "%.6f", end - 0.1), t1 = buf;
    return energy::format_trnkit_power(tr);
}

}  // namespace

Sandbox make_sandbox(const std::string& trnkit, const std::string& corpus_dir, const std::vector<std::string>& env, const RunLimits& limits) {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/trnkit-clifuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder from " + pattern);
    Sandbox s;
    s.root = pattern, s.fx = s.root + "/fx", s.run_dir = s.root + "/run", s.watch_log = s.root + "/writes.log";
    for (const char* d : {"fx", "run", "home", "tmp", "cache"}) fs::create_directories(s.root + "/" + d);
    const fs::path fx = s.fx;

    cv::imwrite((fx / "small.png").string(), trn::test::textured_image(64, 48, 3).mat());
    cv::imwrite((fx / "map.png").string(), trn::test::textured_image(240, 200, 1).mat());
    cv::imwrite((fx / "templ.png").string(), trn::test::textured_image(240, 200, 1).mat()(cv::Rect(100, 80, 40, 30)));
    put(fx / "corrupt.png", std::string("\x89PNG\r\n\x1a\n", 8) + "this is not a png");
    put(fx / "empty.txt", "");
    std::string garbage;
    for (unsigned i = 0, x = 12345; i < 2048; ++i) x = x * 1103515245u + 12345u, garbage += static_cast<char>(x >> 23);
    put(fx / "garbage.bin", garbage);
    put(fx / "poses.csv", "x,y,yaw,scale\n119.5,94.5,0,1\n60,60,0.5,1\n");
    put(fx / "a_dir/inside.txt", "a file inside a folder\n");
    put(fx / "sysfs/class/hwmon/hwmon0/name", "ina3221\n");
    put(fx / "sysfs/class/hwmon/hwmon0/in1_input", "5000\n");
    put(fx / "sysfs/class/hwmon/hwmon0/curr1_input", "400\n");
    // Stand-ins for the devices: a writer that replaces its destination by rename() replaces the
    // link here, where a run as root given /dev/null itself would replace the system's /dev/null.
    fs::create_symlink("/dev/full", fx / "dev-full");
    fs::create_symlink("/dev/null", fx / "dev-null");
    fs::create_symlink("/dev/zero", fx / "dev-zero");

    fs::copy_file(corpus_dir + "/markers/frames.csv", fx / "markers.csv");
    put(fx / "power.csv", power_log_for(energy::read_markers((fx / "markers.csv").string()), s.t0, s.t1));
    const auto made = [&](const std::vector<std::string>& args, const char* what) {
        std::vector<std::string> argv = {trnkit};
        argv.insert(argv.end(), args.begin(), args.end());
        const RunResult r = run_sandboxed(argv, s.fx, env, limits);
        if (r.exit_code != 0) std::printf("fixture %s not made (exit %d): %s\n", what, r.exit_code, r.err.c_str());
        return r.exit_code == 0;
    };
    if (!made({"energy", "integrate", "power.csv", "--markers", "markers.csv", "--json", "run.json"}, "run.json"))
        fs::copy_file(corpus_dir + "/run_report/run.json", fx / "run.json");
    made({"simulate", "--scenario", "FL-200", "--frames", "3", "--size-m", "400", "--out", "flight"}, "flight/ (AIR folder)");
    fs::copy(fx, s.root + "/fx-pristine", fs::copy_options::recursive | fs::copy_options::copy_symlinks);
    return s;
}

std::string fixture_fingerprint(const Sandbox& s) {
    std::ostringstream os;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(s.fx, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const auto st = it->symlink_status(ec);
        os << it->path().string() << ' ' << static_cast<int>(st.type());
        if (st.type() == fs::file_type::regular)
            os << ' ' << fs::file_size(it->path(), ec) << ' ' << fs::last_write_time(it->path(), ec).time_since_epoch().count();
        os << '\n';
    }
    return os.str();
}

void restore_fixtures(const Sandbox& s) {
    fs::remove_all(s.fx);
    fs::copy(s.root + "/fx-pristine", s.fx, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
}

}  // namespace trn::fuzz
