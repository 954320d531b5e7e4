#include "backend_env.hpp"

#include <cstdlib>

#include "trn/backend_option_text.hpp"

namespace trn::cli {

BackendOptions backend_options_from_environment() {
    return backend_options_from_variables([](const char* name) { return std::getenv(name); });
}

}  // namespace trn::cli
