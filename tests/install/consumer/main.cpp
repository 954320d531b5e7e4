// Scores one particle through the installed library: prints the NCC of an exact crop (1.000).
#include <cstdio>
#include <vector>

#include <trn/registry.hpp>

int main() {
    std::vector<unsigned char> map(64 * 64);
    for (int i = 0; i < 64 * 64; ++i) map[i] = static_cast<unsigned char>((i * 37 + (i / 64) * 11) % 251);
    std::vector<unsigned char> templ(16 * 16);
    for (int v = 0; v < 16; ++v)
        for (int u = 0; u < 16; ++u) templ[v * 16 + u] = map[(20 + v) * 64 + 10 + u];
    auto backend = trn::default_registry().create("cpu");
    const trn::MapHandle h = backend->upload_map({map.data(), 64, 64, 64});
    const trn::Pose pose{10 + 7.5f, 20 + 7.5f, 0, 1};
    trn::ParticleScore score;
    backend->score(h, trn::GrayView{templ.data(), 16, 16, 16}, {&pose, 1}, {}, {&score, 1});
    std::printf("ncc %.3f\n", score.ncc);
    return score.valid() && score.ncc > 0.999f ? 0 : 1;
}
