#pragma once
/// @file
/// The defects of `scantling localize` (issue 12 item 4): every sighting of the recording
/// (images/defect_sightings.csv) lifted with the nearest depth frame through the fused
/// trajectory, merged per defect, placed in the surveyors' terms, compared with the world's
/// defects where the recording has them, and written as defects.json, defects.csv and, per
/// defect, defects/<id>/crop.png (the best view's image around it) and defects/<id>/cloud.ply
/// (its returns within local_cloud_radius_m, world frame).

#include <Eigen/Geometry>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <scantling/io/recording.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/localization/defect_lifting.hpp>
#include <scantling/localization/defect_map.hpp>
#include <scantling/localization/survey_location.hpp>

#include "scantling/localize_report.hpp"

namespace scantling::app {

/// One mapped defect with where it is and, when the world lists it, how far from the truth.
struct SurveyedDefect {
    localization::MappedDefect mapped;
    localization::SurveyLocation location;
    std::optional<double> error_m;  ///< to the world's defect centre
    std::optional<localization::SurveyLocation> true_location;
    bool right_frame() const { return true_location && true_location->frame == location.frame; }
    bool right_longitudinal() const {
        return true_location && true_location->longitudinal == location.longitudinal;
    }
};

struct DefectSurvey {
    std::string note;  ///< why nothing was surveyed ("" when sightings were processed)
    std::size_t sightings = 0;
    std::size_t lifted = 0;
    std::map<std::string, std::size_t> not_lifted;  ///< reason ("no_depth", "no_pose") → count
    std::vector<SurveyedDefect> defects;
};

DefectSurvey survey_defects(const io::Recording& recording, const LocalizeRun& run,
                            const Eigen::Isometry3d& T_body_depth,
                            const io::StructuralMap* structure,
                            const localization::DefectLiftingConfig& config = {});

/// defects.json, defects.csv and defects/<id>/{crop.png, cloud.ply} in `dir`.
void write_defects(const std::filesystem::path& dir, const DefectSurvey& survey,
                   const io::Recording& recording);
void print_defects(std::ostream& out, const DefectSurvey& survey);

}  // namespace scantling::app
