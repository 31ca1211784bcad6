#pragma once
// The exploration loop's figures (exploration_mission.hpp): what it measures on the truth per
// tick, the explored-volume curve, and the files it writes into mission/.
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include <scantling/mission/exploration_mission.hpp>
#include <scantling/sim/motion_state.hpp>
#include <scantling/sim/sensor_mount.hpp>

#include "reachable_volume.hpp"

namespace scantling::mission::detail {

class ExplorationFigures {
  public:
    ExplorationFigures(const ExplorationMissionScenario& scenario, ReachableVolume reachable);

    /// Once per tick: the truth against the estimate, the distance flown, the clearance.
    void add_tick(const sim::SceneView& scene, const sim::MotionState& truth,
                  const localization::DroneState& estimate, control::MissionState state,
                  double t_s);
    void add_image(std::size_t sightings);
    /// A point of the explored-volume curve when `volume_every_s` has passed (and at `force`).
    void sample_volume(const ExplorationStack& stack, double t_s, bool force = false);
    /// The exploration ended (no gain left, or stopped) at `t_s`.
    void mark_ended(double t_s);

    ExplorationMissionResult result(const ExplorationStack& stack) const;
    double reachable_share(const mapping::OccupancyOctree& map) const;

  private:
    const ExplorationMissionScenario& scenario_;
    ReachableVolume reachable_;
    ExplorationMissionResult result_;
    std::optional<Eigen::Vector3d> previous_p_;
    double error_sq_sum_ = 0.0;
    std::size_t ticks_ = 0;
    double next_sample_s_ = 0.0;
    double next_clearance_s_ = 0.0;
    std::optional<double> ended_s_;
};

/// mission/summary.json's figures.
std::string exploration_summary_json(const ExplorationMissionScenario& scenario,
                                     const ExplorationMissionResult& result);
/// mission/exploration.csv: the explored-volume curve.
std::string exploration_curve_csv(const ExplorationMissionResult& result);
/// mission/plans.csv: one line per planning iteration.
std::string exploration_plans_csv(const ExplorationStack& stack);

}  // namespace scantling::mission::detail
