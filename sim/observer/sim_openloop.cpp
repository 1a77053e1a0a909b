// sim_openloop: run a scenario open loop (zero or constant gimbal-rate command) and write truth
// and sensor counts as CSV. A check tool; the closed loop runs through the LCM bridge.
//
//   sim_openloop SCENARIO.yaml [--cmd-radps BY BZ] [--ode] [--out FILE.csv] [--every N]
//   (command line: CLI11; --help lists the options)
//
// Exit status: 0 run completed, 2 DIVERGED, 1 usage or scenario error.
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "fsw_cli.hpp"
#include "observer/sail_plant.hpp"

int main(int argc, char **argv)
{
    std::string scn_path;
    std::string out_path;
    std::vector<double> cmd_radps{0.0, 0.0};
    bool ode = false;
    long every = 1;
    CLI::App app{"sim_openloop: run a scenario open loop (zero or constant gimbal-rate command) and write "
                 "truth and sensor counts as CSV.\nExit 0 run completed, 2 DIVERGED, 1 usage or scenario error.",
                 "sim_openloop"};
    fsw_cli::last_value_wins(app);
    app.add_option("scenario", scn_path, "scenario file (sim/observer/scenarios/*.yaml)")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--cmd-radps", cmd_radps, "constant gimbal-rate command BY BZ [rad/s] (default 0 0)")
        ->expected(2)
        ->type_name("BY BZ")
        ->multi_option_policy(CLI::MultiOptionPolicy::Throw)   // exactly two numbers, given once
        ->transform(fsw_cli::Real());
    app.add_flag("--ode", ode, "propagate with the RK4 ODE instead of the exact ZOH step");
    app.add_option("--out", out_path, "CSV file (default: stdout)");
    app.add_option("--every", every, "write every N-th step (the final state is always written)")
        ->transform(fsw_cli::Int())
        ->check(CLI::Range(1L, std::numeric_limits<long>::max()).description(">= 1"))
        ->capture_default_str();
    const int rc = fsw_cli::parse(app, argc, argv, 1);
    if (rc >= 0) {
        return rc;
    }

    sim::Scenario scn;
    try {
        scn = sim::load_scenario(scn_path);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "sim_openloop: %s\n", e.what());
        return 1;
    }
    if (ode) {
        scn.mission_part<sim::SailScenario>().propagator = sim::Propagator::Ode;
    }
    sim::SailPlant plant(scn);

    // The command goes in as counts, like the bridge's: NaN/range checked before conversion.
    sim::GimbalActuators act(scn.mission_part<sim::SailScenario>().gimbal);
    sim::ActuatorCmd cmd;
    cmd.n_ch = 2u;
    for (std::size_t i = 0; i < 2u; ++i) {
        std::uint8_t st = 0u;
        cmd.cnt[i] = act.counts(cmd_radps[i], &st);
        if (st != 0u) {
            std::fprintf(stderr, "sim_openloop: command %g rad/s is not representable in counts\n", cmd_radps[i]);
            return 1;
        }
    }

    std::FILE *out = stdout;
    if (!out_path.empty()) {
        out = std::fopen(out_path.c_str(), "w");
        if (out == nullptr) {
            std::fprintf(stderr, "sim_openloop: cannot write %s\n", out_path.c_str());
            return 1;
        }
    }
    std::fprintf(out, "# scenario=%s model=%s sigma=%d k2=%.9g j_factor=%.6g period_us=%u propagator=%s\n",
                 scn.name.c_str(), sim::sigma_name(scn.mission_part<sim::SailScenario>().sigma), scn.mission_part<sim::SailScenario>().sigma, scn.mission_part<sim::SailScenario>().k2_true_per_s2, scn.mission_part<sim::SailScenario>().j_factor,
                 static_cast<unsigned>(scn.period_us), ode ? "ode" : "zoh");
    std::fprintf(out, "t_s,seq");
    for (const std::string &n : plant.truth_names()) {
        std::fprintf(out, ",%s", n.c_str());
    }
    std::fprintf(out, ",gyro_y_cnt,gyro_z_cnt,gyro_y_status,gyro_z_status\n");

    auto row = [&](const sim::SensorFrame &f) {
        std::fprintf(out, "%.6f,%u", static_cast<double>(f.utime_us) * 1e-6, static_cast<unsigned>(f.seq));
        for (double v : plant.truth()) {
            std::fprintf(out, ",%.17g", v);
        }
        std::fprintf(out, ",%d,%d,%u,%u\n", f.cnt[0], f.cnt[1], static_cast<unsigned>(f.status[0]),
                     static_cast<unsigned>(f.status[1]));
    };
    sim::RunState st = plant.check();
    while (st == sim::RunState::Running) {
        const sim::SensorFrame f = plant.sense();
        if (static_cast<long>(f.seq) % every == 0) {
            row(f);
        }
        cmd.seq = f.seq;
        plant.apply(cmd);
        st = plant.propagate();
    }
    row(plant.sense());  // final state (t_N, or the first state beyond the limits)
    if (out != stdout) {
        std::fclose(out);
    }
    std::fprintf(stderr, "sim_openloop: %s after %u steps, %zu truth events%s%s\n",
                 st == sim::RunState::Diverged ? "DIVERGED" : "done", static_cast<unsigned>(plant.seq()),
                 plant.events().size(), st == sim::RunState::Diverged ? ": " : "",
                 plant.diverged_reason().c_str());
    return st == sim::RunState::Diverged ? 2 : 0;
}
