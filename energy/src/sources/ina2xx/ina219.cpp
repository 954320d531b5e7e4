#include "trn/energy/ina219.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "option_reader.hpp"

namespace trn::energy {

Ina219Config Ina219Config::resolved() const {
    Ina219Config c = *this;
    if (!(c.shunt_ohm > 0) || !std::isfinite(c.shunt_ohm)) throw Error("INA219 config: shunt_ohm must be > 0");
    if (c.pga_mv != 40 && c.pga_mv != 80 && c.pga_mv != 160 && c.pga_mv != 320)
        throw Error("INA219 config: pga_mv must be 40, 80, 160 or 320 (got " + std::to_string(c.pga_mv) + ")");
    if (c.adc_bits < 9 || c.adc_bits > 12) throw Error("INA219 config: adc bits must be 9..12");
    const int s = c.adc_samples;
    if (s < 1 || s > 128 || (s & (s - 1)) != 0) throw Error("INA219 config: adc averaging must be 1, 2, 4, ..., 128");
    if (s > 1 && c.adc_bits != 12) throw Error("INA219 config: averaging needs 12-bit mode");
    if (c.current_lsb_a > 0) {
        const double cal = std::trunc(0.04096 / (c.current_lsb_a * c.shunt_ohm));
        if (cal < 1 || cal > 65535) throw Error("INA219 config: current_lsb gives calibration " + std::to_string(cal) + " outside 1..65535");
        if (c.calibration == 0) c.calibration = static_cast<std::uint16_t>(cal) & 0xFFFE;  // bit 0 is not writable
    } else if (c.calibration > 0) {
        c.current_lsb_a = 0.04096 / (c.calibration * c.shunt_ohm);
    } else {
        throw Error("INA219 config: give current_lsb or cal");
    }
    return c;
}

double Ina219Config::conversion_time_s() const {
    static const double single[] = {84e-6, 148e-6, 276e-6, 532e-6};
    static const double averaged[] = {532e-6, 1.06e-3, 2.13e-3, 4.26e-3, 8.51e-3, 17.02e-3, 34.05e-3, 68.10e-3};
    if (adc_samples == 1) return single[adc_bits - 9];
    int k = 0;
    while ((1 << k) < adc_samples) ++k;
    return averaged[k];
}

Ina219Config Ina219Config::from_options(const ParseOptions& options, const std::string& parser) {
    OptionReader o(options, parser, {"shunt_ohm", "current_lsb", "cal", "pga_mv", "adc", "use", "time_ref"});
    Ina219Config c;
    c.shunt_ohm = o.number("shunt_ohm", c.shunt_ohm);
    c.current_lsb_a = o.number("current_lsb", 0);
    const double cal = o.number("cal", 0);
    if (cal < 0 || cal > 65535 || cal != std::trunc(cal)) throw Error(parser + ": option cal must be an integer 0..65535");
    c.calibration = static_cast<std::uint16_t>(cal);
    const double pga = o.number("pga_mv", 320);
    c.pga_mv = static_cast<int>(pga);
    if (pga != c.pga_mv) throw Error(parser + ": option pga_mv must be 40, 80, 160 or 320");
    const std::string adc = o.text("adc", "12bit");
    int bits = 0, samples = 1;
    char tail[8] = {};
    if (std::sscanf(adc.c_str(), "%dbit_x%d%7s", &bits, &samples, tail) == 2 || std::sscanf(adc.c_str(), "%dbit%7s", &bits, tail) == 1) {
        c.adc_bits = bits;
        c.adc_samples = samples;
    } else {
        throw Error(parser + ": option adc='" + adc + "': expected e.g. 12bit or 12bit_x8");
    }
    try {
        return c.resolved();
    } catch (const Error& e) {
        throw Error(parser + ": " + e.what());
    }
}

Ina219Reading decode_ina219(const Ina219Registers& regs, const Ina219Config& c) {
    Ina219Reading r;
    r.shunt_v = static_cast<std::int16_t>(regs.shunt) * 10e-6;
    r.bus_v = (regs.bus >> 3) * 4e-3;
    r.conversion_ready = (regs.bus & 0x2) != 0;
    r.overflow = (regs.bus & 0x1) != 0 || std::abs(r.shunt_v) > c.pga_mv * 1e-3;
    r.current_a = regs.current ? static_cast<std::int16_t>(*regs.current) * c.current_lsb_a : r.shunt_v / c.shunt_ohm;
    r.power_w = regs.power ? *regs.power * 20.0 * c.current_lsb_a : r.bus_v * r.current_a;
    return r;
}

namespace {

std::uint16_t clamp_reg(double v, double lo, double hi) {
    return static_cast<std::uint16_t>(static_cast<std::int32_t>(std::lround(std::clamp(v, lo, hi))) & 0xFFFF);
}

}  // namespace

SimulatedIna219Log simulate_ina219(const Ina219Config& config, const std::function<double(double)>& load_current_a,
                                   const std::function<double(double)>& bus_voltage_v, double t_begin, double t_end,
                                   double poll_period_s, double poll_jitter_s, std::uint64_t seed) {
    const Ina219Config c = config.resolved();
    if (!(poll_period_s > 0) || !(t_end > t_begin)) throw Error("simulate_ina219: need poll period > 0 and t_end > t_begin");
    const double tc = c.conversion_time_s();
    // Mean of f over [a, b] by the midpoint rule: the ADC integrates its input over the window.
    auto window_mean = [](const std::function<double(double)>& f, double a, double b) {
        const int steps = 16;
        double s = 0;
        for (int i = 0; i < steps; ++i) s += f(a + (b - a) * (i + 0.5) / steps);
        return s / steps;
    };
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> jitter(-poll_jitter_s, poll_jitter_s);
    SimulatedIna219Log log;
    log.text = "# SIMULATED INA219 (register-level model, not a measurement)\n";
    char buf[160];
    std::snprintf(buf, sizeof buf, "# shunt_ohm=%.9g current_lsb=%.9g cal=%u pga_mv=%d adc=%dbit_x%d\n", c.shunt_ohm,
                  c.current_lsb_a, c.calibration, c.pga_mv, c.adc_bits, c.adc_samples);
    log.text += buf;
    log.text += "time_s,shunt,bus,current,power\n";
    // Shunt then bus conversion make one cycle of 2*tc; results latch at the cycle's end.
    std::uint16_t shunt_reg = 0, bus_reg = 0, current_reg = 0, power_reg = 0;
    bool cnvr = false;
    double next_cycle_end = t_begin + 2 * tc;
    for (double nominal = t_begin + poll_period_s; ; nominal += poll_period_s) {
        const double t_read = nominal + jitter(rng);
        if (t_read > t_end) break;
        while (next_cycle_end <= t_read) {
            const double s0 = next_cycle_end - 2 * tc;
            const double i_mean = window_mean(load_current_a, s0, s0 + tc);
            const double v_mean = window_mean(bus_voltage_v, s0 + tc, s0 + 2 * tc);
            const double fs = c.pga_mv * 1e-3;
            const double vs = i_mean * c.shunt_ohm;
            const bool ovf = std::abs(vs) > fs;
            shunt_reg = clamp_reg(vs / 10e-6, -fs / 10e-6, fs / 10e-6);
            const std::uint16_t bus_value = clamp_reg(v_mean / 4e-3, 0, 8191);
            const std::int32_t cur = (static_cast<std::int16_t>(shunt_reg) * static_cast<std::int32_t>(c.calibration)) / 4096;
            current_reg = static_cast<std::uint16_t>(cur & 0xFFFF);
            const std::int32_t pw = (std::abs(cur) * static_cast<std::int32_t>(bus_value)) / 5000;
            power_reg = static_cast<std::uint16_t>(std::min(pw, 65535));
            cnvr = true;
            bus_reg = static_cast<std::uint16_t>((bus_value << 3) | (ovf ? 1 : 0));
            next_cycle_end += 2 * tc;
            ++log.conversions;
        }
        const std::uint16_t bus_out = static_cast<std::uint16_t>(bus_reg | (cnvr ? 2 : 0));
        std::snprintf(buf, sizeof buf, "%.9f,0x%04X,0x%04X,0x%04X,0x%04X\n", t_read, shunt_reg, bus_out, current_reg, power_reg);
        log.text += buf;
        cnvr = false;  // reading the power register clears CNVR
        ++log.reads;
    }
    return log;
}

}  // namespace trn::energy
