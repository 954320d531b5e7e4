#include "field_flags.hpp"

#include <array>
#include <utility>

namespace trn::cli {
namespace {

// One table for every command: a field has one flag wherever it appears.
constexpr std::array<std::pair<const char*, const char*>, 43> kFlags{{
    {"dataset", "--dataset"},
    {"flight.folder", "--dataset"},
    {"map", "--map"},
    {"nodata", "--nodata"},
    {"metres_per_pixel", "--mpp"},
    {"hfov_deg", "--hfov-deg"},
    {"focal_px", "--focal-px"},
    {"focal_width", "--focal-width"},
    {"hfov_deg (or focal_px with focal_width)", "--hfov-deg (or --focal-px with --focal-width)"},
    {"fps", "--fps"},
    {"rate_hz", "--rate"},
    {"start_x, start_y", "--start"},
    {"max_tilt_deg", "--max-tilt-deg"},
    {"start_heading_rad", "--start-heading-deg"},
    {"init_radius_m", "--init-radius-m"},
    {"reinit_radius_m", "--reinit-radius-m"},
    // import-photos (trnkit::sim's photo import)
    {"photos", "DIR"},
    {"altitude_agl_m", "--altitude-agl"},
    {"sensor_width_mm", "--sensor-width-mm"},
    {"width", "--width"},
    {"ignore_orientation", "--ignore-orientation"},
    {"map_origin", "--map-origin"},
    // localize --start-from-gps
    {"start_from_gps", "--start-from-gps"},
    {"odometry", "--odometry"},
    // energy integrate / compare (trnkit::energy's run report and its hints)
    {"utc_offset", "--utc-offset"},
    {"timezone", "--timezone"},
    {"offset", "--offset"},
    {"clock", "--clock"},
    {"align", "--align"},
    {"search", "--search"},
    {"insist", "--insist"},
    {"sync_unit_ms", "--sync-unit-ms"},
    // experiment (trnkit::experiments' runner)
    {"shard", "--shard"},
    {"job", "--job"},
    {"backend", "--backend"},
    {"list_jobs", "--list-jobs"},
    {"out", "--out"},
    {"profile", "--profile"},
    {"lock_monitor", "--lock-monitor"},
    {"max_particles", "--max-particles"},
    {"kld_upper_quantile", "--kld-upper-quantile"},
    {"results", "--results"},
    {"resume", "--resume"},
}};

}  // namespace

std::string flag_of(const std::string& field) {
    for (const auto& [f, flag] : kFlags)
        if (field == f) return flag;
    return field;
}

std::string flags_in(std::string text) {
    for (std::size_t open = text.find('`'); open != std::string::npos; open = text.find('`', open + 1)) {
        const std::size_t close = text.find('`', open + 1);
        if (close == std::string::npos) break;
        const std::string field = text.substr(open + 1, close - open - 1), flag = flag_of(field);
        if (flag == field) {  // not a field (a quoted command, say): left as it is
            open = close;
            continue;
        }
        text.replace(open, close - open + 1, flag);
        open += flag.size() - 1;
    }
    return text;
}

std::string with_flags(const FieldError& error) { return flag_of(error.field()) + ": " + flags_in(error.detail()); }

}  // namespace trn::cli
