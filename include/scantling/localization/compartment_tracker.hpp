#pragma once
/// @file
/// Which compartment the robot is in, followed through the map tree (SPEC §7, art. B): the
/// compartment changes only when the robot's path passes through a manhole (or another
/// connection) of the compartment it is in, never because an estimate strayed across a wall.
/// In a tank of identical bays this is what keeps the landmarks of the bay next door (a frame
/// spacing away, looking the same) out of the association.
///
/// Thread-safety: plain state, one per robot.

#include <Eigen/Core>
#include <optional>

#include <scantling/io/structural_map.hpp>

namespace scantling::localization {

class CompartmentTracker {
  public:
    /// `map` must outlive the tracker (nullptr: no structure, the compartment stays unknown).
    /// `margin_m`: how far outside an opening's edges a crossing still counts (the estimate's
    /// error), >= 0.
    explicit CompartmentTracker(const io::StructuralMap* map, double margin_m = 0.1);

    /// Forgets the history: the compartment is `id` (-1: unknown).
    void reset(int id) { current_ = id; }
    /// Sets the compartment from where the robot is (compartment_at), e.g. after a
    /// re-localisation; unknown outside every compartment.
    void locate(const Eigen::Vector3d& p_world);
    /// The robot moved from `from` to `to` (consecutive estimates): crossing an opening of the
    /// current compartment moves it to the compartment on the other side (-1: outside the tank).
    /// While unknown, the compartment is located at `to`. Returns the compartment afterwards.
    int move(const Eigen::Vector3d& from_world, const Eigen::Vector3d& to_world);
    int current() const { return current_; }

  private:
    /// The connection of the current compartment the segment passes through, if any.
    std::optional<int> crossed(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

    const io::StructuralMap* map_ = nullptr;
    double margin_m_ = 0.1;
    int current_ = -1;
};

}  // namespace scantling::localization
