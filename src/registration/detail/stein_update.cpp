#include "stein_update.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include <scantling/core/parallel.hpp>
#include <scantling/core/random.hpp>

#include "stein_gradient.hpp"
#include "stein_summary.hpp"

namespace scantling::registration::detail {
namespace {

constexpr double kBeta1 = 0.9;  // Adam's published defaults
constexpr double kBeta2 = 0.999;
constexpr double kAdamEpsilon = 1e-12;  // the gradients span many decades: keep it negligible

/// The DoFs sharing one kernel and one learning rate (translation or rotation).
struct Block {
    std::vector<int> dofs;
    double lr = 0.0;
    double bandwidth = 1.0;  ///< h of exp(−d² / h)
};

double sq_distance(const Vector6d& a, const Vector6d& b, const Block& block) {
    double sum = 0.0;
    for (const int d : block.dofs) {
        const double diff = difference(a[d], b[d], is_angle(d));
        sum += diff * diff;
    }
    return sum;
}

/// Median heuristic h = median(d²) / log K (Liu & Wang 2016).
double median_bandwidth(const std::vector<Vector6d>& particles, const Block& block) {
    std::vector<double> d2;
    for (std::size_t i = 0; i < particles.size(); ++i) {
        for (std::size_t j = i + 1; j < particles.size(); ++j) {
            d2.push_back(sq_distance(particles[i], particles[j], block));
        }
    }
    auto mid = d2.begin() + static_cast<std::ptrdiff_t>(d2.size() / 2);
    std::nth_element(d2.begin(), mid, d2.end());
    const double h = *mid / std::log(static_cast<double>(particles.size()));
    return h > 0.0 ? h : 1.0;  // coincident particles: no repulsion either way
}

struct Adam {
    Vector6d m = Vector6d::Zero();
    Vector6d v = Vector6d::Zero();
};

struct SvgdState {
    std::vector<Vector6d> grad_log_p;
    std::vector<Matrix6d> information;  ///< −∇² log p (Gauss-Newton) per particle
    std::vector<Matrix6d> grad_noise;   ///< covariance of grad_log_p's batch estimate
    std::vector<Adam> adam;
    std::vector<Block> blocks;
};

std::vector<Block> make_blocks(const SteinIcpConfig& config) {
    if (config.reduced_3dof) {
        return {{{0, 1}, config.translation_lr_m}, {{5}, config.rotation_lr_rad}};
    }
    return {{{0, 1, 2}, config.translation_lr_m}, {{3, 4, 5}, config.rotation_lr_rad}};
}

/// ∇log p of every particle from its own random batch (stream t · K + i).
void compute_gradients(const std::vector<Vector6d>& particles,
                       std::span<const Eigen::Vector3d> source, const KdTree& tree,
                       std::span<const Eigen::Vector3d> normals, const SteinIcpConfig& config,
                       int iteration, SvgdState& state) {
    const Rng base(config.seed);
    const std::size_t k = particles.size();
    const std::size_t batch = std::min<std::size_t>(config.batch_size, source.size());
    // log p = −Σ r² / (2σ²) over all N points; the batch sum is scaled up by N / B.
    const double scale =
        -static_cast<double>(source.size()) /
        (static_cast<double>(batch) * 2.0 * config.noise_sigma_m * config.noise_sigma_m);
    parallel_for(config.parallel, k, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            Rng rng = base.split(static_cast<std::uint64_t>(iteration) * k + i);
            const std::vector<std::size_t> idx = rng.sample_indices(source.size(), batch);
            const BatchGradient g =
                batch_gradient(particles[i], source, idx, tree, normals,
                               config.max_correspondence_distance_m, config.back_faces);
            state.grad_log_p[i] = scale * g.sum;
            // −∇² log p = Σ Jᵀ J / σ² (Gauss-Newton) over all N points: −2 · scale times the
            // batch sum.
            state.information[i] = -2.0 * scale * g.information;
            // The batch is a sample without replacement of B of the N per-point gradients:
            // Var(scale · Σ) = scale² · m · (1 − B / N) · (their sample covariance).
            const auto m = static_cast<double>(g.num_inliers);
            state.grad_noise[i].setZero();
            if (g.num_inliers >= 2) {
                const Matrix6d cov = (g.sum_outer - g.sum * g.sum.transpose() / m) / (m - 1.0);
                const double fpc =
                    1.0 - static_cast<double>(batch) / static_cast<double>(source.size());
                state.grad_noise[i] = scale * scale * m * fpc * cov;
            }
        }
    });
}

