#pragma once
/// @file
/// The crawler's stop-and-map scored on the truth (crawler_mission.hpp): obstacle precision and
/// recall per stop against the world's labelled obstacles, and the stops' map and PF poses
/// against the true pose.
///
/// Scoring, per stop, in the body frame of the TRUE pose at the stop (so that the detection is
/// judged, not the localisation): a labelled obstacle is in view when a point of its axis (every
/// centimetre) falls in an observed cell of the stop's grid (any label but unknown); it is found
/// when a cluster of its sign (positive or negative) comes within its radius + kMatchToleranceM
/// of its axis (distance from the axis samples to the cluster's extent). A cluster is right when
/// it is within that distance of any labelled obstacle of its sign. Recall = found / in view per
/// class, precision = right / clusters per sign, both summed over the stops (an obstacle seen at
/// three stops counts three times: each stop's map is what the crawler drives on).

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include <scantling/mission/crawler_mission.hpp>
#include <scantling/perception/stop_and_map.hpp>
#include <scantling/sim/surface_obstacles_truth.hpp>

namespace scantling::mission::detail {

/// A cluster this close to an obstacle's footprint (beyond its radius) matches it: 1.5 cells of
/// the 2 cm grid, the blur of a voxel and a cell edge.
inline constexpr double kMatchToleranceM = 0.03;

class StopMetrics {
  public:
    explicit StopMetrics(std::vector<sim::ObstacleTruth> truths) : truths_(std::move(truths)) {}

    /// One stop and the true pose of the robot during it.
    void add(const perception::StopMap& stop, const Eigen::Isometry3d& T_world_body_true);
    CrawlerStopScores scores() const;

  private:
    std::vector<sim::ObstacleTruth> truths_;
    CrawlerStopScores sums_;
    double map_sq_sum_ = 0.0, pf_sq_sum_ = 0.0;
};

}  // namespace scantling::mission::detail
