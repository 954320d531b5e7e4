// Status codes, the thread-local last-error message and the version string of the C API.
#include "c_status.hpp"

#include <cstdio>
#include <new>
#include <string>

#include "trn/build_info.hpp"
#include "trn/error.hpp"

namespace trn::capi {
namespace {

thread_local std::string last_error;

trn_status fail(trn_status status, const char* function, const char* what) noexcept {
    try {
        last_error = std::string(function) + ": " + what;
    } catch (...) {  // no memory for the message: keep at least the function's name
        last_error.clear();
    }
    return status;
}

}  // namespace

trn_status succeed() noexcept {
    last_error.clear();  // never allocates
    return TRN_OK;
}

trn_status translate_current_exception(const char* function) noexcept {
    try {
        throw;
    } catch (const InvalidArgument& e) {
        return fail(TRN_ERR_INVALID_ARGUMENT, function, e.what());
    } catch (const BackendUnavailable& e) {
        return fail(TRN_ERR_UNAVAILABLE, function, e.what());
    } catch (const Error& e) {
        return fail(TRN_ERR_FAILED, function, e.what());
    } catch (const std::bad_alloc&) {
        return fail(TRN_ERR_OUT_OF_MEMORY, function, "out of memory");
    } catch (const std::exception& e) {
        return fail(TRN_ERR_INTERNAL, function, e.what());
    } catch (...) {
        return fail(TRN_ERR_INTERNAL, function, "unknown exception");
    }
}

}  // namespace trn::capi

extern "C" {

const char* trn_last_error(void) { return trn::capi::last_error.c_str(); }

const char* trn_status_name(trn_status status) {
    switch (trn::capi::raw_enum(status)) {
        case TRN_OK: return "TRN_OK";
        case TRN_ERR_INVALID_ARGUMENT: return "TRN_ERR_INVALID_ARGUMENT";
        case TRN_ERR_UNAVAILABLE: return "TRN_ERR_UNAVAILABLE";
        case TRN_ERR_FAILED: return "TRN_ERR_FAILED";
        case TRN_ERR_OUT_OF_MEMORY: return "TRN_ERR_OUT_OF_MEMORY";
        case TRN_ERR_INTERNAL: return "TRN_ERR_INTERNAL";
    }
    return "unknown trn_status";
}

const char* trn_version(void) {
    // A fixed buffer, filled once (thread-safe static init): nothing here can throw into C.
    static const struct Text {
        char s[128];
        Text() {
            const auto& b = trn::build_info();
            std::snprintf(s, sizeof s, "%.*s (commit %.*s)", int(b.version.size()), b.version.data(), int(b.git_commit.size()),
                          b.git_commit.data());
        }
    } text;
    return text.s;
}

}  // extern "C"
