#pragma once
// The one progress display of the CLI: a bar redrawn in place on a terminal; on a pipe or log
// file (CI, `| tee`) a plain line every 10 % instead of hundreds of carriage returns.
#include <cstddef>

namespace trn::cli {

// `total` == 0 means unknown: a running count. `unit` names what is counted ("steps", "frames").
void draw_progress(std::size_t done, std::size_t total, const char* unit);

}  // namespace trn::cli
