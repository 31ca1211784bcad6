#include "scantling/localization/compartment_tracker.hpp"

#include <cmath>

#include <scantling/core/error.hpp>

namespace scantling::localization {
namespace {

/// The opening's width axis (horizontal in a wall, across the ship in a deck) and height axis.
std::pair<Eigen::Vector3d, Eigen::Vector3d> opening_axes(const Eigen::Vector3d& normal) {
    Eigen::Vector3d width = normal.cross(Eigen::Vector3d::UnitZ());
    if (width.norm() < 1e-6) width = Eigen::Vector3d::UnitY();
    width.normalize();
    return {width, normal.cross(width).normalized()};
}

bool passes_through(const io::Connection& c, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                    double margin_m) {
    const double s0 = c.normal.dot(from - c.centre);
    const double s1 = c.normal.dot(to - c.centre);
    if ((s0 > 0.0) == (s1 > 0.0) || s0 == s1) return false;
    const Eigen::Vector3d q = from + (s0 / (s0 - s1)) * (to - from) - c.centre;
    const auto [width, height] = opening_axes(c.normal);
    return std::abs(q.dot(width)) <= 0.5 * c.width_m + margin_m &&
           std::abs(q.dot(height)) <= 0.5 * c.height_m + margin_m;
}

}  // namespace

CompartmentTracker::CompartmentTracker(const io::StructuralMap* map, double margin_m)
    : map_(map), margin_m_(margin_m) {
    if (!(margin_m >= 0.0) || !std::isfinite(margin_m)) {
        throw ConfigError("compartment tracker: margin_m must be finite and >= 0");
    }
}

void CompartmentTracker::locate(const Eigen::Vector3d& p_world) {
    const auto c = map_ != nullptr ? io::compartment_at(*map_, p_world) : std::nullopt;
    current_ = c ? *c : -1;
}

std::optional<int> CompartmentTracker::crossed(const Eigen::Vector3d& from,
                                               const Eigen::Vector3d& to) const {
    for (const io::Connection& c : map_->connections) {
        if (c.compartment_a != current_ && c.compartment_b != current_) continue;
        if (passes_through(c, from, to, margin_m_)) return c.id;
    }
    return std::nullopt;
}

int CompartmentTracker::move(const Eigen::Vector3d& from_world, const Eigen::Vector3d& to_world) {
    if (map_ == nullptr || !from_world.allFinite() || !to_world.allFinite()) return current_;
    if (current_ < 0) {
        locate(to_world);
        return current_;
    }
    if (const auto id = crossed(from_world, to_world)) {
        const io::Connection& c = map_->connections[static_cast<std::size_t>(*id)];
        current_ = c.compartment_a == current_ ? c.compartment_b : c.compartment_a;
    }
    return current_;
}

}  // namespace scantling::localization
