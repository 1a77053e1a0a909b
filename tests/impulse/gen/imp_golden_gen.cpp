// imp_golden_gen — build-time golden vectors of the impulse solver from its double reference
// (spec 00 §6.4, 50-impulse §6). Run by a custom command of host builds only (golden_vectors() of
// tests/golden/CMakeLists.txt); writes a C header of const integer arrays into the build tree
// (never committed):
//
//   gv_imp_vectors.h   impulse sets: G3 (the paper's example, iterates 0-5 and the plan) and a
//                      G4 subset (Monte Carlo draws of tools/impulse/imp_mc.cpp, seed 1)
//
//   imp_golden_gen --out <dir>      (command line: CLI11; --help)
//
// Problems are built as tests/impulse/test_imp_golden_host.cpp and imp_mc build them (state
// quantised to q28, tau_f to q29, alpha and units from IMP_TBL_DEFAULT; the reference solves the
// dequantised problem with the table's guards). The emitter, the record CRC and the command line
// are tests/golden/gen/gv_emit.hpp's.
#include "gv_emit.hpp"
#include "impulse/imp_ref_solver.hpp"
#include "sensors/rng.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

extern "C" {
#include "gv_imp.h"
#include "imp_tables.h"
}

static_assert(sizeof(gv_imp_case_t) == 34u * 4u, "gv_imp_case_t: the emitter writes 34 words");
static_assert(sizeof(gv_imp_iter_t) == 12u * 4u, "gv_imp_iter_t: the emitter writes 12 words");

