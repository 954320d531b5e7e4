#pragma once
// Raspberry Pi 5 PMIC readings (`vcgencmd pmic_read_adc`): the line format and the sum of rails,
// shared by the log reader (parse_pi_pmic.cpp) and the live sampler (pi_pmic_sampler.cpp).
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "trn/energy/power_sampler.hpp"

namespace trn::energy::pmic {

struct Reading {
    std::string rail;  // "VDD_CORE"
    bool current = false;
    double value = 0;  // A or V
};

// "  VDD_CORE_A current(7)=0.72300000A" / "  EXT5V_V volt(24)=5.14647000V"; nullopt otherwise.
std::optional<Reading> parse_line(std::string_view line);

// One dump: currents and voltages by rail.
struct Dump {
    std::map<std::string, double> amps, volts;
    bool empty() const { return amps.empty() && volts.empty(); }
};

// Sum of I x V over the rails with both readings; `rails` names them ("0V8_SW+1V1_SYS+..."),
// `unpaired` the readings left out ("EXT5V_V").
struct Sum {
    double w = 0;
    std::string rails;
    std::set<std::string> unpaired;
};
Sum sum(const Dump& d);

// What the PMIC sum leaves out, for notes.
inline constexpr const char* kNotInSum =
    "not in it: the 5 V input's own draw for USB/peripherals and the PMIC's conversion losses, so a wall meter reads more";

// Live source "pmic:vcgencmd": runs `VCGENCMD pmic_read_adc` (an absolute path, with an empty
// environment) at every poll and records the sum of its rails. Throws trn::Error naming the
// program when it cannot be run, fails, or prints no paired rail.
std::unique_ptr<PowerSampler> make_sampler(const std::string& vcgencmd);

}  // namespace trn::energy::pmic
