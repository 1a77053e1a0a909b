// fsw_cli.hpp: what the host command-line tools add to CLI11 (Debian 12: libcli11-dev 2.1.2).
// Header-only, host only; used by hil_host/sil/sil, hil_host/tools/lcm_pingpong,
// sim/observer/sim_openloop, tests/<module>/gen/<prefix>_golden_gen and tools/impulse/imp_mc (each links
// CLI11::CLI11 and adds this directory to its include path).
//
// Options, help, required options, choices (CLI::IsMember), ranges (CLI::Range) and paths
// (CLI::ExistingFile, CLI::ExistingDirectory) are CLI11's. Two things are written here, because
// CLI11 2.1's own number conversion would change what the tools read:
//   * integers: CLI11 converts with strtoll/strtoull in base 0, so "010" would be 8, "0x10" 16,
//     and "-1" given to an unsigned option 2^64 - 1. Int() and UInt() read base 10, as the tools
//     always did, and reject anything else;
//   * doubles: CLI11 converts with strtold and then narrows to double, which rounds twice: about
//     one 17-digit decimal in 5 000 (Python's repr() writes such numbers, e.g. tools/impulse/mc.py
//     passing --omega) became the neighbouring double of the one strtod reads. Real() reads the
//     text with strtod, as the tools did, and rejects what is not a finite number.
// Both are CLI11 transforms: they check the text, then replace it with a form CLI11 converts
// exactly (canonical decimal; C99 hexadecimal floating point), so CLI::Range checks added after
// them see the value the tool will get.
#ifndef FSW_CLI_HPP
#define FSW_CLI_HPP

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace fsw_cli {

// Base-10 signed integer (int64 range), nothing after it.
inline CLI::Validator Int()
{
    return CLI::Validator(
        [](std::string &s) -> std::string {
            char *end = nullptr;
            errno = 0;
            const long long v = std::strtoll(s.c_str(), &end, 10);
            if (s.empty() || end != s.c_str() + s.size() || errno != 0) {
                return "'" + s + "' is not a base-10 integer";
            }
            s = std::to_string(v);
            return std::string{};
        },
        "", "fsw_cli::Int");
}

// Base-10 unsigned integer (uint64 range), no sign, nothing after it.
inline CLI::Validator UInt()
{
    return CLI::Validator(
        [](std::string &s) -> std::string {
            char *end = nullptr;
            errno = 0;
            const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
            if (s.empty() || s.find_first_of("+-") != std::string::npos || end != s.c_str() + s.size() ||
                errno != 0) {
                return "'" + s + "' is not a base-10 unsigned integer";
            }
            s = std::to_string(v);
            return std::string{};
        },
        "", "fsw_cli::UInt");
}

// A finite floating-point number as strtod reads it, nothing after it.
inline CLI::Validator Real()
{
    return CLI::Validator(
        [](std::string &s) -> std::string {
            char *end = nullptr;
            const double v = std::strtod(s.c_str(), &end);
            if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) {
                return "'" + s + "' is not a finite number";
            }
            char hex[48];
            (void)std::snprintf(hex, sizeof hex, "%a", v);
            s = hex;
            return std::string{};
        },
        "", "fsw_cli::Real");
}

// Options given twice take the last value, as the hand-written parsers did (CLI11's default is an
// error). Call before adding options.
inline void last_value_wins(CLI::App &app)
{
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

// Parses argv with app. Returns -1 when the tool should go on; otherwise the exit status: 0 after
// --help (printed on stdout), usage_status after a parse error (CLI11 has printed the reason and
// "Run with --help for more information." on stderr). The tools keep the exit status they always
// gave for bad usage, rather than CLI11's codes from 100 up.
inline int parse(CLI::App &app, int argc, char **argv, int usage_status)
{
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        return app.exit(e) == 0 ? 0 : usage_status;
    }
    return -1;
}

}  // namespace fsw_cli

#endif  // FSW_CLI_HPP
