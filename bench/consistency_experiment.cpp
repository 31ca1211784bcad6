/// @file
/// Issue 5, item 8: is the registration uncertainty consistent? Simulated scans with known truth
/// (registration_tank_scans.hpp): the ballast-tank mock-up seen by a depth camera and the
/// distillation column seen by a 360° LiDAR. For ICP (point-to-plane; Hessian and clustered
/// sandwich covariance, with and without back-face rejection) and Stein-ICP (particle
/// covariance) the normalised estimation error squared NEES = eᵀ Σ⁻¹ e is averaged over the
/// trials (ICP: those that converged and pass SPEC §7's overlap gate) and compared with its
/// two-sided 95 % χ² band. In the
/// column (near-symmetric about its axis) it also counts the particles' yaw modes and how often the
/// KDE mode and the particle mean land within 10° of the true yaw.
///
/// Usage: scantling_experiment_consistency [trials_per_world = 100] [seed = 1]
///        [stein_particles = 100] [cases = all | stein | stein-mockup | stein-column]; one
///        thread (the stein-* cases skip the ICP variants, so the two worlds can run in two
///        processes).

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/quality.hpp>
#include <scantling/registration/stein_icp.hpp>

#include "consistency_stats.hpp"
#include "registration_tank_scans.hpp"

namespace {

using namespace scantling;
using bench::NeesStats;
using bench::TankScanner;

constexpr double kPi = std::numbers::pi;
constexpr double kVoxelM = 0.05;                                     // scan and map resolution
constexpr double kGuessTransM = 0.2, kGuessRotRad = 10 * kPi / 180;  // uniform ± per DoF

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }

/// The ICP variants: covariance model (with its map error σ_m) × back-face rejection.
struct IcpVariant {
    const char* label;
    registration::IcpCovariance covariance;
    double map_error_sigma_m;
    registration::BackFaces back_faces;
};

constexpr auto kHessian = registration::IcpCovariance::kHessian;
constexpr auto kClustered = registration::IcpCovariance::kClusteredSandwich;
constexpr auto kKeep = registration::BackFaces::kKeep;
constexpr auto kReject = registration::BackFaces::kReject;
constexpr auto kPreferFront = registration::BackFaces::kPreferFront;
constexpr IcpVariant kIcpVariants[] = {
    {"ICP Hessian, back faces kept", kHessian, 0.0, kKeep},
    {"ICP clustered, back faces kept", kClustered, 0.001, kKeep},
    {"ICP Hessian, back faces out", kHessian, 0.0, kReject},
    {"ICP clustered σ_m = 0, back faces out", kClustered, 0.0, kReject},
    {"ICP clustered, back faces out", kClustered, 0.001, kReject},
    {"ICP clustered, front faces preferred (default)", kClustered, 0.001, kPreferFront},
};

registration::IcpConfig icp_config(const IcpVariant& v) {
    registration::IcpConfig c;
    c.max_correspondence_distance_m = 0.5;  // covers 0.2 m + 10° at ~2 m
    c.max_iterations = 50;
    c.covariance = v.covariance;
    c.map_error_sigma_m = v.map_error_sigma_m;
    c.back_faces = v.back_faces;
    c.parallel.num_threads = 1;
    return c;
}

registration::SteinIcpConfig stein_config(bool column, int particles, std::uint64_t seed) {
    registration::SteinIcpConfig c;
    c.num_particles = particles;
    c.seed = seed;
    c.parallel.num_threads = 1;
    if (column) {
        c.reduced_3dof = true;
        c.init = registration::SteinInit::kIcpSeeded;  // heading unknown: yaws over [−π, π]
    } else {
        // Box just covering the ±0.2 m / ±10° guess error.
        c.init_half_widths << 0.25, 0.25, 0.25, 0.2, 0.2, 0.2;
    }
    return c;
}

struct Results {
    std::vector<NeesStats> icp;
    NeesStats stein_mode, stein_mean;
    int stein_mode_gated = 0, stein_mean_gated = 0;  ///< trials through the overlap gate
    bench::YawStats yaw;
};

struct Trial {
    bench::TankScan scan;
    Eigen::Isometry3d T_guess;
};

/// SPEC §7's overlap gate (>= 75 % of the scan within one voxel of the map): a localisation
/// filter fuses only registrations that pass it, so NEES is taken over those.
bool accepted(const Trial& t, const KdTree& tree, const Eigen::Isometry3d& T_map_body) {
    registration::OverlapGateConfig gate;
    gate.voxel_size_m = kVoxelM;
    return registration::check_overlap(transformed(t.scan.body, T_map_body), tree, gate).passed;
}

void run_icp(const TankScanner& s, const KdTree& tree, const Trial& t, Results& out) {
    for (std::size_t v = 0; v < std::size(kIcpVariants); ++v) {
        const auto r =
            registration::align(t.scan.body, s.map(), tree, t.T_guess, icp_config(kIcpVariants[v]));
        // Left perturbation in the target frame: T_true = exp(ε) T_est (result.hpp).
        const Vector6d eps = se3_log(t.scan.T_map_body * r.T_target_source.inverse());
        const double n =
            r.covariance ? bench::nees(eps, *r.covariance, {0, 1, 2, 3, 4, 5}) : std::nan("");
        const bool ok = r.converged && accepted(t, tree, r.T_target_source);
        out.icp[v].add(ok, n, r.T_target_source, t.scan.T_map_body);
    }
}

