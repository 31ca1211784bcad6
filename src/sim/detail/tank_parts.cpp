#include "tank_parts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim::detail {
namespace {

// Stiffeners stop this far from the edge of an opening they would cross (a real opening is
// reinforced and the stiffener sniped).
constexpr double kOpeningClearance_m = 0.05;

// The [0, length] intervals of a stiffener that remain after cutting out openings.
std::vector<std::pair<double, double>> uncut_segments(const Wall& wall, double v_lo, double v_hi) {
    std::vector<std::pair<double, double>> segments{{0.0, wall.length_m()}};
    for (const Rect2& hole : wall.holes) {
        if (hole.v1 + kOpeningClearance_m <= v_lo || hole.v0 - kOpeningClearance_m >= v_hi) {
            continue;
        }
        const double cut0 = hole.u0 - kOpeningClearance_m;
        const double cut1 = hole.u1 + kOpeningClearance_m;
        std::vector<std::pair<double, double>> kept;
        for (const auto& [a, b] : segments) {
            if (cut0 > a) kept.emplace_back(a, std::min(b, cut0));
            if (cut1 < b) kept.emplace_back(std::max(a, cut1), b);
        }
        segments = std::move(kept);
    }
    return segments;
}

}  // namespace

void add_wall(MeshBuilder& builder, const Wall& wall, int tag) {
    std::vector<Loop3> holes;
    for (const Rect2& h : wall.holes) {
        holes.push_back(rectangle(wall.c00, wall.u(), wall.v(), h.u0, h.u1, h.v0, h.v1));
    }
    builder.add_polygon({wall.c00, wall.c10, wall.c11, wall.c01}, holes, wall.normal, tag);
}

std::vector<double> even_positions(double width_m, double spacing_m) {
    const int n = std::max(0, static_cast<int>(std::lround(width_m / spacing_m)) - 1);
    std::vector<double> positions;
    for (int k = 1; k <= n; ++k) positions.push_back(width_m * k / (n + 1));
    return positions;
}

FrameLine add_longitudinal(MeshBuilder& builder, const Wall& wall, double v_m,
                           const StiffenerConfig& stiffener, int number) {
    const int tag = builder.surface(fmt::format("longitudinal_{}", number));
    const double t = stiffener.thickness_m;
    const double h = stiffener.height_m;
    const double flange = stiffener.profile == ProfileKind::Angle ? stiffener.flange_width_m : 0.0;
    const Eigen::Vector3d u = wall.u(), v = wall.v(), n = wall.normal;
    for (const auto& [a, b] : uncut_segments(wall, v_m - 0.5 * t, v_m + 0.5 * t + flange)) {
        // The web starts on the wall plane (coplanar with it: no gap at the weld).
        builder.add_box(
            box_between(wall.c00, u, v, n, {a, v_m - 0.5 * t, 0.0}, {b, v_m + 0.5 * t, h}), tag);
        if (flange > 0.0) {
            builder.add_box(box_between(wall.c00, u, v, n, {a, v_m - 0.5 * t, h - t},
                                        {b, v_m + 0.5 * t + flange, h}),
                            tag);
        }
    }
    FrameLine line;
    line.number = number;
    line.point = wall.at(0.0, v_m) + h * n;
    line.axis = u;
    line.surface = wall.name;
    return line;
}

Eigen::Vector3d point_at_x(const FrameLine& line, double x_m) {
    return line.point + ((x_m - line.point.x()) / line.axis.x()) * line.axis;
}

void add_frame_landmarks(WorldMetadata& metadata, int compartment, const FrameLine& frame,
                         double face_x_m, std::span<const FrameLine> longitudinals) {
    for (const FrameLine& longitudinal : longitudinals) {
        Landmark landmark;
        landmark.id = static_cast<int>(metadata.landmarks.size());
        landmark.kind = LandmarkKind::FrameLongitudinal;
        landmark.position = point_at_x(longitudinal, face_x_m);
        landmark.compartment = compartment;
        landmark.frame = frame.number;
        landmark.longitudinal = longitudinal.number;
        metadata.landmarks.push_back(landmark);
    }
}

void add_connection(WorldMetadata& metadata, Connection connection) {
    connection.id = static_cast<int>(metadata.connections.size());
    metadata.connections.push_back(connection);
    for (const int compartment : {connection.compartment_a, connection.compartment_b}) {
        if (compartment == Connection::kOutside) continue;
        Landmark landmark;
        landmark.id = static_cast<int>(metadata.landmarks.size());
        landmark.kind = LandmarkKind::ManholeCentre;
        landmark.position = connection.centre;
        landmark.compartment = compartment;
        landmark.connection = connection.id;
        metadata.landmarks.push_back(landmark);
    }
}

void add_compartment(WorldMetadata& metadata, std::string name, const Eigen::Vector3d& min,
                     const Eigen::Vector3d& max, int level) {
    Compartment c;
    c.id = static_cast<int>(metadata.compartments.size());
    c.name = std::move(name);
    c.bounds.extend(min);
    c.bounds.extend(max);
    c.level = level;
    metadata.compartments.push_back(c);
}

}  // namespace scantling::sim::detail
