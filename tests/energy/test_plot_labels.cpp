// Issue 23 finding 8: gnuplot reads an explicit tic label as a format string, so a platform named
// "100% load" was drawn as "100 1.000000oad" and one named "%s" failed the whole plot.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "trn/energy/plots.hpp"

TEST(EnergyPlots, PercentInPlatformNamesIsDrawnLiterally) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("trn_plot_labels_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string image = (dir / "boxes.png").string();
    const std::vector<trn::energy::PlotSeries> series = {{"100% load", {1, 2, 3, 4}}, {"%s", {2, 3, 4, 5}}, {"%%d", {1, 1, 2, 3}}};
    ASSERT_NO_THROW(trn::energy::plot_boxes(series, image, "energy per frame (J)"));
    EXPECT_TRUE(std::filesystem::exists(image));
    std::string script;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".gp") {
            std::ifstream in(e.path());
            std::stringstream ss;
            ss << in.rdbuf();
            script = ss.str();
        }
    EXPECT_NE(script.find("100%% load"), std::string::npos) << script;
    EXPECT_NE(script.find("'%%%%d'"), std::string::npos) << script;
    std::filesystem::remove_all(dir);
}
