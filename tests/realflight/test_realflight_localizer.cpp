// Issue 24: one localization path. On the real flight (the 16 frames as an AIR folder), on every
// backend family this build has: `trnkit localize`, the library's whole-flight run, the online
// Localizer fed row by row (AirFrameReader: frames as taken, attitude, altitude, odometry
// increments) and docs/EMBEDDING.md's C and C++ programs give the same estimates: bit for bit
// between the library, the online Localizer, C and C++ (printed with 17 digits), and to the CSV's 10
// digits with the CLI. Skipped (visibly) without the shared data.
#include <cstdio>
#include <sstream>

#include "real_air_fixture.hpp"
#include "trn/error.hpp"
#include "trn/localize/air_frames.hpp"
#include "trn/localize/air_inputs.hpp"
#include "trn/localize/localization.hpp"
#include "trn/registry.hpp"

namespace trn::test {
namespace {

class RealFlightLocalizer : public RealAirFolder, public testing::WithParamInterface<const char*> {};

localize::LocalizerConfig cli_defaults() {  // what `trnkit localize --init-radius-m 50 --seed 1` sets
    localize::LocalizerConfig c;
    c.filter.init_radius_m = 50;
    c.filter.seed = 1;
    return c;
}

TEST_P(RealFlightLocalizer, CliLibraryOnlineCAndCxxGiveTheSameEstimates) {
    const std::string backend = GetParam();
    std::unique_ptr<Backend> batch_backend, online_backend;
    try {
        batch_backend = default_registry().create(backend);
        online_backend = default_registry().create(backend);
    } catch (const BackendUnavailable& e) {
        GTEST_SKIP() << backend << " NOT AVAILABLE: " << e.what();
    }
    // The CLI.
    const std::string out = dir_ + "/cli";
    const auto cli = run_trnkit("localize --dataset " + dir_ + " --map " + map() + " --rate 0.5 --no-plots --backend " + backend +
                                " --init-radius-m 50 --seed 1 --out " + out);
    ASSERT_EQ(cli.code, 0) << cli.output;
    const auto cli_rows = csv(out + "/localization.csv");

    // The library's whole-flight run.
    localize::AirInputOptions io;
    io.dataset = dir_, io.map = map();
    const localize::AirInputs in = localize::resolve_air_inputs(io);
    const double mpp = in.map.metres_per_pixel;
    localize::LocalizationSpec spec;
    spec.flight = localize::AirFolderFlight{dir_, in.camera, in.fps};
    spec.rate_hz = 0.5;
    spec.localizer = cli_defaults();
    const localize::LocalizationResult batch = localize::run_localization(spec, in.map.image.view(), mpp, *batch_backend);
    ASSERT_EQ(batch.rows.size(), 16u);
    ASSERT_EQ(cli_rows.size(), batch.rows.size());
    for (std::size_t i = 0; i < batch.rows.size(); ++i) {
        EXPECT_EQ(cli_rows[i].at("estimate_x"), ten_digits(batch.rows[i].estimate_x)) << "row " << i;
        EXPECT_EQ(cli_rows[i].at("estimate_y"), ten_digits(batch.rows[i].estimate_y)) << "row " << i;
        EXPECT_EQ(cli_rows[i].at("estimate_yaw"), ten_digits(batch.rows[i].estimate_yaw)) << "row " << i;
    }

    // The online Localizer, fed as a robot would feed it.
    localize::AirFrameReader reader(dir_);
    localize::AirFrame frame;
    std::unique_ptr<localize::Localizer> online;
    std::size_t step = 0;
    while (reader.next(frame)) {
        if (!online) {
            localize::LocalizerConfig c = cli_defaults();
            c.start_x = frame.truth_x, c.start_y = frame.truth_y, c.camera_hfov_deg = in.camera.hfov_deg;
            online = std::make_unique<localize::Localizer>(in.map.image.view(), mpp, *online_backend, c);
        }
        const localize::Estimate e = online->step(frame.observation());
        ASSERT_LT(step, batch.rows.size());
        EXPECT_EQ(e.x, batch.rows[step].estimate_x) << "step " << step;
        EXPECT_EQ(e.y, batch.rows[step].estimate_y) << "step " << step;
        EXPECT_EQ(e.yaw, batch.rows[step].estimate_yaw) << "step " << step;
        EXPECT_EQ(e.particles, batch.rows[step].particles) << "step " << step;
        ++step;
    }
    EXPECT_EQ(step, batch.rows.size());

    // docs/EMBEDDING.md's C and C++ programs.
    char args[64];
    std::snprintf(args, sizeof args, " %.17g %.17g ", mpp, in.camera.hfov_deg);
    for (const char* program : {TRN_LOCALIZE_FLIGHT_EXE, TRN_LOCALIZE_FLIGHT_CPP_EXE}) {
        const auto c = run_shell(std::string(program) + " " + dir_ + " " + map() + args + backend + " 2>&1");
        ASSERT_EQ(c.code, 0) << c.output;
        std::istringstream lines(c.output);
        std::size_t row = 0;
        for (std::string line; std::getline(lines, line);) {
            if (line.rfind("step ", 0) != 0) continue;
            std::istringstream cells(line.substr(5));
            std::size_t index;
            std::string x, y, yaw;
            cells >> index >> x >> y >> yaw;
            ASSERT_LT(row, batch.rows.size()) << line;
            EXPECT_EQ(index, row);
            EXPECT_EQ(std::strtod(x.c_str(), nullptr), batch.rows[row].estimate_x) << line;
            EXPECT_EQ(std::strtod(y.c_str(), nullptr), batch.rows[row].estimate_y) << line;
            EXPECT_EQ(std::strtod(yaw.c_str(), nullptr), batch.rows[row].estimate_yaw) << line;
            ++row;
        }
        EXPECT_EQ(row, batch.rows.size()) << c.output;
    }
    std::cout << backend << ": " << batch.rows.size() << " steps identical (CLI, library, online, C, C++); filter mean error "
              << batch.summary.filter_mean_error_m << " m\n";
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, RealFlightLocalizer, testing::Values("cpu-ref", "cpu", "opencl", "vulkan"),
                         [](const testing::TestParamInfo<const char*>& i) { return i.param[0] == 'c' && i.param[3] == '-' ? std::string("cpu_ref") : std::string(i.param); });

}  // namespace
}  // namespace trn::test
