#pragma once
/// @file
/// A simulated world: a triangle mesh, one surface tag per triangle, and the metadata that
/// surveyors and the localisation use (compartments, manholes, frame and longitudinal numbers,
/// landmarks, defects). SPEC §7, §8, §10.
///
/// Frame: everything is in the world frame, metres, z up. Orientation: triangles are
/// counter-clockwise seen from the free space they face, i.e. normals point into the space a
/// robot moves in: into the tank for a tank's shell, out of the material for plates, members
/// and outside-inspected objects (cylinder, storage tank). Ray casting is double-sided anyway.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/bounds.hpp>
#include <scantling/core/triangle_mesh.hpp>

namespace scantling::sim {

/// What a surface tag stands for. `tag` equals the index in WorldMetadata::surfaces.
struct Surface {
    int tag = 0;
    std::string name;      ///< e.g. "side_shell", "web_frame", "longitudinal_3"
    bool textured = true;  ///< carries visual texture (stereo points exist only on textured)
    double albedo = 0.5;   ///< diffuse reflectance in [0, 1] (camera, LiDAR intensity)
};

/// A space of the world a robot can be in; `bounds` is axis-aligned and may include some
/// structure (e.g. the dead space behind a sloped hopper).
struct Compartment {
    int id = 0;  ///< index in WorldMetadata::compartments
    std::string name;
    Aabb bounds;
    int level = 0;  ///< deck level, 0 = lowest
};

enum class ConnectionKind {
    Manhole,          ///< opening in a web frame or bulkhead
    LevelTransition,  ///< opening in a deck between two levels
    Entry,            ///< opening to the outside (compartment_b = kOutside)
};

/// A passage between two compartments (an edge of the map tree of SPEC §7).
struct Connection {
    static constexpr int kOutside = -1;

    int id = 0;
    ConnectionKind kind = ConnectionKind::Manhole;
    int compartment_a = 0;
    int compartment_b = kOutside;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();   ///< centre of the opening, mid-plate
    Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  ///< unit, pointing from a to b
    double width_m = 0.0;                               ///< horizontal size of the opening
    double height_m = 0.0;  ///< the other size (vertical in a wall, along x in a deck)
};

/// A numbered structural member surveyors quote positions by.
/// Web frame (or bulkhead, or tray): the plane through `point` with normal `axis`.
/// Longitudinal: the line through `point` along `axis`, at the free edge (toe) of the profile,
/// in the middle of its web.
struct FrameLine {
    int number = 0;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  ///< unit
    std::string surface;  ///< name of the surface it is on / is (e.g. "side_shell")
};

enum class LandmarkKind {
    FrameLongitudinal,  ///< toe of a longitudinal where it meets a frame face (on a surface)
    ManholeCentre,      ///< centre of an opening (in the air, mid-plate)
};

/// A 3D point of the map tree (SPEC §7, art. B). Each compartment lists its own landmarks, so
/// a manhole centre appears once for each compartment it joins.
struct Landmark {
    int id = 0;  ///< index in WorldMetadata::landmarks
    LandmarkKind kind = LandmarkKind::FrameLongitudinal;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    int compartment = 0;
    int frame = -1;         ///< FrameLine::number of the frame, -1 if none
    int longitudinal = -1;  ///< FrameLine::number of the longitudinal, -1 if none
    int connection = -1;    ///< Connection::id for a manhole centre, -1 otherwise
};

enum class DefectKind { Corrosion, Crack };

/// A defect patch: the disc of `radius_m` around `centre` on the surface `surface_tag`
/// (a crack is the segment of half-length radius_m along `direction`).
struct Defect {
    int id = 0;
    DefectKind kind = DefectKind::Corrosion;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();      ///< on the surface
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();     ///< unit, into free space
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit, tangent to the surface
    double radius_m = 0.0;
    int surface_tag = 0;
    int compartment = -1;  ///< compartment it is seen from, -1 when outside all
};

struct WorldMetadata {
    std::string name;  ///< world kind, e.g. "ballast_tank_mockup"
    std::vector<Surface> surfaces;
    std::vector<Compartment> compartments;
    std::vector<Connection> connections;
    std::vector<FrameLine> frames;
    std::vector<FrameLine> longitudinals;
    std::vector<Landmark> landmarks;
    std::vector<Defect> defects;
};

struct World {
    TriangleMesh mesh;
    std::vector<int> surface_tags;  ///< one per triangle, index into metadata.surfaces
    WorldMetadata metadata;
};

/// Throws InputError naming `what` when the mesh is invalid, the tags are not one per triangle
/// or not valid surface indices, or an id/compartment reference is out of range.
void check_valid(const World& world, std::string_view what);

/// Tag of the surface called `name`, or -1.
int find_surface(const WorldMetadata& metadata, std::string_view name);

/// Id of the first compartment whose bounds contain `p` (borders included), or -1.
int compartment_at(const WorldMetadata& metadata, const Eigen::Vector3d& p);

/// Id of the defect covering the surface point `p` on surface `surface_tag`, or -1: within
/// 1 cm of the defect's plane and within radius_m of the centre (corrosion) or within 1 cm of
/// the crack segment (a crack is a hairline). O(number of defects).
int defect_at(const WorldMetadata& metadata, const Eigen::Vector3d& p, int surface_tag);

std::string_view to_string(ConnectionKind kind);
std::string_view to_string(LandmarkKind kind);
std::string_view to_string(DefectKind kind);

}  // namespace scantling::sim
