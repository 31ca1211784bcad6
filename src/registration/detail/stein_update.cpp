#include "stein_update.hpp"

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
            const BatchGradient g = batch_gradient(particles[i], source, idx, tree, normals,
                                                   config.max_correspondence_distance_m);
            state.grad_log_p[i] = scale * g.sum;
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

}  // namespace

void run_svgd(std::vector<Vector6d>& particles, std::span<const Eigen::Vector3d> source,
              const KdTree& target_tree, std::span<const Eigen::Vector3d> target_normals,
              const SteinIcpConfig& config) {
    SvgdState state{std::vector<Vector6d>(particles.size(), Vector6d::Zero()),
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
}

}  // namespace scantling::registration::detail
