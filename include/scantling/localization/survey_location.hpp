#pragma once
/// @file
/// Where a point of the map is in the surveyors' language (SPEC §7): the compartment, the
/// nearest frame (web frame or bulkhead) and the offset from it along the ship, the nearest
/// longitudinal and the distance to it, and the height above the tank floor. A class-society
/// report reads "bay 2, frame 1 + 0.42 m, longitudinal 3, 1.10 m above the floor".
///
/// Frame: world (map) frame, metres. Pure functions of the structural map; reentrant.

#include <Eigen/Core>
#include <string>

#include <scantling/io/structural_map.hpp>

namespace scantling::localization {

struct SurveyLocation {
    int compartment = -1;  ///< io::Compartment::id, -1 when outside every compartment
    std::string compartment_name;
    int frame = -1;             ///< FrameLine::number of the nearest frame, -1 when none
    double from_frame_m = 0.0;  ///< signed, along that frame's axis
    int longitudinal = -1;      ///< FrameLine::number of the nearest longitudinal, -1 when none
    double from_longitudinal_m = 0.0;  ///< distance to its toe line, >= 0
    /// Above the tank floor: the lowest compartment floor (z of the lowest bounds), or z when
    /// the map has no compartment.
    double height_above_floor_m = 0.0;

    /// "bay_2, frame 1 + 0.42 m, longitudinal 3 (0.05 m), 1.10 m above the floor".
    std::string text() const;
};

/// The survey location of `p_world`. The compartment is the one whose bounds, grown by
/// `margin_m`, contain the point (a defect lies on a plate at the boundary of its bounds):
/// `compartment_hint` when it is one of them (the compartment the robot saw it from), else the
/// smallest such.
SurveyLocation locate_in_structure(const io::StructuralMap& map, const Eigen::Vector3d& p_world,
                                   int compartment_hint = -1, double margin_m = 0.05);

}  // namespace scantling::localization