/// φ(xᵢ) of one block: kernel-weighted gradients plus the kernel's repulsion.
void add_phi(const std::vector<Vector6d>& particles, const SvgdState& state, const Block& block,
             std::size_t i, Vector6d& phi) {
    for (std::size_t j = 0; j < particles.size(); ++j) {
        const double kernel =
            std::exp(-sq_distance(particles[j], particles[i], block) / block.bandwidth);
        for (const int d : block.dofs) {
            const double repulsion =
                2.0 / block.bandwidth * difference(particles[i][d], particles[j][d], is_angle(d));
            phi[d] += kernel * (state.grad_log_p[j][d] + repulsion);
        }
    }
}

void adam_step(const Vector6d& phi, const Block& block, double lr_scale, int step, Adam& adam,
               Vector6d& x) {
    const double c1 = 1.0 - std::pow(kBeta1, step), c2 = 1.0 - std::pow(kBeta2, step);
    for (const int d : block.dofs) {
        adam.m[d] = kBeta1 * adam.m[d] + (1.0 - kBeta1) * phi[d];
        adam.v[d] = kBeta2 * adam.v[d] + (1.0 - kBeta2) * phi[d] * phi[d];
        x[d] += block.lr * lr_scale * (adam.m[d] / c1) / (std::sqrt(adam.v[d] / c2) + kAdamEpsilon);
        if (is_angle(d)) x[d] = wrap_angle(x[d]);
    }
}

void svgd_step(std::vector<Vector6d>& particles, SvgdState& state, double lr_scale, int step,
               const ParallelConfig& parallel) {
    for (Block& b : state.blocks) b.bandwidth = median_bandwidth(particles, b);
    std::vector<Vector6d> next = particles;
    const double inv_k = 1.0 / static_cast<double>(particles.size());
    parallel_for(parallel, particles.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            for (const Block& b : state.blocks) {
                Vector6d phi = Vector6d::Zero();
                add_phi(particles, state, b, i, phi);
                adam_step(phi * inv_k, b, lr_scale, step, state.adam[i], next[i]);
            }
        }
    });
    particles.swap(next);
}

/// Free DoFs in block order (the blocks partition them).
std::vector<int> free_dofs(const SvgdState& state) {
    std::vector<int> dofs;
    for (const Block& b : state.blocks) dofs.insert(dofs.end(), b.dofs.begin(), b.dofs.end());
    return dofs;
}

