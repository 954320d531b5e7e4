#include "trn/energy/format_catalog.hpp"

#include <sstream>

namespace trn::energy {

const std::vector<PowerLogFormat>& power_log_format_catalog() {
    static const std::vector<PowerLogFormat> formats = {
        {"ina219-csv", "INA219 Python/Arduino scripts writing CSV", "time + bus voltage + current, or a power column (header names them)",
         "time s, ms, us, ISO date or row index; V/mV, A/mA (default mA), W/mW (default mW) from the column names",
         "time_s,bus_V,current_mA,power_mW\n    0.010,5.02,412.0,2068.2",
         "columns, time, bus_v, shunt_v, current, power, time_unit=s|ms|us|iso|index, period_s, bus_v_unit, current_unit, power_unit, use=vi|power"},
        {"ina219-tuples", "Arduino INA219 loggers printing Python tuples", "(t, bus_V, current_mA, power_mW)", "t s or a timer tick; V, mA, mW",
         "(1.050032, 11.18, 1.2, 13.416)", "tick_period_s, tick_bits, max_bus_v"},
        {"ina219-raw", "INA219 register dumps (and trnkit's INA219 simulator)", "time_s,shunt,bus[,current][,power] registers, hex or decimal",
         "s; registers decoded with shunt_ohm / current_lsb or cal (also from '# key=value' comments)", "time_s,shunt,bus,current,power\n    0.0021,0x0fa0,0x5dc2,0x0fa0,0x0bb8",
         "shunt_ohm, current_lsb, cal, pga_mv, adc (12bit, 12bit_x8, ...), use=vi|power, time_ref=adc|read"},
        {"nvidia-smi", "nvidia-smi --query-gpu=timestamp,[index,]power.draw --format=csv[,noheader][,nounits] [-lms N]",
         "timestamp, power.draw.instant or power.draw; index/uuid/pci.bus_id to pick a GPU; headerless rows: timestamp, the one field in W, an index before them",
         "local date-time YYYY/MM/DD HH:MM:SS.mmm (no zone); W ('45.2 W' or '45.2' with nounits)",
         "0, 2024/10/30 18:42:33.189, 22.89 W", "column, gpu, columns (names for a headerless log)"},
        {"tegrastats", "NVIDIA Jetson tegrastats (TX1/TX2, Nano, Xavier, Orin)", "input rail VDD_IN / POM_5V_IN current/average, or the sum of rails",
         "optional MM-DD-YYYY HH:MM:SS local time stamp; mW", "10-01-2025 20:05:55 RAM 1095/3964MB ... POM_5V_IN 2793/1750 POM_5V_GPU 76/25",
         "rail=NAME|sum, interval_ms (lines without time stamps)"},
        {"pmt", "PMT (power measurement toolkit) dumps", "timestamp + sensor columns; M <t> \"label\" markers", "s (UNIX time); W",
         "1733935203.149 17.000", "column"},
        {"rapl-tools", "kentcz/rapl-tools AppPowerMeter CSV (headerless)", "pkg_W,pp0_W,pp1_W,dram_W,elapsed_s (interval means)", "W; s since start",
         "23.51,12.03,0.00,2.41,0.100", "domain=pkg|pp0|pp1|dram"},
        {"perf-stat", "perf stat -a -x, -I MS -e power/energy-pkg/", "time,joules,Joules,event,... per interval", "s since start; J per interval -> W",
         "     1.001048308,19.63,Joules,power/energy-pkg/,2002406532,100.00,,", "(none)"},
        {"hwmon-records", "shell loops reading hwmon curr1_input/in1_input after `date`", "Timestamp: <date> then curr1_input: mA and in1_input: mV",
         "date with zone abbreviation (English or German); mA x mV", "Timestamp: Fr 20. Okt 17:43:31 CEST 2023\n    curr1_input: 412\n    in1_input: 5020", "(none)"},
        {"powerstat", "powerstat [-R] [-D] (vmstat-like table)", "Time ... Watts (or another power column); rows until the '--------' summary",
         "time of day HH:MM:SS (local; date= makes it absolute); W, mean over each sample interval",
         "  Time    User  Nice   Sys  Idle    IO  Run Ctxt/s  IRQ/s Fork Exec Exit  Watts\n    16:11:27   0.5   0.0   0.2  99.3   0.0    1    218     97    0    0    0   6.89",
         "column (Watts, pkg-0, dram, ...), date=YYYY-MM-DD"},
        {"turbostat", "turbostat [--Summary] --show Time_Of_Day_Seconds,PkgWatt,... --interval S", "the summary row of each interval (CPU '-'), PkgWatt or another *Watt column",
         "Time_Of_Day_Seconds (UNIX s) or rows every interval_s; W, mean over each interval",
         "Time_Of_Day_Seconds\tCore\tCPU\tBusy%\tPkgWatt\tCorWatt\n    1764590400.002345\t-\t-\t3.51\t12.84\t4.20", "column (PkgWatt, CorWatt, RAMWatt, GFXWatt, SysWatt), interval_s"},
        {"trnkit", "trnkit energy sample (and the INA219 simulator's decode)", "# trnkit-power v1 header, then t_s,power_w",
         "s (UNIX time when the header says wall_clock=1); W", "# trnkit-power v1 kind=instant wall_clock=1 resolution_w=0.001\n    1764590400.001,5.123", "(none)"},
    };
    return formats;
}

std::string format_catalog_text() {
    std::ostringstream os;
    os << "Power-log formats (--format NAME, or auto). Every format also takes --timezone NAME / --utc-offset +HH:MM\n"
          "for local time stamps and --opt time_uncertainty_s=S (each stamp's time known to +-S s, added to the\n"
          "error bounds); --opt KEY=VALUE passes the options below.\n";
    for (const auto& f : power_log_format_catalog()) {
        os << "\n" << f.name << ": " << f.source << "\n";
        os << "  columns: " << f.columns << "\n";
        os << "  units:   " << f.units << "\n";
        os << "  example: " << f.example << "\n";
        os << "  options: " << f.options << "\n";
    }
    return os.str();
}

}  // namespace trn::energy
