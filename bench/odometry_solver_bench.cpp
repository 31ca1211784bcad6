// LiODOM pose solver (issue 4, item 1: "Ceres or your own Gauss-Newton/LM: choose by
// measurement"): our register_edges (edge_registration.cpp, Gauss-Newton on IRLS) against the
// same problem solved with Ceres, on a real registration: LiODOM ("kitti" preset) runs over the
// first 8 of the 16 real sweeps, then the 9th sweep's edges are registered to its local map from
// the constant-velocity prediction. Both solvers use the same correspondences (k nearest
// local-map points, farthest within max_neighbor_distance_m, λ1 ≥ ratio · λ2), re-found at each
// outer iteration, the same range weight ω, Huber threshold and iteration limits; the Ceres side
// uses Levenberg-Marquardt on quaternion + translation with autodiff. The inputs are built and
// both final poses compared once, before the timed loops.
#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/io/sweep_source.hpp>
#include <scantling/odometry/edge_features.hpp>
#include <scantling/odometry/edge_registration.hpp>
#include <scantling/odometry/liodom.hpp>

#include "bench_support.hpp"

namespace scantling::bench {
namespace {

/// Sweeps run through the odometry before the registered one (the 9th, index 8).
constexpr std::size_t kWarmupSweeps = 8;

struct SolverInput {
    std::unique_ptr<odometry::LidarOdometry> odometry;  ///< owns the local map
    odometry::EdgeFeatures edges;
    Eigen::Isometry3d T_init = Eigen::Isometry3d::Identity();
    odometry::LiodomConfig config;
};

/// Built once in main(); empty when the shared data is absent.
std::optional<SolverInput>& input() {
    static std::optional<SolverInput> in;
    return in;
}

std::optional<SolverInput> make_input() {
    const std::string dir = std::string(SCANTLING_SHARED_DATA_DIR) + "/lidar-scans";
    if (!std::filesystem::exists(dir)) {
        std::printf("skip: %s is absent (the real sweeps are needed)\n", dir.c_str());
        return std::nullopt;
    }
    const auto source = io::open_sweep_source(dir);
    if (source->size() <= kWarmupSweeps) {
        std::printf("skip: %s holds %zu sweeps, need %zu\n", dir.c_str(), source->size(),
                    kWarmupSweeps + 1);
        return std::nullopt;
    }
    SolverInput in;
    in.config = odometry::liodom_preset("kitti");
    in.odometry = std::make_unique<odometry::LidarOdometry>(in.config);
    std::vector<Eigen::Isometry3d> poses;
    for (std::size_t i = 0; i < kWarmupSweeps; ++i) {
        poses.push_back(in.odometry->process(source->read(i)).T_odom_sensor);
    }
    in.edges = in.odometry->extract(source->read(kWarmupSweeps));
    // Constant velocity: the previous estimate times the last relative motion.
    const Eigen::Isometry3d& last = poses[kWarmupSweeps - 1];
    in.T_init = last * (poses[kWarmupSweeps - 2].inverse() * last);
    return in;
}

// ---- the Ceres equivalent -------------------------------------------------------------------

/// ω (I − uuᵀ)(R p + t − c): its norm is ω times the point-to-line distance.
struct PointToLineCost {
    Eigen::Vector3d p;
    Eigen::Vector3d c;
    Eigen::Vector3d u;
    double omega;

    template <typename T>
    bool operator()(const T* q_xyzw, const T* t, T* residual) const {
        const Eigen::Map<const Eigen::Quaternion<T>> q(q_xyzw);
        const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation(t);
        const Eigen::Matrix<T, 3, 1> d = q * p.cast<T>() + translation - c.cast<T>();
        const Eigen::Matrix<T, 3, 1> uc = u.cast<T>();
        Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
        r = T(omega) * (d - uc * uc.dot(d));
        return true;
    }
};

/// Stops the solve at the first step below the thresholds, as register_edges stops its
/// Gauss-Newton steps (reads the parameters: needs update_state_every_iteration).
class StopOnSmallStep : public ceres::IterationCallback {
  public:
    StopOnSmallStep(const Eigen::Quaterniond& q, const Eigen::Vector3d& t, double translation_m,
                    double rotation_rad)
        : q_(q), t_(t), translation_m_(translation_m), rotation_rad_(rotation_rad) {}

    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
        if (summary.iteration == 0) converged_ = false;
        if (summary.iteration > 0 && summary.step_is_successful) {
            const double dt_m = (t_ - t_prev_).norm();
            const double dr_rad =
                Eigen::AngleAxisd(q_.normalized() * q_prev_.normalized().inverse()).angle();
            converged_ = dt_m < translation_m_ && dr_rad < rotation_rad_;
        }
        q_prev_ = q_;
        t_prev_ = t_;
        return converged_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }
    bool converged() const { return converged_; }

