#pragma once
// TI INA219 register decoding (datasheet SBOS448) and a register-level SIMULATED INA219 that
// generates raw logs for tests and demos. Nothing here talks to hardware.
//
// Decode rules: shunt voltage register is signed, LSB 10 uV; bus voltage register holds the
// value in bits 15..3 (LSB 4 mV), CNVR in bit 1 and OVF in bit 0; current register is signed,
// LSB = current_LSB; power register is unsigned, LSB = 20 x current_LSB; and
// Cal = trunc(0.04096 / (current_LSB x R_shunt)).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "trn/energy/parsers.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct Ina219Config {
    double shunt_ohm = 0.1;
    double current_lsb_a = 0;        // 0: derived from calibration (or from max_expected_a)
    std::uint16_t calibration = 0;   // 0: computed from current_lsb_a
    int pga_mv = 320;                // shunt full scale: 40, 80, 160 or 320 mV
    int adc_bits = 12;               // 9..12
    int adc_samples = 1;             // averaging: 1, 2, 4, ..., 128 (12-bit only when > 1)

    // Resolves current_lsb/calibration and checks every field; throws naming the bad field.
    Ina219Config resolved() const;
    // One shunt or bus conversion (datasheet table 5), seconds.
    double conversion_time_s() const;
    // Options: shunt_ohm, current_lsb, cal, pga_mv, adc ("12bit", "12bit_x8", "9bit", ...).
    static Ina219Config from_options(const ParseOptions& options, const std::string& parser);
};

struct Ina219Registers {
    std::uint16_t shunt = 0, bus = 0;
    std::optional<std::uint16_t> current, power;
};

struct Ina219Reading {
    double shunt_v = 0, bus_v = 0, current_a = 0, power_w = 0;
    bool conversion_ready = false;  // CNVR
    bool overflow = false;          // OVF bit, or |shunt| beyond the PGA range
};

Ina219Reading decode_ina219(const Ina219Registers& regs, const Ina219Config& resolved_config);

// A SIMULATED INA219 in continuous shunt+bus mode polled by a logger: each conversion averages
// the true signal over its window, results are quantised to register LSBs, the current and power
// registers are computed with the chip's integer arithmetic, and CNVR is set by a finished
// conversion and cleared by reading the power register.
struct SimulatedIna219Log {
    std::string text;          // raw register log (time_s,shunt,bus,current,power in hex)
    std::size_t reads = 0;     // logger polls
    std::size_t conversions = 0;
};
SimulatedIna219Log simulate_ina219(const Ina219Config& config, const std::function<double(double)>& load_current_a,
                                   const std::function<double(double)>& bus_voltage_v, double t_begin, double t_end,
                                   double poll_period_s, double poll_jitter_s = 0, std::uint64_t seed = 1);

}  // namespace trn::energy
TRN_API_END
