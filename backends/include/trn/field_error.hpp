#pragma once
// A bad or missing field of a library spec or config: what() = "field: detail", and both parts
// apart, so a front end can put its own spelling of the field (the CLI its flag, Python its
// keyword) in front of the detail.
#include <string>
#include <utility>

#include "trn/error.hpp"

TRN_API_BEGIN
namespace trn {

class FieldError : public Error {
public:
    FieldError(std::string field, std::string detail) : Error(field + ": " + detail), field_(std::move(field)), detail_(std::move(detail)) {}
    const std::string& field() const { return field_; }
    const std::string& detail() const { return detail_; }

private:
    std::string field_, detail_;
};

}  // namespace trn
TRN_API_END
