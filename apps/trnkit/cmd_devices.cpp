// `trnkit devices`: every backend family this build has, with its devices or why it has none.
#include <iostream>

#include "backend_env.hpp"
#include "commands.hpp"
#include "trn/registry.hpp"

namespace trn::cli {

void add_devices_command(CLI::App& app) {
    auto* cmd = app.add_subcommand("devices", "List every backend and device, with driver and version");
    auto verbose = std::make_shared<bool>(false);
    cmd->add_flag("-v,--verbose", *verbose, "Show device details");
    cmd->callback([verbose] {
        for (const FamilyStatus& f : default_registry().status(backend_options_from_environment())) {
            std::cout << f.family << " - " << f.description << "\n";
            if (f.devices.empty()) std::cout << "  not available: " << f.why_none << "\n";
            for (const DeviceInfo& d : f.devices) {
                std::cout << "  " << d.name << "  [" << d.type << "] " << d.device << "  (" << d.driver << ")\n";
                if (*verbose && !d.details.empty()) std::cout << "      " << d.details << "\n";
            }
        }
    });
}

}  // namespace trn::cli
