// pd_analysis — the host analysis of spec 40 on the reconstructed single-channel model
// (sim/pd/pd_model): A3-1 rigid table, A3-2 lifted spectral radius, A3-3 / §4.1 sweep and synthesis.
//
//   pd_analysis rigid                                                   A3-1 table, every channel
//   pd_analysis rho --law fast|literal --channel C [--f HZ] [--rigid] [--k2 0:5:800]
//                                                                       rho, zeta per k2; largest stable k2
//   pd_analysis sweep --channel C --f HZ [--k2 0:5:1000] [--law fast|literal]
//                                                                       t*(k2), admissibility, k2opt
//   pd_analysis synth --channel C [--threads N] [--json FILE]           §4.1 steps 1-4 over the 19 nodes
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "fsw_cli.hpp"
#include "pd/pd_model.hpp"

namespace {

using namespace ref::pd;

std::vector<double> parse_range(const std::string &s)
{
    double a = 0, b = 0, c = 0;
    char tail = 0;
    if (std::sscanf(s.c_str(), "%lf:%lf:%lf%c", &a, &b, &c, &tail) == 3) {
        return grid(a, b, c);
    }
    if (std::sscanf(s.c_str(), "%lf%c", &a, &tail) == 1) {
        return {a};
    }
    throw std::invalid_argument("bad range '" + s + "' (FROM:STEP:TO or a number)");
}

Law parse_law(const std::string &s) { return s == "literal" ? Law::Literal : Law::Fast; }

int cmd_rigid()
{
    std::printf("channel  k0  k1  k2   a2      a1       a0      roots [1/s]                          b2     b1     "
                "eta[1/s]  min|Re s|  t_p[s]  lhs > rhs        dom\n");
    for (const Channel &ch : {Channel::yaw(), Channel::roll(), Channel::pitch()}) {
        const RigidAnalysis r = rigid_analysis(ch);
        std::printf("%-7s %3.0f %3.0f %4.0f  %.4f  %7.4f  %.5f", ch.name.c_str(), ch.k0, ch.k1, ch.k2, r.a2, r.a1,
                    r.a0);
        for (const auto &z : r.roots) {
            std::printf("  %+.4f%+.4fj", z.real(), z.imag());
        }
        std::printf("  %.3f  %.3f  %.5f  %.5f  %.2f  %.0f > %.1f %s  x%.1f %s\n", r.b2, r.b1, r.eta, r.min_abs_re,
                    r.t_p, r.stab_lhs, r.stab_rhs, r.stable ? "stable" : "UNSTABLE", r.dominance,
                    r.real_dominant ? "real root dominant" : "NOT dominant");
    }
    return 0;
}

int cmd_rho(const std::string &law_s, const std::string &chan, double f, bool rigid, const std::string &k2r)
{
    Channel ch = Channel::by_name(chan);
    if (rigid) {
        ch = ch.rigid();
    }
    const Law law = parse_law(law_s);
    const Discrete d = discretise(ch, f);
    double last_stable = -1, rho_max = 0;
    bool run = true;
    std::printf("# %s %s f=%.4f Hz %s\n# k2  rho  zeta  s_least\n", chan.c_str(), law_s.c_str(), f,
                rigid ? "rigid" : "with modes");
    for (double k2 : parse_range(k2r)) {
        const Spectrum sp = spectrum(d, ch, law, k2);
        std::printf("%6.1f  %.5f  %.4f  %+.4f%+.4fj\n", k2, sp.rho, sp.zeta, sp.s_least.real(), sp.s_least.imag());
        rho_max = std::max(rho_max, sp.rho);
        if (run && sp.rho < 1.0) {
            last_stable = k2;
        } else {
            run = false;
        }
    }
    std::printf("# largest stable k2 (first unstable above it): %.1f; max rho %.5f\n", last_stable, rho_max);
    return 0;
}

int cmd_sweep(const std::string &chan, double f, const std::string &k2r, const std::string &law_s)
{
    const Channel ch = Channel::by_name(chan);
    const NodeResult r = sweep_node(ch, f, parse_range(k2r), parse_law(law_s));
    std::printf("# %s f=%.4f Hz %s\n# k2  t*[s]  rho  zeta  admissible\n", chan.c_str(), f, law_s.c_str());
    for (std::size_t i = 0; i < r.k2.size(); ++i) {
        std::printf("%6.1f  %7.2f  %.5f  %.4f  %d\n", r.k2[i], r.tstar[i], r.rho[i], r.zeta[i],
                    r.admissible[i] ? 1 : 0);
    }
    std::printf("# k2opt %.1f  t*min %.2f s\n", r.k2opt, r.tmin);
    return 0;
}

int cmd_synth(const std::string &chan, unsigned threads, const std::string &json)
{
    const Channel ch = Channel::by_name(chan);
    const std::vector<double> fs = f_nodes();
    const std::vector<double> g = grid(0.0, 5.0, 1000.0);
    std::vector<NodeResult> nodes(fs.size());
    const auto t0 = std::chrono::steady_clock::now();
    std::atomic<std::size_t> next{0};
    auto work = [&]() {
        for (std::size_t i = next++; i < fs.size(); i = next++) {
            nodes[i] = sweep_node(ch, fs[i], g);
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < std::max(1u, threads); ++t) {
        pool.emplace_back(work);
    }
    for (std::thread &t : pool) {
        t.join();
    }
    const Schedule sc = finish_schedule(std::move(nodes));
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("# %s synthesis (§4.1), k2 grid 0:5:1000, cap %g\n# f[Hz]  k2opt  t*min[s]  k2s  t*(k2s)  rho  zeta\n",
                chan.c_str(), ch.k2_cap > 1e100 ? -1.0 : ch.k2_cap);
    for (std::size_t i = 0; i < sc.nodes.size(); ++i) {
        const NodeResult &n = sc.nodes[i];
        std::size_t j = static_cast<std::size_t>(std::lround(sc.k2s[i] / 5.0));
        std::printf("%.3f  %6.1f  %7.2f  %6.1f  %7.2f  %.5f  %.4f\n", n.f, n.k2opt, n.tmin, sc.k2s[i], n.tstar[j],
                    n.rho[j], n.zeta[j]);
    }
    std::printf("# k2_cold %.1f\n# wall %.3f s with %u thread(s)\n", sc.k2_cold, wall, std::max(1u, threads));
    if (!json.empty()) {
        std::FILE *fp = std::fopen(json.c_str(), "w");
        if (fp == nullptr) {
            std::fprintf(stderr, "cannot write %s\n", json.c_str());
            return 1;
        }
        std::fprintf(fp, "{\n  \"channel\": \"%s\",\n  \"k2_grid\": [0, 5, 1000],\n  \"k2_cold\": %.1f,\n  \"nodes\": [\n",
                     chan.c_str(), sc.k2_cold);
        for (std::size_t i = 0; i < sc.nodes.size(); ++i) {
            const NodeResult &n = sc.nodes[i];
            std::size_t j = static_cast<std::size_t>(std::lround(sc.k2s[i] / 5.0));
            std::fprintf(fp,
                         "    {\"f\": %.3f, \"k2opt\": %.1f, \"tstar_min\": %.2f, \"k2\": %.1f, \"tstar\": %.2f, "
                         "\"rho\": %.6f, \"zeta\": %.5f}%s\n",
                         n.f, n.k2opt, n.tmin, sc.k2s[i], n.tstar[j], n.rho[j], n.zeta[j],
                         i + 1 < sc.nodes.size() ? "," : "");
        }
        std::fprintf(fp, "  ],\n  \"wall_s\": %.3f,\n  \"threads\": %u\n}\n", wall, std::max(1u, threads));
        std::fclose(fp);
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    CLI::App app{"pd_analysis: host analysis of spec 40 (A3-1, A3-2, A3-3, §4.1)"};
    fsw_cli::last_value_wins(app);
    app.require_subcommand(1);
    const std::vector<std::string> channels{"yaw", "roll", "pitch"}, laws{"fast", "literal"};

    CLI::App *rg = app.add_subcommand("rigid", "A3-1: rigid analysis table (§2.3) per channel");

    std::string law = "fast", chan = "pitch", k2r = "0:5:800", json;
    double f = 0.05;
    bool rigid = false;
    unsigned threads = 1;
    CLI::App *rh = app.add_subcommand("rho", "A3-2: lifted spectral radius per k2");
    rh->add_option("--law", law)->check(CLI::IsMember(laws));
    rh->add_option("--channel", chan)->required()->check(CLI::IsMember(channels));
    rh->add_option("--f", f, "f_min [Hz]")->transform(fsw_cli::Real());
    rh->add_flag("--rigid", rigid, "drop the elastic modes");
    rh->add_option("--k2", k2r, "FROM:STEP:TO");

    CLI::App *sw = app.add_subcommand("sweep", "A3-3: t*(k2), admissibility, k2opt at one f");
    sw->add_option("--channel", chan)->required()->check(CLI::IsMember(channels));
    sw->add_option("--f", f, "f_min [Hz]")->required()->transform(fsw_cli::Real());
    sw->add_option("--k2", k2r, "FROM:STEP:TO (default 0:5:1000)");
    sw->add_option("--law", law)->check(CLI::IsMember(laws));

    CLI::App *sy = app.add_subcommand("synth", "§4.1 steps 1-4 over the 19 f nodes");
    sy->add_option("--channel", chan)->required()->check(CLI::IsMember(channels));
    sy->add_option("--threads", threads)->transform(fsw_cli::UInt());
    sy->add_option("--json", json);

    const int st = fsw_cli::parse(app, argc, argv, 2);
    if (st >= 0) {
        return st;
    }
    try {
        if (rg->parsed()) {
            return cmd_rigid();
        }
        if (rh->parsed()) {
            return cmd_rho(law, chan, f, rigid, k2r);
        }
        if (sw->parsed()) {
            return cmd_sweep(chan, f, sw->count("--k2") != 0u ? k2r : std::string("0:5:1000"), law);
        }
        if (sy->parsed()) {
            return cmd_synth(chan, threads, json);
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "pd_analysis: %s\n", e.what());
        return 1;
    }
    return 2;
}
