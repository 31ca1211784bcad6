#pragma once
// Walls, longitudinals and landmarks shared by the tank builders (private to the simulator).

#include "mesh_builder.hpp"

#include <scantling/sim/world.hpp>
#include <scantling/sim/world_builders.hpp>

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <vector>

namespace scantling::sim::detail {

/// Rectangle [u0, u1] x [v0, v1] in a wall's (u, v) coordinates.
struct Rect2 {
    double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
};

/// A flat rectangular tank wall seen from inside. The corners are the exact points shared
/// with the neighbouring walls; u runs from c00 to c10 (along the longitudinals), v from c00
/// to c01, `normal` points into the tank.
struct Wall {
    std::string name;
    Eigen::Vector3d c00, c10, c11, c01;
    Eigen::Vector3d normal;
    std::vector<Rect2> holes;

    Eigen::Vector3d u() const { return (c10 - c00).normalized(); }
    Eigen::Vector3d v() const { return (c01 - c00).normalized(); }
    double length_m() const { return (c10 - c00).norm(); }
    double width_m() const { return (c01 - c00).norm(); }
    Eigen::Vector3d at(double a, double b) const { return c00 + a * u() + b * v(); }
};

/// The wall as a single surface facing `normal`, with its holes.
void add_wall(MeshBuilder& builder, const Wall& wall, int tag);

/// n = round(width / spacing) - 1 positions evenly spread inside (0, width): k width / (n + 1).
std::vector<double> even_positions(double width_m, double spacing_m);

/// Adds longitudinal `number` along u at v = v_m (cut around the wall's holes) as surface
/// "longitudinal_<number>" and returns its toe line.
FrameLine add_longitudinal(MeshBuilder& builder, const Wall& wall, double v_m,
                           const StiffenerConfig& stiffener, int number);

/// Point of a longitudinal's toe line (not parallel to x = const) in the plane x = x_m.
Eigen::Vector3d point_at_x(const FrameLine& line, double x_m);

/// Appends FrameLongitudinal landmarks of `compartment`: each longitudinal's toe on the face
/// x = face_x_m of `frame`.
void add_frame_landmarks(WorldMetadata& metadata, int compartment, const FrameLine& frame,
                         double face_x_m, std::span<const FrameLine> longitudinals);

/// Appends the connection and a ManholeCentre landmark for each compartment it joins.
void add_connection(WorldMetadata& metadata, Connection connection);

/// Box-shaped compartment.
void add_compartment(WorldMetadata& metadata, std::string name, const Eigen::Vector3d& min,
                     const Eigen::Vector3d& max, int level = 0);

}  // namespace scantling::sim::detail
