// UAV3D experiment (SPEC §9, RESULTS-TO-REPRODUCE 4.7): the helix table (Table 1) and the
// point-density planner tables (Tables 2–3) as markdown, on stdout.
// Usage: scantling_uav3d_experiment [frame_rate_hz] [seed] [max_rotations] [disparity_sigma_px]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/mission/reconstruction_experiment.hpp>

namespace {

using scantling::mission::ReconstructionExperimentConfig;

void helix_table(const ReconstructionExperimentConfig& config, double max_rotations) {
    fmt::print("## Table 1: helix, ω = {} rad/s\n\n", config.omega_radps);
    fmt::print(
        "| rotations | r (m) | v_z (m/s) | time (s) | path (m) | frames | raw points | confirmed "
        "| seg 0 | seg 1 | seg 2 | seg 3 |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const double rotations : {5.0, 10.0, 15.0, 20.0, 25.0, 50.0, 100.0}) {
        if (rotations > max_rotations) continue;
        for (const double radius_m : {2.0, 3.0}) {
            const auto run = scantling::mission::run_helix(config, radius_m, rotations);
            fmt::print(
                "| {} | {} | {:.5f} | {:.1f} | {:.1f} | {} | {} | {} | {} | {} | {} | {} |\n",
                rotations, radius_m, run.v_z_mps, run.duration_s, run.path_length_m, run.frames,
                run.raw_points, run.confirmed_points, run.sectors[0], run.sectors[1],
                run.sectors[2], run.sectors[3]);
            std::fflush(stdout);
        }
    }
    fmt::print("\n");
}

void planner_table(const ReconstructionExperimentConfig& config, double radius_m) {
    scantling::planning::PointDensityPlannerConfig planner;
    planner.fixed_centre_xy_m = Eigen::Vector2d::Zero();
    planner.fixed_flight_radius_m = radius_m;
    planner.flight_height_m = 3.0;
    planner.max_steps = 4;
    const auto run = scantling::mission::run_planner(config, planner);
    fmt::print("## Planner, r_flight = {} m, z = {} m (threshold {} per sector, max {} steps)\n\n",
               radius_m, run.flight_height_m, planner.density_threshold_points, planner.max_steps);
    fmt::print(
        "| step | total | seg 0 | seg 1 | seg 2 | seg 3 | target | arc (°) | turns | path (m) | "
        "time (s) |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& s : run.steps) {
        fmt::print("| {} | {} | {} | {} | {} | {} | {} | {:.0f} | {:.2f} | {:.1f} | {:.1f} |\n",
                   s.step, s.total, s.sectors[0], s.sectors[1], s.sectors[2], s.sectors[3],
                   s.target_sector < 0 ? std::string("turn") : fmt::format("{}", s.target_sector),
                   s.arc_rad * 180.0 / std::numbers::pi, s.turns, s.path_length_m, s.time_s);
    }
    const char* stop = run.stop == scantling::planning::PlannerStatus::kThresholdReached
                           ? "every sector reached the threshold"
                           : "step limit";
    fmt::print(
        "\nStopped: {}. Voxel estimate of the centre on the step-0 map: ({:.2f}, {:.2f}) m, "
        "r_flight {:.1f} m.\n\n",
        stop, run.voxel_estimate.centre_xy_m.x(), run.voxel_estimate.centre_xy_m.y(),
        run.voxel_estimate.flight_radius_m);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        ReconstructionExperimentConfig config;
        if (argc > 1) config.frame_rate_hz = std::stod(argv[1]);
        if (argc > 2) config.seed = std::stoull(argv[2]);
        const double max_rotations = argc > 3 ? std::stod(argv[3]) : 100.0;
        if (argc > 4) config.stereo.disparity_sigma_px = std::stod(argv[4]);
        fmt::print("frame rate {} Hz, seed {}, disparity noise {} px\n\n", config.frame_rate_hz,
                   config.seed, config.stereo.disparity_sigma_px);
        planner_table(config, 2.0);
        planner_table(config, 3.0);
        helix_table(config, max_rotations);
        return EXIT_SUCCESS;
    } catch (const std::exception& e) {
        fmt::print(stderr, "uav3d_experiment: {}\n", e.what());
        return EXIT_FAILURE;
    }
}
