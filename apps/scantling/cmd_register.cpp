// `scantling register SRC TGT --method M --out T.txt`: the registration library on two files.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/ransac_registration.hpp>
#include <scantling/registration/robust_registration.hpp>
#include <scantling/registration/stein_icp.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {
namespace {

namespace reg = registration;
using Clock = std::chrono::steady_clock;

enum class Method { kIcp, kPointToPlane, kGicp, kFpfhTeaser, kFpfhRansac, kStein };

constexpr std::array<std::pair<std::string_view, Method>, 6> kMethods{{
    {"icp", Method::kIcp},
    {"p2plane", Method::kPointToPlane},
    {"gicp", Method::kGicp},
    {"fpfh-teaser", Method::kFpfhTeaser},
    {"fpfh-ransac", Method::kFpfhRansac},
    {"stein", Method::kStein},
}};

/// Local methods: 0.1 m keeps the shape of room- and street-scale scans at a few thousand
/// points. Global methods: SPEC §7's 0.05 m, the scale FPFH radii and noise bounds are set for.
constexpr double kLocalVoxelM = 0.1;
constexpr double kGlobalVoxelM = 0.05;
bool is_global(Method m) { return m == Method::kFpfhTeaser || m == Method::kFpfhRansac; }

Method method_from_string(const std::string& name) {
    for (const auto& [text, method] : kMethods) {
        if (text == name) return method;
    }
    throw ConfigError(fmt::format(
        "--method = '{}', expected icp, p2plane, gicp, fpfh-teaser, fpfh-ransac or stein", name));
}

/// What every method reports, in the CLI's words.
struct Outcome {
    Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
    /// The method's own test passed; otherwise nothing is written (the pose would be the
    /// initial guess or a half-way step, indistinguishable from a result in the file).
    bool converged = false;
    std::string failure;  ///< why not, in the method's words
    std::string status;
    double fitness = 0.0;
    double rmse_m = 0.0;
    std::optional<Matrix6d> covariance;
    std::string covariance_label;
    std::string details;  ///< method-specific lines, each ending in '\n'
};

void check_options(const RegisterOptions& o, Method method) {
    const double voxel = o.voxel_size_m.value_or(0.0);
    if (!std::isfinite(voxel) || voxel < 0.0 || (is_global(method) && o.voxel_size_m && voxel == 0))
        throw ConfigError(
            fmt::format("--voxel = {}, expected >= 0 m ({} for global methods)", voxel, "> 0"));
    if (o.max_distance_m && !(std::isfinite(*o.max_distance_m) && *o.max_distance_m > 0.0))
        throw ConfigError(fmt::format("--max-distance = {}, expected > 0 m", *o.max_distance_m));
    if (o.num_threads < 0)
        throw ConfigError(fmt::format("--threads = {}, expected >= 0", o.num_threads));
    reg::back_faces_from_string(o.back_faces, "--back-faces");
    if (is_global(method) && o.init_path)
        throw ConfigError(
            "--init applies to icp, p2plane, gicp and stein (global methods need no guess)");
    const auto dir = std::filesystem::path(o.out).parent_path();
    std::error_code ec;
    if (o.out.empty()) throw ConfigError("--out is required");
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
        throw FileError(o.out, "'" + dir.string() + "' is not an existing directory");
    io::check_output_file(o.out);
    io::ensure_output_distinct(o.out, {o.source, o.target, o.init_path.value_or("")});
}

PointCloud load(const std::string& path, double voxel_m, int num_threads) {
    PointCloud cloud = remove_non_finite(io::read_cloud(path));
    if (cloud.empty()) throw InputError(path + ": no finite points");
    if (voxel_m <= 0.0) return cloud;
    VoxelGridConfig config;
    config.voxel_size_m = voxel_m;
    config.parallel.num_threads = num_threads;
    return voxel_downsample(cloud, config);
}

Outcome from_registration(const reg::RegistrationResult& r) {
    Outcome o{.T_target_source = r.T_target_source,
              .converged = r.converged,
              .failure = fmt::format("{} after {} iterations", r.status, r.iterations),
              .status = r.converged ? fmt::format("converged ({} iterations)", r.iterations)
                                    : fmt::format("not converged: {} ({} iterations)", r.status,
                                                  r.iterations),
              .fitness = r.fitness,
              .rmse_m = r.rmse_m,
              .covariance = r.covariance,
              .covariance_label = "twist (rho, omega), m² and rad²",
              .details = {}};
    if (r.degeneracy.degenerate) o.details += "degenerate: yes (no covariance)\n";
    return o;
}

Outcome run_icp(const PointCloud& src, const PointCloud& tgt, const Eigen::Isometry3d& init,
                reg::IcpMethod method, const RegisterOptions& o) {
    reg::IcpConfig config;
    config.method = method;
    config.back_faces = reg::back_faces_from_string(o.back_faces, "--back-faces");
    if (o.max_distance_m) config.max_correspondence_distance_m = *o.max_distance_m;
    config.parallel.num_threads = o.num_threads;
    return from_registration(reg::align(src, tgt, init, config));
}

Outcome run_stein(const PointCloud& src, PointCloud tgt, const Eigen::Isometry3d& init,
                  const RegisterOptions& o) {
    reg::SteinIcpConfig config;
    if (o.max_distance_m) config.max_correspondence_distance_m = *o.max_distance_m;
    config.back_faces = reg::back_faces_from_string(o.back_faces, "--back-faces");
    config.parallel.num_threads = o.num_threads;
    // Point-to-plane likelihood, as p2plane: with point-to-point the posterior of the refined
    // particles has a local minimum per sampling cell, which shows as spurious KDE modes.
    if (!tgt.has_normals()) {
        const reg::IcpConfig icp;
        estimate_normals(tgt, {.num_neighbors = icp.num_neighbors,
                               .viewpoint = Eigen::Vector3d::Zero(),
                               .parallel = {.num_threads = o.num_threads}});
    }
    const reg::SteinIcpResult r = reg::stein_icp(src, tgt, init, config);
    // Stein-ICP has no convergence test of its own (it runs a fixed number of steps): its mode
    // is unsupported when fewer source points lie within reach of the target than ICP needs to
    // take a step at all.
    const auto supporting = static_cast<std::size_t>(std::llround(r.fitness * src.size()));
    const auto needed = static_cast<std::size_t>(reg::IcpConfig{}.min_correspondences);
    return {.T_target_source = r.T_target_source,
            .converged = supporting >= needed,
            .failure = fmt::format("{} source points within {} m of the target at the mode, "
                                   "expected at least {}",
                                   supporting, config.max_correspondence_distance_m, needed),
            .status = fmt::format("particles: {}, modes: {}", r.particles.size(), r.num_modes),
            .fitness = r.fitness,
            .rmse_m = r.rmse_m,
            .covariance = r.covariance,
            .covariance_label = "particles (x, y, z, roll, pitch, yaw), m² and rad²",
            .details = fmt::format("modes: {}\n", r.num_modes)};
}

/// ICP refinement of a global estimate: point-to-plane on the downsampled clouds (they carry
/// normals), reaching 2 voxels because that is how far matched voxel centres can be off.
reg::IcpConfig refine_config(double voxel_m, const RegisterOptions& o) {
    reg::IcpConfig icp;
    icp.method = reg::IcpMethod::kPointToPlane;
    icp.max_correspondence_distance_m = o.max_distance_m.value_or(2.0 * voxel_m);
    icp.back_faces = reg::back_faces_from_string(o.back_faces, "--back-faces");
    icp.parallel.num_threads = o.num_threads;
    return icp;
}

reg::FpfhPipelineConfig pipeline_config(double voxel_m, const RegisterOptions& o) {
    reg::FpfhPipelineConfig c;
    c.voxel_size_m = voxel_m;
    c.normals.parallel.num_threads = o.num_threads;
    c.fpfh.radius_m = 5.0 * voxel_m;
    c.fpfh.parallel.num_threads = o.num_threads;
    c.match.parallel.num_threads = o.num_threads;
    c.robust.noise_bound_m = voxel_m;
    c.robust.parallel.num_threads = o.num_threads;
    c.refine = refine_config(voxel_m, o);
    return c;
}

Outcome run_teaser(const PointCloud& src, const PointCloud& tgt, double voxel_m,
                   const RegisterOptions& o) {
    const reg::FpfhPipelineResult r =
        reg::register_fpfh_teaser(src, tgt, pipeline_config(voxel_m, o));
    Outcome out = from_registration(r.registration);
    out.details += fmt::format(
        "correspondences: {}, clique: {}, robust inliers: {}, robust converged: {}, refined: {}\n",
        r.num_correspondences, r.robust.max_clique_size, r.robust.inliers.size(),
        r.robust.registration.converged, r.refined);
    return out;
}

/// The FPFH front end of the TEASER pipeline, then Open3D-style RANSAC and the same refinement.
Outcome run_ransac(const PointCloud& src_in, const PointCloud& tgt_in, double voxel_m,
                   const RegisterOptions& o) {
    const reg::FpfhPipelineConfig c = pipeline_config(voxel_m, o);
    PointCloud src = voxel_downsample(src_in, voxel_m), tgt = voxel_downsample(tgt_in, voxel_m);
    estimate_normals(src, c.normals);
    estimate_normals(tgt, c.normals);
    const auto matches = reg::match_features(reg::compute_fpfh(src, c.fpfh),
                                             reg::compute_fpfh(tgt, c.fpfh), c.match);
    reg::RansacConfig ransac;
    ransac.max_correspondence_distance_m = 1.5 * voxel_m;
    ransac.parallel.num_threads = o.num_threads;
    const reg::RansacResult r = reg::ransac_register(src.points, tgt.points, matches, ransac);
    Outcome out = from_registration(r.registration);
    if (r.registration.converged) {
        const auto icp = reg::align(src, tgt, r.registration.T_target_source, *c.refine);
        if (icp.converged) out = from_registration(icp);
    }
    out.details += fmt::format("correspondences: {}, ransac inliers: {}, ransac hypotheses: {}\n",
                               matches.size(), r.inliers.size(), r.registration.iterations);
    return out;
}

std::string matrix_text(const Eigen::Matrix4d& M) {
    std::string text;
    for (int r = 0; r < 4; ++r) {
        text +=
            fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}\n", M(r, 0), M(r, 1), M(r, 2), M(r, 3));
    }
    return text;
}

