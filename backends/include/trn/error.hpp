#pragma once
// One exception type for every trnkit failure, so callers can catch trn::Error and show
// what() to a person: messages always name the argument, file or device call at fault.
#include <stdexcept>
#include <string>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A backend that was asked for by name but is not built or has no usable device.
class BackendUnavailable : public Error {
public:
    using Error::Error;
};

}  // namespace trn
TRN_API_END
