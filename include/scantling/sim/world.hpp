#pragma once
/// @file
/// A simulated world: a triangle mesh, one surface tag per triangle, and the metadata that
/// surveyors and the localisation use (compartments, manholes, frame and longitudinal numbers,
/// landmarks, defects: io::StructuralMap). SPEC §7, §8, §10.
///
/// Frame: everything is in the world frame, metres, z up. Orientation: triangles are
/// counter-clockwise seen from the free space they face, i.e. normals point into the space a
/// robot moves in: into the tank for a tank's shell, out of the material for plates, members
/// and outside-inspected objects (cylinder, storage tank). Ray casting is double-sided anyway.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/triangle_mesh.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/sim/surface_obstacles_truth.hpp>

namespace scantling::sim {

// The metadata types live in io (structural_map.hpp), so algorithms can read a recording's
// world/metadata.json without seeing sim; sim keeps its names for them.
using io::Compartment;
using io::Connection;
using io::ConnectionKind;
using io::Defect;
using io::DefectKind;
using io::FrameLine;
using io::Landmark;
using io::LandmarkKind;
using io::Surface;
using io::to_string;
using WorldMetadata = io::StructuralMap;

struct World {
    TriangleMesh mesh;
    std::vector<int> surface_tags;  ///< one per triangle, index into metadata.surfaces
    WorldMetadata metadata;
    /// Ground truth of the obstacles on the surface (surface_obstacles_truth.hpp): the plate's
    /// edges and holes, and the bolts, brackets and weld beads a scenario places; their
    /// triangles are in `mesh` (a placed obstacle has its own surface, named as its truth).
    /// Simulation-only: not written by write_world.
    std::vector<ObstacleTruth> obstacles{};
};

/// Throws InputError naming `what` when the mesh is invalid, the tags are not one per triangle
/// or not valid surface indices, an id/compartment reference is out of range, or an obstacle
/// truth is not finite, has radius_m <= 0 or height_m = 0, or repeats a name.
void check_valid(const World& world, std::string_view what);

/// Tag of the surface called `name`, or -1.
int find_surface(const WorldMetadata& metadata, std::string_view name);

/// Id of the defect covering the surface point `p` on surface `surface_tag`, or -1: within
/// 1 cm of the defect's plane and within radius_m of the centre (corrosion) or within 1 cm of
/// the crack segment (a crack is a hairline). O(number of defects).
int defect_at(const WorldMetadata& metadata, const Eigen::Vector3d& p, int surface_tag);

}  // namespace scantling::sim
