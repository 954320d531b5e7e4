// Register decoding against the datasheet, and SIMULATED INA219 raw logs (register-level model,
// not measurements) decoded back to the known energy.
#include <gtest/gtest.h>

#include "trn/error.hpp"
#include "trn/energy/ina219.hpp"
#include "trn/energy/integrate.hpp"

using namespace trn::energy;

TEST(Ina219, DatasheetCalibrationExample) {
    // SBOS448 8.5.1: 0.1 ohm shunt, current LSB 100 uA -> Cal = 4096.
    Ina219Config c;
    c.shunt_ohm = 0.1;
    c.current_lsb_a = 100e-6;
    EXPECT_EQ(c.resolved().calibration, 4096);
    Ina219Registers r;
    r.shunt = 0x07D0;        // 2000 x 10 uV = 20 mV
    r.bus = (3000 << 3) | 2;  // 12 V, CNVR
    r.current = 2000;        // x 100 uA = 0.2 A
    r.power = 480;           // x 2 mW = 0.96 W
    const Ina219Reading d = decode_ina219(r, c.resolved());
    EXPECT_NEAR(d.shunt_v, 0.020, 1e-12);
    EXPECT_NEAR(d.bus_v, 12.0, 1e-12);
    EXPECT_NEAR(d.current_a, 0.2, 1e-12);
    EXPECT_NEAR(d.power_w, 0.96, 1e-12);
    EXPECT_TRUE(d.conversion_ready);
    EXPECT_FALSE(d.overflow);
    r.shunt = static_cast<std::uint16_t>(-4000);  // -40 mV with PGA /1 (40 mV): at range, no overflow
    c.pga_mv = 40;
    EXPECT_FALSE(decode_ina219(r, c.resolved()).overflow);
    r.shunt = static_cast<std::uint16_t>(-4001);
    EXPECT_TRUE(decode_ina219(r, c.resolved()).overflow);
}

TEST(Ina219, SimulatedRawLogConstantLoad) {
    Ina219Config c;
    c.shunt_ohm = 0.1, c.current_lsb_a = 100e-6, c.adc_samples = 1;
    // 0.5 A at 5 V for 1 s, polled at 1 kHz while a 12-bit conversion cycle takes 1.064 ms.
    const auto log = simulate_ina219(c, [](double) { return 0.5; }, [](double) { return 5.0; }, 0, 1, 1e-3, 5e-5);
    const PowerTrace tr = parse_ina219_raw(log.text, "simulated.csv");
    EXPECT_LT(tr.size(), log.reads);  // polls without a new conversion are dropped
    EXPECT_NEAR(describe_sampling(tr).rate_hz, 1 / 1.064e-3, 100);
    const IntervalEnergy e = integrate_interval(tr, 0.1, 0.9);
    EXPECT_NEAR(e.energy_j, 2.5 * 0.8, 1e-3 * 2.0);
}

TEST(Ina219, SimulatedRawLogRampWithQuantisation) {
    Ina219Config c;
    c.shunt_ohm = 0.05, c.current_lsb_a = 50e-6, c.adc_samples = 4;
    const auto current = [](double t) { return 0.2 + 0.3 * t; };
    const auto log = simulate_ina219(c, current, [](double) { return 11.1; }, 0, 2, 1e-3);
    const PowerTrace tr = parse_ina219_raw(log.text, "simulated.csv");
    const double a = 0.3, b = 1.7;
    const double exact = 11.1 * (0.2 * (b - a) + 0.15 * (b * b - a * a));
    const IntervalEnergy e = integrate_interval(tr, a, b);
    // The ADC window lags the read time by ~1.5 conversions; that bias is far below 0.1 % here.
    EXPECT_NEAR(e.energy_j, exact, 1e-3 * exact);
    EXPECT_GT(tr.resolution_w, 0);
}

TEST(Ina219, OverflowIsFlaggedAndRefusalsNameTheLine) {
    Ina219Config c;
    c.shunt_ohm = 0.1, c.current_lsb_a = 100e-6, c.pga_mv = 40;
    const auto log = simulate_ina219(c, [](double t) { return t < 0.5 ? 0.2 : 0.6; }, [](double) { return 5.0; }, 0, 1, 2e-3);
    const PowerTrace tr = parse_ina219_raw(log.text, "sim.csv");
    bool flagged = false;
    for (const auto& n : tr.notes) flagged = flagged || n.find("flagged overflow") != std::string::npos;
    EXPECT_TRUE(flagged);
    try {
        parse_ina219_raw("# shunt_ohm=0.1 current_lsb=0.0001\ntime_s,shunt,bus\n0.1,0x10,0x5\n0.2,0x1G,0x5\n", "bad.csv");
        FAIL() << "expected a refusal";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.csv:4:"), std::string::npos) << e.what();
    }
}