void print_report(const Outcome& r, double ms, std::ostream& out) {
    out << "T_target_source:\n" << matrix_text(r.T_target_source.matrix());
    out << fmt::format("status: {}\nfitness: {:.6f}\nrmse_m: {:.6g}\ntime_ms: {:.1f}\n", r.status,
                       r.fitness, r.rmse_m, ms);
    out << r.details;
    if (!r.covariance) return;
    out << "covariance (" << r.covariance_label << "):\n";
    for (int i = 0; i < 6; ++i) {
        const Vector6d row = r.covariance->row(i).transpose();
        out << fmt::format("{:.6e}\n", fmt::join(row.data(), row.data() + 6, " "));
    }
}

/// What to try after `method` failed, with the settings it ran with.
std::string retry_hint(Method method, double voxel_m, const RegisterOptions& o) {
    if (is_global(method)) {
        return fmt::format(
            "check that the clouds overlap, or try another --voxel (now {} m: larger gives more "
            "distinctive features, smaller keeps thin structures) or the other global method",
            voxel_m);
    }
    const double reach_m = o.max_distance_m.value_or(
        method == Method::kStein ? reg::SteinIcpConfig{}.max_correspondence_distance_m
                                 : reg::IcpConfig{}.max_correspondence_distance_m);
    return fmt::format(
        "try a closer --init, a larger --max-distance (now {} m) or a global method "
        "(fpfh-teaser, fpfh-ransac)",
        reach_m);
}

