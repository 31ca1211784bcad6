#pragma once
/// @file
/// The structural map of a tank, hull or any inspected structure: the metadata that surveyors
/// and the localisation use besides the geometry (compartments, manholes, frame and
/// longitudinal numbers, landmarks, defects). SPEC §7, §8, §10. The simulator builds it with
/// every world and exports it as a recording's `world/metadata.json` (structural_map_to_json);
/// read_structural_map reads it back, so algorithms get it without seeing `sim` (issue 12
/// item 2, issue 13 item 0).
///
/// Frame: everything is in the world frame, metres, z up. Ids are positions: `Surface::tag`,
/// `Compartment::id`, `Connection::id`, `Landmark::id` and `Defect::id` equal the item's index in
/// its list (the reader refuses anything else, so `map.compartments[id]` is safe on a map it
/// returned). Frame and longitudinal numbers are the surveyors' numbers, unique per list, >= 0
/// (-1 means "none" in a landmark).
///
/// Thread-safety: plain data and pure functions; concurrent calls are safe.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/bounds.hpp>

namespace scantling::io {

/// What a surface tag stands for. `tag` equals the index in StructuralMap::surfaces.
struct Surface {
    int tag = 0;
    std::string name;      ///< e.g. "side_shell", "web_frame", "longitudinal_3"
    bool textured = true;  ///< carries visual texture (stereo points exist only on textured)
    double albedo = 0.5;   ///< diffuse reflectance in [0, 1] (camera, LiDAR intensity)

    bool operator==(const Surface&) const = default;
};

/// A space of the world a robot can be in; `bounds` is axis-aligned and may include some
/// structure (e.g. the dead space behind a sloped hopper).
struct Compartment {
    int id = 0;  ///< index in StructuralMap::compartments
    std::string name;
    Aabb bounds;
    int level = 0;  ///< deck level, 0 = lowest

    bool operator==(const Compartment& other) const {  // Aabb has no ==
        return id == other.id && name == other.name && bounds.min == other.bounds.min &&
               bounds.max == other.bounds.max && level == other.level;
    }
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

    bool operator==(const Connection&) const = default;
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

    bool operator==(const FrameLine&) const = default;
};

enum class LandmarkKind {
    FrameLongitudinal,  ///< toe of a longitudinal where it meets a frame face (on a surface)
    ManholeCentre,      ///< centre of an opening (in the air, mid-plate)
};

/// A 3D point of the map tree (SPEC §7, art. B). Each compartment lists its own landmarks, so
/// a manhole centre appears once for each compartment it joins.
struct Landmark {
    int id = 0;  ///< index in StructuralMap::landmarks
    LandmarkKind kind = LandmarkKind::FrameLongitudinal;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    int compartment = 0;
    int frame = -1;         ///< FrameLine::number of the frame, -1 if none
    int longitudinal = -1;  ///< FrameLine::number of the longitudinal, -1 if none
    int connection = -1;    ///< Connection::id for a manhole centre, -1 otherwise

    bool operator==(const Landmark&) const = default;
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

    bool operator==(const Defect&) const = default;
};

struct StructuralMap {
    std::string name;  ///< world kind, e.g. "ballast_tank_mockup"
    std::vector<Surface> surfaces;
    std::vector<Compartment> compartments;
    std::vector<Connection> connections;
    std::vector<FrameLine> frames;
    std::vector<FrameLine> longitudinals;
    std::vector<Landmark> landmarks;
    std::vector<Defect> defects;

    /// Exact equality of every field (what a write/read round trip keeps).
    bool operator==(const StructuralMap&) const = default;
};

/// Lower-case names used in the JSON ("manhole", "level_transition", "entry", ...).
std::string_view to_string(ConnectionKind kind);
std::string_view to_string(LandmarkKind kind);
std::string_view to_string(DefectKind kind);

/// The map as indented JSON with keys in a fixed order and doubles printed so that they read
/// back bit-exact (deterministic text). Layout: {"name", "surfaces", "compartments" (min/max
/// corners), "connections" (compartment_b = -1 for the outside), "frames", "longitudinals",
/// "landmarks", "defects"}, kinds as to_string gives them. When `surface_tags` (one per mesh
/// triangle) is given it is appended run-length encoded as "triangle_surface_tags":
/// [[tag, count], ...] in triangle order.
std::string structural_map_to_json(const StructuralMap& map,
                                   std::span<const int> surface_tags = {});

/// Largest file read_structural_map accepts (checked before reading), and the most JSON values
/// (objects, arrays, keys, numbers, strings) it builds, which bounds its memory to a few
/// hundred MB on hostile input; the largest simulated world (ship hull) has about 8 000.
inline constexpr std::size_t kMaxStructuralMapBytes = std::size_t{64} << 20;
inline constexpr std::size_t kMaxStructuralMapValues = 2'000'000;
/// Deepest nesting accepted (the layout nests 4 levels).
inline constexpr int kMaxStructuralMapDepth = 16;

/// Reads a map written by structural_map_to_json (a recording's `world/metadata.json`).
/// Every key of the layout is required, and `triangle_surface_tags` is optional: its pairs are
/// checked (tags of listed surfaces, counts >= 1) and then dropped, as they belong with the
/// mesh. Throws FileError when the file cannot be read, ParseError naming the file and the
/// field for ("world/metadata.json: compartments[1].min: expected 3 numbers"): a file over
/// kMaxStructuralMapBytes, more values or nesting than the limits above, malformed JSON, a
/// missing or unknown key, a wrong type, a non-finite number or one out of int range, an
/// unknown kind, an id that is not the item's index (duplicates first named as such), a
/// negative or repeated frame/longitudinal number, min > max in a compartment, an axis, normal or
/// direction not of unit length (within 1e-6), a negative size, an albedo outside [0, 1], and
/// a reference to a compartment, surface, connection, frame or longitudinal that does not
/// exist.
StructuralMap read_structural_map(const std::string& path);

/// The same checks on JSON text; `name` stands for the file in messages.
StructuralMap parse_structural_map(std::string_view text, const std::string& name);

/// The compartment whose bounds contain `p_world` (borders included); when several do (a
/// shared wall, nested compartments), the one with the smallest volume, and of equal volumes
/// the first listed. nullopt outside all. O(number of compartments).
std::optional<int> compartment_at(const StructuralMap& map, const Eigen::Vector3d& p_world);

/// The compartment with `id`, or nullptr.
const Compartment* find_compartment(const StructuralMap& map, int id);

/// Number of the frame nearest to `p_world`, a frame being the infinite plane through `point`
/// with normal `axis` (distance |(p − point) · axis|: where along the ship p is, whatever its
/// height or breadth); ties go to the first listed; nullopt when there are no frames.
std::optional<int> nearest_frame(const StructuralMap& map, const Eigen::Vector3d& p_world);

/// Number of the longitudinal nearest to `p_world`, a longitudinal being the infinite line
/// through `point` along `axis` (distance ‖(p − point) − ((p − point) · axis) axis‖: which
/// stiffener p is beside, wherever along the ship); ties go to the first listed; nullopt when
/// there are none.
std::optional<int> nearest_longitudinal(const StructuralMap& map, const Eigen::Vector3d& p_world);

}  // namespace scantling::io