  private:
    const Eigen::Quaterniond& q_;
    const Eigen::Vector3d& t_;
    double translation_m_;
    double rotation_rad_;
    Eigen::Quaterniond q_prev_ = Eigen::Quaterniond::Identity();
    Eigen::Vector3d t_prev_ = Eigen::Vector3d::Zero();
    bool converged_ = false;
};

struct CeresResult {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    std::size_t num_correspondences = 0;
    int iterations = 0;
    double solve_s = 0.0;  ///< inside ceres::Solve, summed over the outer iterations
};

CeresResult register_edges_ceres(const odometry::EdgeFeatures& edges, const odometry::LocalMap& map,
                                 const Eigen::Isometry3d& T_init, double min_range_m,
                                 double max_range_m,
                                 const odometry::EdgeRegistrationConfig& config) {
    const std::size_t n = edges.size();
    std::vector<double> weights(n);
    for (std::size_t i = 0; i < n; ++i) {
        weights[i] = odometry::edge_range_weight(edges.ranges_m[i], min_range_m, max_range_m,
                                                 config.range_weighting);
    }
    Eigen::Quaterniond q(T_init.linear());
    Eigen::Vector3d t = T_init.translation();
    ceres::HuberLoss huber(config.huber_delta_m);
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    options.max_num_iterations = config.inner_iterations;
    options.num_threads = std::max(config.parallel.num_threads, 1);
    options.logging_type = ceres::SILENT;
    StopOnSmallStep stop(q, t, config.convergence_translation_m, config.convergence_rotation_rad);
    options.update_state_every_iteration = true;
    options.callbacks.push_back(&stop);
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::EigenQuaternionManifold quaternion_manifold;

    CeresResult result;
    std::vector<odometry::EdgeLine> lines(n);
    for (int outer = 0; outer < config.max_iterations; ++outer) {
        const Eigen::Isometry3d T = Eigen::Translation3d(t) * q;
        parallel_for(config.parallel, n, 256, [&](std::size_t begin, std::size_t end) {
            std::vector<Eigen::Vector3d> points;
            std::vector<double> distances;
            for (std::size_t i = begin; i < end; ++i) {
                lines[i] =
                    odometry::fit_edge_line(map, T * edges.points[i], config, points, distances);
            }
        });
        ceres::Problem problem(problem_options);
        std::size_t count = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (!lines[i].valid) continue;
            auto* cost =
                new ceres::AutoDiffCostFunction<PointToLineCost, 3, 4, 3>(new PointToLineCost{
                    edges.points[i], lines[i].centroid, lines[i].direction, weights[i]});
            problem.AddResidualBlock(cost, &huber, q.coeffs().data(), t.data());
            ++count;
        }
        result.num_correspondences = count;
        result.iterations = outer + 1;
        if (count < static_cast<std::size_t>(config.min_correspondences)) {
            result.T = T_init;
            return result;
        }
        problem.SetManifold(q.coeffs().data(), &quaternion_manifold);
        ceres::Solver::Summary summary;
        ceres::Solve(options, &problem, &summary);
        result.solve_s += summary.total_time_in_seconds;
        q.normalize();
        // Ceres' own tolerances may end the solve before a small step: then the update of the
        // whole outer iteration decides.
        const double dt_m = (t - T.translation()).norm();
        const double dr_rad =
            Eigen::AngleAxisd(q * Eigen::Quaterniond(T.linear()).inverse()).angle();
        if (stop.converged() ||
            (dt_m < config.convergence_translation_m && dr_rad < config.convergence_rotation_rad)) {
            break;
        }
    }
    result.T = Eigen::Translation3d(t) * q;
    return result;
}