namespace {

using gv::Emit;
using gv::header_top;
using gv::hex32;
using gv::ibound;
using gv::inf_norm;
using gv::qnt;
using gv::Q28;
using gv::Q29;
using gv::Q30;
using gv::set_crc;
using gv::write_file;

const gv::Origin kOrigin{"imp_golden_gen", "tests/impulse/gen/imp_golden_gen.cpp", "sim/impulse", "gv_imp.h"};

int32_t ceil_q8(double v) { return static_cast<int32_t>(std::ceil(v * 256.0)); }

struct Problem {
    gv_imp_case_t v{};
    ref::ImpCase c;   // the dequantised case the fixed-point code sees
};

// State in SI -> q28 problem (units and alpha from the table) and its dequantised case.
Problem make_problem(const imp_params_t &p, const ref::Vec6 &x0, double tauf)
{
    Problem f;
    f.c.w = p.omega_nradps * 1e-9;
    f.c.a_nom = p.a_nom_umps2 * 1e-6;
    f.v.tauf_q29 = qnt(tauf, 29);
    f.c.T = f.v.tauf_q29 / Q29 / f.c.w;
    for (int i = 0; i < 6; ++i) {
        const auto si = static_cast<size_t>(i);
        const double unit = (i % 2 == 0) ? f.c.L() : f.c.V();
        f.v.x0_q28[i] = qnt(x0(i) / unit, 28);
        f.v.xt_q28[i] = 0;
        f.c.x0(i) = f.v.x0_q28[i] / Q28 * unit;
        f.c.xt(i) = 0.0;
        f.v.alpha_q30[i] = p.alpha_q30[i];
        f.c.alpha[si] = p.alpha_q30[i] / Q30;
    }
    return f;
}

// The reference plan of a problem, into the record.
void solve_ref(const imp_params_t &p, Problem &f, uint32_t &n_valid)
{
    const ref::ImpGuards g = ref::guards_from_table(p);
    const ref::ImpPlan pl = ref::solve(f.c, g);
    gv_imp_case_t &v = f.v;
    v.outcome = pl.outcome;
    v.pattern = pl.pattern;
    for (size_t s = 0; s < 2; ++s) {
        v.how[s] = pl.how[s];
        v.iters[s] = static_cast<uint32_t>(pl.iters[s]);
        v.dv_q28[s] = qnt(pl.dv[s], 28);
    }
    for (size_t r = 0; r < 3; ++r) {
        v.t1_q29[r] = qnt(pl.t1[r], 29);
        v.t2_q29[r] = qnt(pl.t2[r], 29);
    }
    v.jinv_q8 = 0;
    if (pl.outcome == IMP_SOL_VALID) {
        ++n_valid;
        const ref::ImpNd nd = ref::nondim(f.c);
        const std::array<double, 2> a1{{pl.t1[0], pl.t1[1]}}, a2{{pl.t2[0], pl.t2[1]}};
        const std::array<double, 2> b1{{pl.t1[2], 0}}, b2{{pl.t2[2], 0}};
        const double nxy = inf_norm(ref::jacobian(nd, 0, pl.pattern & 0xFu, a1, a2).inverse());
        const double nz = inf_norm(ref::jacobian(nd, 1, (pl.pattern >> 4) & 3u, b1, b2).inverse());
        v.jinv_q8 = ceil_q8(std::max(nxy, nz));
    }
}

void emit_imp_case(Emit &e, const gv_imp_case_t &v)
{
    e.nl();
    e.open();
    e.i(v.tauf_q29);
    e.in(v.x0_q28, 6);
    e.in(v.xt_q28, 6);
    e.in(v.alpha_q30, 6);
    e.u(v.outcome);
    e.u(v.pattern);
    e.un(v.how, 2);
    e.un(v.iters, 2);
    e.in(v.t1_q29, 3);
    e.in(v.t2_q29, 3);
    e.in(v.dv_q28, 2);
    e.i(v.jinv_q8);
    e.close();
}

void emit_imp_iter(Emit &e, const gv_imp_iter_t &v)
{
    e.nl();
    e.open();
    e.u(v.sub);
    e.u(v.pat);
    e.u(v.k);
    e.in(v.t1_q29, 2);
    e.in(v.t2_q29, 2);
    e.in(v.f_q28, 4);
    e.i(v.jn_q8);
    e.close();
}

void gen_imp(const std::string &out_dir)
{
    const imp_params_t &p = IMP_TBL_DEFAULT;
    const ref::ImpGuards g = ref::guards_from_table(p);
    const double w = p.omega_nradps * 1e-9;
    uint32_t n_valid = 0;
    // G3: the paper's example (spec 50 §3.4): X0 = (5 km, -1 m/s, 4 km, -1 m/s, 4 km, -1 m/s), T = 1055 s.
    ref::Vec6 ex;
    ex << 5000, -1, 4000, -1, 4000, -1;
    Problem g3 = make_problem(p, ex, w * 1055.0);
    solve_ref(p, g3, n_valid);
    std::vector<gv_imp_iter_t> its;
    {
        const ref::ImpNd nd = ref::nondim(g3.c);
        const std::array<std::pair<int, unsigned>, 2> subs{{{0, 0xCu}, {1, 0x1u}}};   // the rule's polarities
        for (const auto &sp : subs) {
            const ref::ImpAttempt a = ref::attempt(nd, g, sp.first, sp.second, {{0, 0}}, {{nd.tauf, nd.tauf}});
            for (size_t k = 0; k < a.hist.size() && k <= 5u; ++k) {
                const ref::ImpIter &h = a.hist[k];
                gv_imp_iter_t r{};
                r.sub = static_cast<uint32_t>(sp.first);
                r.pat = sp.second;
                r.k = static_cast<uint32_t>(k);
                for (size_t m = 0; m < 2; ++m) {
                    r.t1_q29[m] = qnt(h.t1[m], 29);
                    r.t2_q29[m] = qnt(h.t2[m], 29);
                }
                for (Eigen::Index m = 0; m < h.f.size(); ++m) { r.f_q28[m] = qnt(h.f(m), 28); }
                r.jn_q8 = ceil_q8(inf_norm(ref::jacobian(nd, sp.first, sp.second, h.t1, h.t2)));
                its.push_back(r);
            }
        }
    }
    // G4 subset: imp_mc's draws (sim::Rng(seed, box_id << 32 | i), X0 = (2u - 1) half-width), seed 1:
    // the first 64 of the nominal box (+-5 km / +-1 m/s, id 1) and 32 of the wide box (+-20 km /
    // +-5 m/s, id 2, where most plans are INFEASIBLE or NO_SOLUTION: outcome equality).
    struct Box {
        uint64_t id;
        double rp, rv;
        uint32_t n;
    };
    const std::array<Box, 2> boxes{{{1u, 5000.0, 1.0, 64u}, {2u, 20000.0, 5.0, 32u}}};
    std::vector<gv_imp_case_t> g4;
    std::array<uint32_t, 2> valid_box{{0, 0}};
    for (size_t b = 0; b < boxes.size(); ++b) {
        for (uint32_t i = 0; i < boxes[b].n; ++i) {
            sim::Rng rng(1u, (boxes[b].id << 32) | i);
            ref::Vec6 x0;
            for (int k = 0; k < 6; ++k) {
                const double u = rng.uniform();
                x0(k) = (2.0 * u - 1.0) * ((k % 2 == 0) ? boxes[b].rp : boxes[b].rv);
            }
            Problem pr = make_problem(p, x0, w * 1055.0);
            solve_ref(p, pr, valid_box[b]);
            g4.push_back(pr.v);
        }
    }
    // Tolerances in LSB of q29 at the table's orbit rate: spec 50 G3 (every iterate 1 ms, final
    // 0.25 ms) and G4 (0.25 ms); + 0.5 LSB for the rounded reference time (the error is an integer).
    const int32_t tol_1ms = ibound(1.0e-3 * w * Q29 + 0.5);
    const int32_t tol_025ms = ibound(0.25e-3 * w * Q29 + 0.5);
    std::string text = header_top(kOrigin, "GV_IMP_VECTORS_H", "gv_imp_vectors.h - impulse solver golden vectors "
                                                      "(spec 50-impulse §6): G3 and a G4 subset.");
    std::ostringstream h;
    h << "#define GV_IMP_TABLE_FP " << hex32(gv_imp_table_fp(&p)) << "   /* IMP_TBL_DEFAULT */\n";
    h << "#define GV_IMP_TOL_1MS_Q29 " << tol_1ms << "     /* 1 ms = " << 1.0e-3 * w * Q29 << " LSB q29, + 0.5 */\n";
    h << "#define GV_IMP_TOL_025MS_Q29 " << tol_025ms << "   /* 0.25 ms = " << 0.25e-3 * w * Q29
      << " LSB q29, + 0.5 */\n\n";
    h << "/* G3: the paper's example, its reference plan (" << (g3.v.outcome == IMP_SOL_VALID ? "VALID" : "not valid")
      << ", pattern " << g3.v.pattern << ") and pure-Newton iterates from (0, tau_f). */\n";
    h << "static const gv_imp_case_t GV_IMP_G3_CASE = ";
    {
        Emit e;
        emit_imp_case(e, g3.v);
        h << e.str() << ";\n";
    }
    h << "#define GV_IMP_G3_N " << its.size() << "u\n";
    h << "#define GV_IMP_G3_CRC " << hex32(set_crc(its)) << "\n";
    h << "static const gv_imp_iter_t GV_IMP_G3[" << its.size() << "] = {";
    {
        Emit e;
        for (const gv_imp_iter_t &r : its) { emit_imp_iter(e, r); }
        h << e.str() << "\n};\n\n";
    }
    h << "/* G4 subset, imp_mc seed 1: nominal box 0-" << boxes[0].n - 1u << " (" << valid_box[0]
      << " valid), wide box 0-" << boxes[1].n - 1u << " (" << valid_box[1] << " valid). */\n";
    h << "#define GV_IMP_G4_N " << g4.size() << "u\n";
    h << "#define GV_IMP_G4_CRC " << hex32(set_crc(g4)) << "\n";
    h << "static const gv_imp_case_t GV_IMP_G4[" << g4.size() << "] = {";
    {
        Emit e;
        for (const gv_imp_case_t &r : g4) { emit_imp_case(e, r); }
        h << e.str() << "\n};\n\n";
    }
    text += h.str() + "#endif\n";
    write_file(out_dir + "/gv_imp_vectors.h", text);
    std::printf("imp_golden_gen: impulse G3 %zu iterates + plan; G4 %zu cases (%u + %u valid)\n", its.size(), g4.size(),
                valid_box[0], valid_box[1]);
}

}  // namespace

int main(int argc, char **argv)
{
    return gv::run(
        argc, argv, "imp_golden_gen",
        "imp_golden_gen: build-time golden vectors of the impulse solver (gv_imp_vectors.h) from its double "
        "reference.",
        [](CLI::App &) {}, [](const std::string &out_dir) { gen_imp(out_dir); });
}
