// Energy integration through the C API: what `trnkit energy integrate` computes, per frame.
#include <string>
#include <vector>

#include "c_handles.hpp"
#include "c_status.hpp"

using trn::capi::guarded;
using trn::capi::InvalidArgument;
using trn::capi::require_pointer;

namespace {

trn::energy::IntegrateRequest to_request(const trn_energy_options& o) {
    trn::energy::IntegrateRequest q;
    const int align = trn::capi::raw_enum(o.align);
    switch (align) {
        case TRN_ALIGN_SAME_CLOCK: q.align = trn::energy::AlignMode::SameClock; break;
        case TRN_ALIGN_OFFSET: q.align = trn::energy::AlignMode::Offset; break;
        case TRN_ALIGN_AUTO: q.align = trn::energy::AlignMode::Auto; break;
        default: throw InvalidArgument("options->align " + std::to_string(align) + " is not a trn_align_mode");
    }
    q.offset_s = o.offset_s;
    q.search_s = o.search_s;
    q.insist = o.insist != 0;
    q.realtime = o.monotonic == 0;
    q.integration.rule = o.hold ? trn::energy::Rule::Hold : trn::energy::Rule::Trapezoid;
    q.integration.min_samples = o.min_samples;
    return q;
}

}  // namespace

extern "C" {

trn_energy_options trn_energy_options_default(void) {
    const trn::energy::IntegrationOptions cxx;  // the C++ defaults
    trn_energy_options o{};
    o.align = TRN_ALIGN_SAME_CLOCK;
    o.min_samples = cxx.min_samples;
    return o;
}

trn_status trn_energy_integrate(const char* log_path, const char* markers_path, const trn_energy_options* options,
                                trn_energy_result** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(log_path, "log_path");
        require_pointer(markers_path, "markers_path");
        const trn_energy_options o = options ? *options : trn_energy_options_default();
        if (o.parse_option_count > 0) require_pointer(o.parse_options, "options->parse_options");
        std::vector<std::string> items;
        for (std::size_t i = 0; i < o.parse_option_count; ++i) {
            require_pointer(o.parse_options[i], ("options->parse_options[" + std::to_string(i) + "]").c_str());
            items.emplace_back(o.parse_options[i]);
        }
        auto result = std::make_unique<trn_energy_result>();
        result->report = trn::energy::integrate_files(log_path, o.format ? o.format : "auto", trn::energy::parse_option_list(items),
                                                      markers_path, to_request(o));
        *out = result.release();
    });
}

trn_status trn_energy_summary_get(const trn_energy_result* result, trn_energy_summary* out) {
    return guarded(__func__, [&] {
        require_pointer(result, "result");
        require_pointer(out, "out");
        const auto& r = result->report;
        trn_energy_summary s{};
        s.frame_count = r.frames.size();
        for (const auto& f : r.frames) s.usable_count += f.energy.flag.empty() ? 1 : 0;
        s.warning_count = r.warnings.size();
        s.idle_w = r.idle_w;
        s.offset_s = r.alignment.mapping.offset_s;
        s.drift = r.alignment.mapping.drift;
        *out = s;
    });
}

trn_status trn_energy_frame_get(const trn_energy_result* result, size_t index, trn_energy_frame* out) {
    return guarded(__func__, [&] {
        require_pointer(result, "result");
        require_pointer(out, "out");
        const auto& frames = result->report.frames;
        if (index >= frames.size())
            throw InvalidArgument("index " + std::to_string(index) + " is out of range (" + std::to_string(frames.size()) + " frames)");
        const auto& f = frames[index].energy;
        *out = {f.id, f.start, f.end, f.gross_j, f.net_j, f.error_j, f.samples, f.flag.c_str()};
    });
}

const char* trn_energy_warning(const trn_energy_result* result, size_t index) {
    return result && index < result->report.warnings.size() ? result->report.warnings[index].c_str() : nullptr;
}

void trn_energy_result_destroy(trn_energy_result* result) { delete result; }

}  // extern "C"