Vector6d param_error(const Vector6d& est, const Vector6d& truth) {
    Vector6d e = est - truth;
    for (int i = 3; i < 6; ++i) e[i] = wrap(e[i]);
    return e;
}

void run_stein(const TankScanner& s, const KdTree& tree, const Trial& t, int particles,
               std::uint64_t seed, Results& out) {
    const bool column = s.scene() == bench::TankScene::kColumn;
    const auto r = registration::stein_icp(t.scan.body, s.map(), tree, t.T_guess,
                                           stein_config(column, particles, seed));
    const Vector6d truth = registration::pose_params_from_isometry(t.scan.T_map_body);
    const std::vector<int> dofs =
        column ? std::vector<int>{0, 1, 5} : std::vector<int>{0, 1, 2, 3, 4, 5};
    // Every trial counts (the mean of a split particle set never passes the gate, and its NEES
    // is the point of the comparison); how many would pass the gate is counted apart.
    const Eigen::Isometry3d T_mean = registration::isometry_from_pose_params(r.mean);
    out.stein_mode.add(true, bench::nees(param_error(r.mode, truth), r.covariance, dofs),
                       r.T_target_source, t.scan.T_map_body);
    out.stein_mean.add(true, bench::nees(param_error(r.mean, truth), r.covariance, dofs), T_mean,
                       t.scan.T_map_body);
    out.stein_mode_gated += accepted(t, tree, r.T_target_source);
    out.stein_mean_gated += accepted(t, tree, T_mean);
    if (!column) return;
    out.yaw.add(std::abs(wrap(r.mode[5] - truth[5])), std::abs(wrap(r.mean[5] - truth[5])),
                r.num_modes);
}

/// `with_icp` false: the Stein-ICP cases only (the ICP ones cost ~half the run).
Results run_scene(const TankScanner& s, int trials, int particles, std::uint64_t seed,
                  bool with_icp) {
    const bool column = s.scene() == bench::TankScene::kColumn;
    const KdTree tree(s.map().points);
    Results res;
    for (const IcpVariant& v : kIcpVariants) {
        if (!with_icp) break;
        res.icp.emplace_back().label = fmt::format("{} {}", s.name(), v.label);
    }
    res.stein_mode.label = s.name() + " Stein (mode)";
    res.stein_mean.label = s.name() + " Stein (mean)";
    res.stein_mode.dof = res.stein_mean.dof = column ? 3 : 6;
    for (int i = 0; i < trials; ++i) {
        Rng rng = Rng(seed).split(static_cast<std::uint64_t>(i));
        Trial t{s.scan(rng), {}};
        // Column: z, roll, pitch known (the Stein-ICP 3-DoF case); ICP still solves 6 DoF.
        t.T_guess = bench::perturbed(t.scan.T_map_body, kGuessTransM, kGuessRotRad, column, rng);
        if (with_icp) run_icp(s, tree, t, res);
        run_stein(s, tree, t, particles, seed * 1000003ULL + static_cast<std::uint64_t>(i), res);
    }
    return res;
}

}  // namespace

int main(int argc, char** argv) {
    const int trials = argc > 1 ? std::atoi(argv[1]) : 100;
    const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
    const int particles = argc > 3 ? std::atoi(argv[3]) : 100;
    const std::string cases = argc > 4 ? argv[4] : "all";
    if (cases != "all" && cases != "stein" && cases != "stein-mockup" && cases != "stein-column") {
        fmt::print(stderr, "cases = {}: expected all, stein, stein-mockup or stein-column\n",
                   cases);
        return 2;
    }
    const bool with_icp = cases == "all";
    bench::print_header();
    bench::YawStats yaw;
    std::string gate_notes;
    for (bench::TankScene scene : {bench::TankScene::kMockup, bench::TankScene::kColumn}) {
        if ((cases == "stein-mockup" && scene == bench::TankScene::kColumn) ||
            (cases == "stein-column" && scene == bench::TankScene::kMockup)) {
            continue;
        }
        const TankScanner scanner(scene, kVoxelM, seed);
        const Results r = run_scene(scanner, trials, particles, seed, with_icp);
        for (const NeesStats& st : r.icp) bench::print_row(st);
        bench::print_row(r.stein_mode);
        bench::print_row(r.stein_mean);
        gate_notes += fmt::format(
            "{}: Stein-ICP through the overlap gate: KDE mode {}/{}, "
            "particle mean {}/{}\n",
            scanner.name(), r.stein_mode_gated, trials, r.stein_mean_gated, trials);
        if (scene == bench::TankScene::kColumn) yaw = r.yaw;
    }
    fmt::print("\n{}", gate_notes);
    bench::print_yaw(yaw);
    return 0;
}
