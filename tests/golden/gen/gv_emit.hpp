// gv_emit.hpp — what every module's golden-vector generator shares (spec 00 §6.4; README.md of
// tests/golden): quantisation to the flight formats, the C emitter of positional initialisers,
// the word-wise CRC of the records (the replays' gv_digest.h, so a header's *_CRC is the
// replay's <set>_vectors digest), the header's opening lines, and the command line (CLI11 with
// --out and the generator's own options). Header-only, host only (C++17): each generator is one
// translation unit, tests/<module>/gen/<prefix>_golden_gen.cpp, built by golden_vectors() of
// tests/golden/CMakeLists.txt. Names no mission.
#ifndef TESTS_GOLDEN_GEN_GV_EMIT_HPP
#define TESTS_GOLDEN_GEN_GV_EMIT_HPP

#include "fsw_cli.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "gv_digest.h"
}

namespace gv {

constexpr double Q28 = 268435456.0;
constexpr double Q29 = 536870912.0;
constexpr double Q30 = 1073741824.0;

// Round to the nearest LSB of q<q>; a value outside int32 is a generation error.
inline int32_t qnt(double v, int q)
{
    const double s = std::round(std::ldexp(v, q));
    if (!(s >= -2147483648.0 && s <= 2147483647.0)) {
        throw std::runtime_error("value outside int32 at q" + std::to_string(q));
    }
    return static_cast<int32_t>(s);
}

// An integer bound from a real one: the errors are integers, so err <= b iff err <= floor(b).
inline int32_t ibound(double b) { return static_cast<int32_t>(std::floor(b)); }

inline double inf_norm(const Eigen::MatrixXd &m) { return m.cwiseAbs().rowwise().sum().maxCoeff(); }

// ------------------------------------------------------------------ C emitter

class Emit {
public:
    void i(int32_t v)
    {
        sep();
        if (v == INT32_MIN) {
            s_ << "(-2147483647 - 1)";
        } else {
            s_ << v;
        }
    }
    void u(uint32_t v)
    {
        sep();
        s_ << v << "u";
    }
    void in(const int32_t *v, size_t n)
    {
        open();
        for (size_t k = 0; k < n; ++k) { i(v[k]); }
        close();
    }
    void un(const uint32_t *v, size_t n)
    {
        open();
        for (size_t k = 0; k < n; ++k) { u(v[k]); }
        close();
    }
    void open()
    {
        sep();
        s_ << "{";
        first_ = true;
    }
    void close()
    {
        s_ << "}";
        first_ = false;
    }
    void nl() { s_ << "\n    "; }
    std::string str() const { return s_.str(); }

private:
    void sep()
    {
        if (!first_) { s_ << ", "; }
        first_ = false;
    }
    std::ostringstream s_;
    bool first_ = true;
};

inline void write_file(const std::string &path, const std::string &text)
{
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!f) { throw std::runtime_error("cannot write " + path); }
    f << text;
    if (!f) { throw std::runtime_error("write failed: " + path); }
}

inline std::string hex32(uint32_t v)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%08xu", v);
    return b;
}

// ------------------------------------------------------------------ digests

inline uint32_t words_crc(const void *rec, size_t bytes, uint32_t crc_in)
{
    gv_dg_t d;
    d.crc = crc_in;
    d.n = 0u;
    gv_dg_words(&d, rec, bytes);
    return d.crc;
}

// The CRC of a set's records as words, in order: what the replay's <set>_vectors line digests.
template <typename T>
uint32_t set_crc(const std::vector<T> &v)
{
    uint32_t c = 0u;
    for (const T &r : v) { c = words_crc(&r, sizeof r, c); }
    return c;
}

// ------------------------------------------------------------------ the header

// The opening of a generated header: what it holds, who wrote it from what, the guard, and the
// module's record layouts (records: "gv_<prefix>.h").
struct Origin {
    const char *generator;   // obs_golden_gen
    const char *source;      // tests/observer/gen/obs_golden_gen.cpp
    const char *reference;   // sim/observer
    const char *records;     // gv_obs.h
};

inline std::string header_top(const Origin &o, const char *guard, const char *what)
{
    std::ostringstream h;
    h << "/*\n * " << what << "\n"
      << " * GENERATED at build time by " << o.generator << " (" << o.source << ")\n"
      << " * from the double reference in " << o.reference << ": do not edit, never commit. Host builds regenerate it;\n"
      << " * Cortex-M builds import it from FSW_HOST_BUILD_DIR/golden/gen (tests/golden/README.md).\n"
      << " */\n#ifndef " << guard << "\n#define " << guard << "\n\n#include \"" << o.records << "\"\n\n";
    return h.str();
}

// ------------------------------------------------------------------ the command line

// A generator's main: CLI11 with --out (an existing directory for the header) and the options
// add_options declares, then generate(out). Exit 0 written, 1 generation error (the message on
// stderr, prefixed with the generator's name), 2 bad usage.
inline int run(int argc, char **argv, const char *name, const std::string &about,
               const std::function<void(CLI::App &)> &add_options,
               const std::function<void(const std::string &out_dir)> &generate)
{
    std::string out_dir;
    CLI::App app{about + "\nExit 0 written, 1 generation error, 2 bad usage.", name};
    fsw_cli::last_value_wins(app);
    add_options(app);
    app.add_option("--out", out_dir, "existing directory for the header")->required()->check(CLI::ExistingDirectory);
    const int rc = fsw_cli::parse(app, argc, argv, 2);
    if (rc >= 0) {
        return rc;
    }
    try {
        generate(out_dir);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return 1;
    }
    return 0;
}

}  // namespace gv

#endif
