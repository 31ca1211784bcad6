#pragma once
/// @file
/// The structure of a distillation column in one depth frame (SPEC §7, art. F): the floor and
/// ceiling (tray decks or heads), the cylindrical wall (centre and radius, checked against the
/// known diameter) and the downcomer plate (a vertical chord plate, one per tray). Art. F
/// attempts a registration only when the wall has the known diameter and the unique downcomer
/// is in view: the wall's centre fixes x and y, the downcomer's direction from the axis fixes
/// the yaw that the column's symmetry leaves free.
///
/// Steps:
/// 1. planes by sequential RANSAC (plane_ransac.hpp); a plane whose normal is within
///    vertical_tolerance_deg of `up` is horizontal: the largest below the viewpoint is the
///    floor, the largest above it the ceiling;
/// 2. the wall by RANSAC on a circle about `up` (cylinder_ransac.hpp) over the points that are
///    on no horizontal plane and on no vertical plane wider than a strip of the wall could be
///    (a flat plate seen across the view would otherwise pull the circle onto a line), refitted
///    without the vertical planes the fit places well inside the wall (a plate seen beside
///    the wall pulls the first fit towards itself); diameter_ok when 2 R is within
///    diameter_tolerance_m of diameter_m, and then the axis is refitted with the known radius;
/// 3. the downcomer: the largest vertical plane (normal within vertical_tolerance_deg of
///    horizontal) at least min_chord_depth_m inside the wall (a chord, not a strip of the wall)
///    whose points, off the wall, cover at least min_downcomer_height_m along `up` without a
///    gap (support beams' faces and weirs are lower).
///
/// Deterministic (both searches are seeded). Reentrant. Cost: ~3 passes over the cloud per
/// plane and up to 3 wall fits of ≤ 10 passes each, plus the RANSAC hypotheses on fixed
/// 2000-point subsamples: ~45 ms for a 320 × 240 L515 frame on one core.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <scantling/core/point_cloud.hpp>
#include <scantling/perception/cylinder_ransac.hpp>
#include <scantling/perception/plane_ransac.hpp>

namespace scantling::perception {

struct ColumnStructureConfig {
    /// The column's inner diameter (SPEC §7 art. F and the simulator's distillation_column:
    /// Ø 3 m), metres, > 0.
    double diameter_m = 3.0;
    /// A wall whose fitted diameter differs by more is not this column (diameter_ok = false):
    /// 10 cm is ~10× the fit's error over a 90° arc and well below the 0.5 m between
    /// standard column sizes. Metres, > 0 and < diameter_m.
    double diameter_tolerance_m = 0.1;
    /// A plane is horizontal (vertical) when its normal is within this angle of `up` (of the
    /// horizontal plane): the IMU's gravity is good to ~1°, tray decks and plates are built
    /// level or plumb to a few degrees. Degrees, in (0, 45).
    double vertical_tolerance_deg = 10.0;
    /// A vertical plane is a chord plate only when it lies at least this far inside the fitted
    /// wall: a strip of the wall cut out by the plane search lies ~1–2 cm inside it, the sim's
    /// downcomer 0.45 m (its width). Metres, > 0 and < diameter_m / 2.
    double min_chord_depth_m = 0.15;
    /// The downcomer must be seen over this height along `up`, without a gap (a plane's band
    /// also crosses the floor far below a beam's face): it spans from the deck below to
    /// the tray above (~2 m), while the other vertical plates of a column, the support beams'
    /// faces (0.2 m) and the weirs (5 cm), are lower. Metres, > 0.
    double min_downcomer_height_m = 0.5;
    /// When the diameter check passes, the axis (axis_point) is refitted to the wall's points
    /// with the radius held at diameter_m / 2. A wall seen as one short arc (a camera facing
    /// the downcomer sees ~20° of it beside the plate) lets the free fit's centre and radius
    /// slide together along the arc's bisector: 4–5 cm in the simulated column, < 2 mm with the
    /// radius known. False: axis_point is the free fit's centre (art. F as published).
    bool axis_from_known_diameter = true;
    /// Plane search: 2 cm bands (the L515's noise at 2 m is ~5 mm); up to 12 planes, since the
    /// search also cuts the wall into flat strips (~0.7 m wide each on a Ø 3 m wall).
    PlaneRansacConfig planes = [] {
        PlaneRansacConfig c;
        c.max_planes = 12;
        return c;
    }();
    /// Wall search: radii from half to twice the expected one are fitted (and then judged by
    /// the diameter check); larger circles could hug the flat plates instead. The bounds must
    /// include the accepted diameters.
    CylinderRansacConfig cylinder = [] {
        CylinderRansacConfig c;
        c.min_radius_m = 0.75;
        c.max_radius_m = 3.0;
        return c;
    }();

    /// Throws ConfigError naming "<prefix>.<field>" (nested: "<prefix>.planes.<field>").
    void validate(std::string_view prefix = "column") const;
};

struct ColumnStructure {
    std::optional<Plane> floor;    ///< largest horizontal plane below the viewpoint
    std::optional<Plane> ceiling;  ///< largest horizontal plane above the viewpoint
    /// The free fit (axis = the unit `up` given): its radius is what the diameter check measures.
    std::optional<Cylinder> wall;
    bool diameter_ok = false;  ///< wall found and 2 R within the tolerance of the diameter
    /// The point of the column axis at the viewpoint's height (input frame): the wall's centre,
    /// refitted with the known radius when diameter_ok (see axis_from_known_diameter), moved
    /// along the axis. axis_point − viewpoint is the sensor's horizontal offset from the axis,
    /// the x, y of a 3-DoF registration.
    std::optional<Eigen::Vector3d> axis_point;
    /// The downcomer plate (normal facing the viewpoint: the face seen).
    std::optional<Plane> downcomer;
    /// The downcomer's normal made exactly horizontal (⟂ up), unit, facing the viewpoint.
    Eigen::Vector3d downcomer_normal = Eigen::Vector3d::Zero();
    /// Signed distance of the plate from the axis along downcomer_normal: the plate passes
    /// through axis_point + downcomer_offset_m · downcomer_normal. Negative when the sensor is
    /// on the axis' side of the plate (the usual case), so sign(offset) · normal points from the
    /// axis to the plate: the direction that fixes the yaw.
    double downcomer_offset_m = 0.0;
    /// Vertical planes that passed every downcomer test (> 1: the downcomer is not unique and
    /// the largest was taken).
    std::size_t downcomer_candidates = 0;
    /// What was found, and why anything was not ("no wall: ...", "no downcomer: ...").
    std::string status;

    /// Art. F's gate: a wall of the known diameter and a downcomer in view.
    bool registrable() const { return diameter_ok && downcomer.has_value(); }
    /// Unit horizontal direction from the axis to the downcomer (zero without a downcomer).
    Eigen::Vector3d downcomer_direction() const {
        return downcomer_offset_m < 0.0 ? Eigen::Vector3d(-downcomer_normal) : downcomer_normal;
    }
};

/// Detects the column's structure in `cloud`, given in any frame where `up` is the column axis
/// direction (gravity from the IMU; need not be unit, must be finite and non-zero) and
/// `viewpoint` is the sensor's position. Drop a depth frame's no-return (NaN) pixels first.
/// An empty cloud finds nothing (status says so). Throws InputError for a non-finite or
/// inconsistent cloud, a bad `up` or a non-finite viewpoint, ConfigError for a bad config.
ColumnStructure detect_column_structure(const PointCloud& cloud, const Eigen::Vector3d& up,
                                        const Eigen::Vector3d& viewpoint,
                                        const ColumnStructureConfig& config = {});

}  // namespace scantling::perception
