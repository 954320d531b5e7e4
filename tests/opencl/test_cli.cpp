// `trnkit score` and `trnkit sobel` with --backend opencl, end to end through real files, checked
// against the same commands on the cpu backend.
#include <fstream>
#include <iterator>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "opencl_test_support.hpp"

namespace trn::test {
namespace {

// The test links the core's objects only (not trnkit::io), so it writes its PNGs with OpenCV.
void save_gray(const std::string& path, GrayView image) {
    const cv::Mat m(image.height, image.width, CV_8UC1, const_cast<std::uint8_t*>(image.data), std::size_t(image.stride));
    ASSERT_TRUE(cv::imwrite(path, m)) << path;
}

int run(const std::string& command) { return std::system((command + " 2>/dev/null").c_str()); }

std::string read_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct Row {
    double ncc, cc, ssd;
    unsigned valid, flags;
};

std::vector<Row> read_scores(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::string line;
    std::getline(in, line);  // header
    std::vector<Row> rows;
    while (std::getline(in, line)) {
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream ss(line);
        double index, x, y, yaw, scale;
        Row r{};
        ss >> index >> x >> y >> yaw >> scale >> r.ncc >> r.cc >> r.ssd >> r.valid >> r.flags;
        if (ss) rows.push_back(r);
    }
    return rows;
}

class OpenClCli : public testing::Test {
protected:
    void SetUp() override {
        std::string why;
        if (opencl::enumerate_devices(why).empty()) GTEST_SKIP() << "no OpenCL device: " << why;
        const int mw = 300, mh = 240, tw = 64, th = 48, tx = 100, ty = 80;
        map_ = textured_pixels(mw, mh, 3);
        std::vector<std::uint8_t> templ(std::size_t(tw) * th);
        for (int y = 0; y < th; ++y)
            for (int x = 0; x < tw; ++x) templ[std::size_t(y) * tw + x] = map_[std::size_t(y + ty) * mw + x + tx];
        save_gray((dir_.path() / "map.png").string(), {map_.data(), mw, mh, mw});
        save_gray((dir_.path() / "templ.png").string(), {templ.data(), tw, th, tw});
        std::ofstream poses(dir_.path() / "poses.csv");
        poses << "x,y,yaw,scale\n";
        poses << tx + 31.5 << "," << ty + 23.5 << ",0,1\n";  // the crop's own pose: ncc 1
        for (int i = 1; i < 40; ++i) poses << 40 + 5.3 * i << "," << 30 + 4.1 * i << "," << 0.15 * i << "," << 0.7 + 0.02 * i << "\n";
        poses << "5,5,0.3,1.5\n";  // mostly outside the map: too few samples
    }
    std::string path(const char* name) const { return (dir_.path() / name).string(); }

    TempDir dir_;
    std::vector<std::uint8_t> map_;
};

TEST_F(OpenClCli, ScoreMatchesTheCpuBackend) {
    for (const char* backend : {"cpu", "opencl"})
        ASSERT_EQ(run(std::string(TRNKIT_EXE) + " score --map " + path("map.png") + " --template " + path("templ.png") +
                      " --poses " + path("poses.csv") + " --backend " + backend + " --out " + path(backend) + ".csv"),
                  0)
            << "trnkit score --backend " << backend;
    const auto cpu = read_scores(path("cpu") + ".csv"), ocl = read_scores(path("opencl") + ".csv");
    ASSERT_EQ(cpu.size(), 41u);
    ASSERT_EQ(ocl.size(), cpu.size());
    EXPECT_NEAR(ocl[0].ncc, 1.0, 1e-4);
    EXPECT_NE(ocl.back().flags, 0u);
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        EXPECT_EQ(ocl[i].ncc, cpu[i].ncc) << i;  // exact scoring: the same printed digits
        EXPECT_EQ(ocl[i].cc, cpu[i].cc) << i;
        EXPECT_EQ(ocl[i].ssd, cpu[i].ssd) << i;
        EXPECT_EQ(ocl[i].valid, cpu[i].valid) << i;
        EXPECT_EQ(ocl[i].flags, cpu[i].flags) << i;
    }
}

TEST_F(OpenClCli, SobelWritesTheSameGradientsAsTheCpuBackend) {
    for (const char* backend : {"cpu", "opencl"})
        ASSERT_EQ(run(std::string(TRNKIT_EXE) + " sobel " + path("map.png") + " --backend " + backend + " --out " + path(backend)), 0)
            << "trnkit sobel --backend " << backend;
    for (const char* file : {"gx.png", "gy.png"}) {
        const std::string cpu = read_bytes(dir_.path() / "cpu" / file), ocl = read_bytes(dir_.path() / "opencl" / file);
        ASSERT_FALSE(cpu.empty()) << file;
        EXPECT_TRUE(cpu == ocl) << file << " differs between --backend cpu and --backend opencl";
    }
}

}  // namespace
}  // namespace trn::test