odometry::EdgeRegistrationConfig registration_config(const SolverInput& in, int threads) {
    odometry::EdgeRegistrationConfig config = in.config.registration;
    config.parallel.num_threads = threads;
    return config;
}

void ours(benchmark::State& state, int threads) {
    const SolverInput& in = *input();
    const auto config = registration_config(in, threads);
    odometry::EdgeRegistrationResult result;
    int outer = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (auto _ : state) {
        result = odometry::register_edges(in.edges, in.odometry->local_map(), in.T_init,
                                          in.config.features.min_range_m,
                                          in.config.features.max_range_m, config);
        benchmark::DoNotOptimize(result.T_world_sensor.data());
        outer += result.iterations;
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    state.counters["corr"] = static_cast<double>(result.num_correspondences);
    state.counters["outer_iters"] = result.iterations;
    state.counters["ms_per_outer"] = ms / std::max(outer, 1);
}

void with_ceres(benchmark::State& state, int threads) {
    const SolverInput& in = *input();
    const auto config = registration_config(in, threads);
    CeresResult result;
    int outer = 0;
    double solve_s = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (auto _ : state) {
        result = register_edges_ceres(in.edges, in.odometry->local_map(), in.T_init,
                                      in.config.features.min_range_m,
                                      in.config.features.max_range_m, config);
        benchmark::DoNotOptimize(result.T.data());
        outer += result.iterations;
        solve_s += result.solve_s;
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    state.counters["corr"] = static_cast<double>(result.num_correspondences);
    state.counters["outer_iters"] = result.iterations;
    state.counters["ms_per_outer"] = ms / std::max(outer, 1);
    // Share of the wall time spent in ceres::Solve (the rest: correspondences, building the
    // problem).
    state.counters["solve_share"] = 1e3 * solve_s / std::max(ms, 1e-9);
}

/// Runs both once and prints how far apart their final poses are.
void print_comparison(const SolverInput& in) {
    const auto config = registration_config(in, 1);
    const auto a = odometry::register_edges(in.edges, in.odometry->local_map(), in.T_init,
                                            in.config.features.min_range_m,
                                            in.config.features.max_range_m, config);
    const auto b = register_edges_ceres(in.edges, in.odometry->local_map(), in.T_init,
                                        in.config.features.min_range_m,
                                        in.config.features.max_range_m, config);
    const Eigen::Isometry3d diff = a.T_world_sensor.inverse() * b.T;
    const Eigen::Isometry3d moved = in.T_init.inverse() * a.T_world_sensor;
    std::printf(
        "input: sweep %zu, %zu edges, local map %zu points; registration moved the prediction by "
        "%.1f mm, %.3f deg\n",
        kWarmupSweeps, in.edges.size(), in.odometry->local_map().size(),
        1e3 * moved.translation().norm(), Eigen::AngleAxisd(moved.linear()).angle() * 180 / M_PI);
    std::printf("ours : %zu correspondences, %d outer iterations, converged %d, rmse %.4f m\n",
                a.num_correspondences, a.iterations, a.converged ? 1 : 0, a.rmse_m);
    std::printf("ceres: %zu correspondences, %d outer iterations\n", b.num_correspondences,
                b.iterations);
    std::printf("final pose difference ours vs ceres: %.3f mm, %.5f deg\n\n",
                1e3 * diff.translation().norm(),
                Eigen::AngleAxisd(diff.linear()).angle() * 180.0 / M_PI);
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    input() = make_input();
    if (input()) {
        print_comparison(*input());
        for (const int threads : {1, 2}) {
            char ours_name[64];
            char ceres_name[64];
            std::snprintf(ours_name, sizeof ours_name, "edge_registration/ours/%dthr", threads);
            std::snprintf(ceres_name, sizeof ceres_name, "edge_registration/ceres/%dthr", threads);
            benchmark::RegisterBenchmark(ours_name, ours, threads)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
            benchmark::RegisterBenchmark(ceres_name, with_ceres, threads)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        }
    }
    return run_all(argc, argv);
}