/// One step of preconditioned Langevin dynamics with the batch-noise correction of stochastic
/// gradient Fisher scoring (Ahn, Korattikara & Welling 2012), F the particles' mean information:
///   xᵢ += ε F⁻¹ ĝᵢ + ξᵢ,   ξᵢ ~ N(0, ε (2 − ε) F⁻¹ − ε² F⁻¹ Cᵢ F⁻¹),
/// ĝᵢ the batch estimate of ∇log p and Cᵢ its covariance. On a Gaussian posterior N(μ, F⁻¹) the
/// deterministic part maps xᵢ − μ to (1 − ε)(xᵢ − μ), and the injected plus the batch noise
/// make the stationary covariance exactly F⁻¹, whatever ε: the spread is the posterior's, not
/// a learning rate's. Each particle moves in its own basin, so the modes found by the SVGD
/// steps are kept. A particle whose batch noise alone would exceed that budget takes a smaller ε.
void langevin_step(std::vector<Vector6d>& particles, const SvgdState& state, double step,
                   bool cap_step, double max_distance_m, const Rng& noise_streams,
                   std::uint64_t stream_base, const ParallelConfig& parallel) {
    const std::vector<int> dofs = free_dofs(state);
    const auto n = static_cast<Eigen::Index>(dofs.size());
    auto restrict = [&](const Matrix6d& m) {
        Eigen::MatrixXd r(n, n);
        for (Eigen::Index a = 0; a < n; ++a) {
            for (Eigen::Index b = 0; b < n; ++b) {
                r(a, b) = m(dofs[static_cast<std::size_t>(a)], dofs[static_cast<std::size_t>(b)]);
            }
        }
        return r;
    };
    Eigen::MatrixXd F = Eigen::MatrixXd::Zero(n, n);
    for (const Matrix6d& info : state.information) F += restrict(info);
    F /= static_cast<double>(particles.size());
    // A direction the points do not constrain (a corridor's axis) has F ≈ 0: its posterior is
    // flat and the noise would carry the particles away without end. A weak Gaussian prior
    // about the particles' mean, one correspondence distance (translation) and one radian
    // (rotation) wide, far below any real curvature, bounds it there (the spread then reports
    // that width) without changing the constrained directions.
    Eigen::VectorXd prior_info(n), centre(n);
    for (Eigen::Index a = 0; a < n; ++a) {
        const int dof = dofs[static_cast<std::size_t>(a)];
        const double scale = is_angle(dof) ? 1.0 : max_distance_m;
        prior_info[a] = 1.0 / (scale * scale);
        F(a, a) += prior_info[a];
        double sum = 0.0, s = 0.0, c = 0.0;
        for (const Vector6d& x : particles) {
            sum += x[dof];
            s += std::sin(x[dof]);
            c += std::cos(x[dof]);
        }
        centre[a] = is_angle(dof) ? std::atan2(s, c) : sum / static_cast<double>(particles.size());
    }
    const Eigen::MatrixXd F_inv = F.inverse();  // n <= 6, symmetric positive definite
    parallel_for(parallel, particles.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            Eigen::VectorXd g(n);
            for (Eigen::Index a = 0; a < n; ++a) {
                const int dof = dofs[static_cast<std::size_t>(a)];
                g[a] = state.grad_log_p[i][dof] -
                       prior_info[a] * difference(particles[i][dof], centre[a], is_angle(dof));
            }
            const Eigen::MatrixXd C = restrict(state.grad_noise[i]);
            // The batch noise fits the budget when ε² C ≤ ε (2 − ε) F (Loewner order), i.e.
            // ε ≤ 2 / (1 + λ), λ the largest eigenvalue of C relative to F: smaller steps
            // for a noisy batch keep the stationary covariance F⁻¹ (only the mixing slows).
            const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rel(C, F);
            const double lambda = std::max(rel.eigenvalues().maxCoeff(), 0.0);
            const double eps = cap_step ? std::min(step, 2.0 / (1.0 + lambda)) : step;
            Eigen::MatrixXd noise_cov = eps * (2.0 - eps) * F_inv - eps * eps * F_inv * C * F_inv;
            noise_cov = 0.5 * (noise_cov + noise_cov.transpose());
            const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(noise_cov);
            Rng rng = noise_streams.split(stream_base + i);
            Eigen::VectorXd xi(n);
            for (Eigen::Index a = 0; a < n; ++a) {
                xi[a] = std::sqrt(std::max(eig.eigenvalues()[a], 0.0)) * rng.normal();
            }
            const Eigen::VectorXd dx = eps * (F_inv * g) + eig.eigenvectors() * xi;
            for (Eigen::Index a = 0; a < n; ++a) {
                const int dof = dofs[static_cast<std::size_t>(a)];
                particles[i][dof] += dx[a];
                if (is_angle(dof)) particles[i][dof] = wrap_angle(particles[i][dof]);
            }
        }
    });
}

}  // namespace

void run_svgd(std::vector<Vector6d>& particles, std::span<const Eigen::Vector3d> source,
              const KdTree& target_tree, std::span<const Eigen::Vector3d> target_normals,
              const SteinIcpConfig& config) {
    SvgdState state{std::vector<Vector6d>(particles.size(), Vector6d::Zero()),
                    std::vector<Matrix6d>(particles.size(), Matrix6d::Zero()),
                    std::vector<Matrix6d>(particles.size(), Matrix6d::Zero()),
                    std::vector<Adam>(particles.size()), make_blocks(config)};
    const int t_max = config.iterations;
    for (int t = 0; t < t_max; ++t) {
        compute_gradients(particles, source, target_tree, target_normals, config, t, state);
        // Geometric decay from 1 to final_lr_fraction over the iterations.
        const double lr_scale =
            t_max > 1 ? std::pow(config.final_lr_fraction, static_cast<double>(t) / (t_max - 1))
                      : 1.0;
        svgd_step(particles, state, lr_scale, t + 1, config.parallel);
    }
    // Batch streams use t · K + i for t < T + R; the Langevin noise takes the ones after.
    const Rng noise_streams(config.seed);
    const int t_all = t_max + config.refine_iterations;
    const auto k = static_cast<std::uint64_t>(particles.size());
    for (int t = 0; t < config.refine_iterations; ++t) {
        compute_gradients(particles, source, target_tree, target_normals, config, t_max + t, state);
        langevin_step(particles, state, config.refine_step, 2 * t >= config.refine_iterations,
                      config.max_correspondence_distance_m, noise_streams,
                      static_cast<std::uint64_t>(t_all + t) * k, config.parallel);
    }
}

}  // namespace scantling::registration::detail
