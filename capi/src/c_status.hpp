#pragma once
// The boundary of the C API: every entry point runs its body through guarded(), which turns each
// C++ exception into a trn_status and this thread's trn_last_error() message, so none crosses into C.
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "trn/trnkit.h"

namespace trn::capi {

// A C-level argument the caller got wrong (null pointer, negative size): TRN_ERR_INVALID_ARGUMENT.
class InvalidArgument : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// Throws InvalidArgument "<what> is NULL" when p is null.
inline void require_pointer(const void* p, const char* what) {
    if (p == nullptr) throw InvalidArgument(std::string(what) + " is NULL");
}

// A C size_t count as the signed count trn::limits checks (saturated, so 2^64-1 stays huge).
inline std::int64_t as_count(std::size_t n) {
    return n > static_cast<std::size_t>(std::numeric_limits<std::int64_t>::max()) ? std::numeric_limits<std::int64_t>::max()
                                                                                  : static_cast<std::int64_t>(n);
}

// The value a C caller stored in an enum field. C may store any int there, but in C++ loading a
// value outside the enumerators' range is undefined, so the bytes are read as an int.
template <typename Enum>
int raw_enum(const Enum& e) {
    static_assert(sizeof(Enum) == sizeof(int), "C enums are int-sized");
    int v;
    std::memcpy(&v, &e, sizeof v);
    return v;
}

// Records success (clears the message) or the failure of `function` and returns its status.
trn_status succeed() noexcept;
trn_status translate_current_exception(const char* function) noexcept;

template <typename Body>
trn_status guarded(const char* function, Body&& body) noexcept {
    try {
        body();
        return succeed();
    } catch (...) {
        return translate_current_exception(function);
    }
}

}  // namespace trn::capi
