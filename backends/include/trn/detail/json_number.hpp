#pragma once
// A number for a JSON writer: the value, or null when it is NaN or infinite (JSON has neither).
// The one helper every report writer uses; a template over the JSON type (nlohmann::json or
// ordered_json) so that this header needs no JSON library. Header-only, not exported.
#include <cmath>

namespace trn {

template <class Json>
Json json_number(double v) {
    return std::isfinite(v) ? Json(v) : Json(nullptr);
}

}  // namespace trn
