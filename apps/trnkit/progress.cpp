#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace trn::cli {

void draw_progress(std::size_t done, std::size_t total, const char* unit) {
    static const bool terminal = ::isatty(STDERR_FILENO) == 1;
    if (total == 0) {
        if (done % 50 == 0) std::fprintf(stderr, terminal ? "\r%zu %s" : "%zu %s\n", done, unit);
        return;
    }
    done = std::min(done, total);
    const std::size_t step = terminal ? 100 : 10;  // redraws over the whole run
    if (done < total && done > 0 && (step * done / total) == (step * (done - 1) / total)) return;
    const int percent = static_cast<int>(100 * done / total);
    if (terminal) {
        const int width = 40, filled = static_cast<int>(width * done / total);
        std::fprintf(stderr, "\r[%s%s] %3d%% %zu/%zu %s", std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
                     percent, done, total, unit);
        if (done == total) std::fputc('\n', stderr);
    } else {
        std::fprintf(stderr, "%3d%% %zu/%zu %s\n", percent, done, total, unit);
    }
}

}  // namespace trn::cli
