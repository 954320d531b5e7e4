// trnkit: command-line entry point. Subcommands are registered from cmd_*.cpp; every failure
// prints one line naming what was wrong and exits non-zero.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <system_error>

#include "commands.hpp"
#include "field_flags.hpp"
#include "trn/io/input_file.hpp"
#include "trn/build_info.hpp"
#include "trn/error.hpp"
#include "trn/io/gnuplot.hpp"

namespace {

// An error is one line whatever it quotes: a newline or other control character inside a file name
// or an option value is shown escaped (\n, \x1b), so scripts reading stderr line by line see it whole.
// Past 4096 bytes the rest is cut ("... (N bytes)"): readers quote at most 80 bytes of a field, this
// catches whatever else would print a 100 KB line.
std::string one_line(std::string_view text) { return trn::io::quote_input(text, 4096); }

int run(int argc, char** argv) {
    CLI::App app{"trnkit: terrain-relative navigation kit (particle-filter map matching, Sobel, energy)"};
    app.require_subcommand(1);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return "trnkit: error: " + one_line(trn::cli::flags_in(e.what())) + " (see --help)\n";  // a library check inside an option's
    });
    const trn::BuildInfo& build = trn::build_info();
    app.set_version_flag("--version", "trnkit " + std::string(build.version) + " (commit " + std::string(build.git_commit) + ")",
                         "Print the version and the git commit it was built from, then exit");
    trn::cli::add_devices_command(app);
    trn::cli::add_sobel_command(app);
    trn::cli::add_score_command(app);
    trn::cli::add_demo_command(app);
    trn::cli::add_frames_command(app);
    trn::cli::add_energy_command(app);
    trn::cli::add_simulate_command(app);
    trn::cli::add_check_command(app);
    trn::cli::add_localize_command(app);
    trn::cli::add_experiment_command(app);
    trn::cli::add_register_command(app);
    trn::cli::add_import_photos_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const trn::FieldError& e) {  // a library spec's field: named by its flag here
        std::cerr << "trnkit: error: " << one_line(trn::cli::with_flags(e)) << "\n";
        return 1;
    } catch (const trn::Error& e) {
        std::cerr << "trnkit: error: " << one_line(trn::cli::flags_in(e.what())) << "\n";
        return 1;
    } catch (const std::filesystem::filesystem_error& e) {  // an errno from a path (EACCES, ENAMETOOLONG ...): bad input
        std::cerr << "trnkit: error: " << one_line(e.path1().empty() ? std::string() : e.path1().string().substr(0, 512) + ": ")
                  << one_line(e.code().message()) << "\n";
        return 1;
    } catch (const std::system_error& e) {
        std::cerr << "trnkit: error: " << one_line(e.what()) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "trnkit: unexpected error: " << one_line(e.what()) << "\n";
        return 2;
    }
    return 0;
}

// Output on stdout is results too (score's CSV, integrate's JSON): flush it and check, so
// `trnkit ... > /dev/full` or a cut pipe to a full disk exits non-zero instead of 0 with lost data.
int check_stdout(int code) {
    errno = 0;
    std::cout.flush();  // (synced with stdio: this already flushes stdout)
    int why = errno;
    if (std::fflush(stdout) != 0) why = errno;
    if (std::cout && !std::ferror(stdout)) return code;
    std::cerr << "trnkit: error: standard output: write failed" << (why ? std::string(" (") + std::strerror(why) + ")" : "") << "\n";
    return code ? code : 1;
}

}  // namespace

int main(int argc, char** argv) {
    // Past a file-size limit (ulimit -f) write() then fails with EFBIG and the writer reports the
    // file, instead of the process dying silently and leaving a cut file behind.
    std::signal(SIGXFSZ, SIG_IGN);
    // Helper programs by an absolute path found now, before anything changes folder, and never
    // through a relative PATH entry ("", "."): plots run gnuplot in a work folder beside the output,
    // where a dataset could have shipped a program of that name. (PATH unset: the system default.)
    if (const char* path = std::getenv("PATH")) trn::io::set_gnuplot_program(trn::io::find_program("gnuplot", path));
    return check_stdout(run(argc, argv));
}