/// Refuses a result that must not be written: the method's test failed, or the pose is not
/// finite (which no test should let through, but a file of NaN is worse than no file).
void check_converged(const Outcome& r, Method method, double voxel_m, const RegisterOptions& o) {
    if (r.converged && r.T_target_source.matrix().allFinite()) return;
    const std::string why = r.converged ? "the pose is not finite" : r.failure;
    throw NotConvergedError(fmt::format(
        "register --method {}: did not converge ({}; fitness {:.3f}, rmse {:.3g} m), so {} was "
        "not written; {}",
        o.method, why, r.fitness, r.rmse_m, o.out, retry_hint(method, voxel_m, o)));
}

}  // namespace

void run_register(const RegisterOptions& o, std::ostream& out) {
    const Method method = method_from_string(o.method);
    check_options(o, method);
    const Eigen::Isometry3d init =
        o.init_path ? read_transform_file(*o.init_path) : Eigen::Isometry3d::Identity();
    const double voxel = o.voxel_size_m.value_or(is_global(method) ? kGlobalVoxelM : kLocalVoxelM);
    // The global pipelines downsample themselves; local methods get the downsampled clouds.
    const double load_voxel = is_global(method) ? 0.0 : voxel;
    const PointCloud src = load(o.source, load_voxel, o.num_threads);
    const PointCloud tgt = load(o.target, load_voxel, o.num_threads);
    spdlog::debug("register: {} and {} points", src.size(), tgt.size());
    const auto start = Clock::now();
    Outcome r;
    switch (method) {
        case Method::kIcp:
            r = run_icp(src, tgt, init, reg::IcpMethod::kPointToPoint, o);
            break;
        case Method::kPointToPlane:
            r = run_icp(src, tgt, init, reg::IcpMethod::kPointToPlane, o);
            break;
        case Method::kGicp:
            r = run_icp(src, tgt, init, reg::IcpMethod::kGeneralized, o);
            break;
        case Method::kFpfhTeaser:
            r = run_teaser(src, tgt, voxel, o);
            break;
        case Method::kFpfhRansac:
            r = run_ransac(src, tgt, voxel, o);
            break;
        case Method::kStein:
            r = run_stein(src, tgt, init, o);
            break;
    }
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    check_converged(r, method, voxel, o);
    io::write_file_atomically(
        o.out, [&](std::ostream& file) { file << matrix_text(r.T_target_source.matrix()); });
    print_report(r, ms, out);
}

}  // namespace scantling::app
