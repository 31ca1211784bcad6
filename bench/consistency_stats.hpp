#pragma once
/// @file NEES and yaw-mode statistics of the consistency experiment (consistency_experiment.cpp).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include <scantling/core/se3.hpp>

namespace scantling::bench {

/// NEES of `e` against `cov` restricted to `dofs`; NaN when that block is not positive definite.
double nees(const Vector6d& e, const Matrix6d& cov, const std::vector<int>& dofs);

/// NEES of one estimator over the trials, against its χ²(d) band.
struct NeesStats {
    std::string label;
    int dof = 6;
    int trials = 0;
    int accepted = 0;       ///< converged (ICP) and through the overlap gate
    int no_covariance = 0;  ///< accepted without a covariance (degenerate, too few cells)
    std::vector<double> nees;
    std::vector<double> trans_err_m;
    std::vector<double> rot_err_deg;

    /// One trial: `ok` = accepted; `n` = its NEES (NaN: none).
    void add(bool ok, double n, const Eigen::Isometry3d& T_est, const Eigen::Isometry3d& T_true);
};

/// Prints the table header of print_row.
void print_header();
/// One markdown row: accepted, NEES n, mean, median, 95 % band of the mean, share of trials
/// under χ²₀.₉₅(d), median translation and rotation errors.
void print_row(const NeesStats& s);

/// Yaw modes of Stein-ICP in the column: how often the particles split into several KDE modes,
/// and how often the KDE mode and the particle mean land within 10° of the true yaw.
struct YawStats {
    int trials = 0, multi_modal = 0;
    int mode_hits = 0, mean_hits = 0;              ///< all trials
    int multi_mode_hits = 0, multi_mean_hits = 0;  ///< trials with >= 2 modes
    double mode_abs_sum_rad = 0.0, mean_abs_sum_rad = 0.0;
    std::vector<int> num_modes_histogram = std::vector<int>(6, 0);  ///< 1, 2, ..., >= 6 modes

    void add(double mode_err_rad, double mean_err_rad, int num_modes);
};

void print_yaw(const YawStats& y);

}  // namespace scantling::bench
