#include "scantling/localization/survey_location.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace scantling::localization {
namespace {

double floor_z(const io::StructuralMap& map) {
    if (map.compartments.empty()) return 0.0;
    double z = std::numeric_limits<double>::infinity();
    for (const io::Compartment& c : map.compartments) z = std::min(z, c.bounds.min.z());
    return z;
}

int containing_compartment(const io::StructuralMap& map, const Eigen::Vector3d& p, int hint,
                           double margin_m) {
    int best = -1;
    double best_volume = std::numeric_limits<double>::infinity();
    for (const io::Compartment& c : map.compartments) {
        const Eigen::Vector3d lo = c.bounds.min.array() - margin_m;
        const Eigen::Vector3d hi = c.bounds.max.array() + margin_m;
        if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
        if (c.id == hint) return hint;
        const double volume = (c.bounds.max - c.bounds.min).prod();
        if (volume < best_volume) best = c.id, best_volume = volume;
    }
    return best;
}

/// The line numbered `number` (numbers are unique per list: io::read_structural_map).
const io::FrameLine& numbered(const std::vector<io::FrameLine>& lines, int number) {
    return *std::find_if(lines.begin(), lines.end(),
                         [number](const io::FrameLine& l) { return l.number == number; });
}

}  // namespace

std::string SurveyLocation::text() const {
    std::string s = compartment >= 0 ? compartment_name : std::string("outside the compartments");
    if (frame >= 0) s += fmt::format(", frame {} {:+.2f} m", frame, from_frame_m);
    if (longitudinal >= 0) {
        s += fmt::format(", longitudinal {} ({:.2f} m)", longitudinal, from_longitudinal_m);
    }
    return s + fmt::format(", {:.2f} m above the floor", height_above_floor_m);
}

SurveyLocation locate_in_structure(const io::StructuralMap& map, const Eigen::Vector3d& p_world,
                                   int compartment_hint, double margin_m) {
    SurveyLocation where;
    where.compartment = containing_compartment(map, p_world, compartment_hint, margin_m);
    if (const io::Compartment* c = io::find_compartment(map, where.compartment)) {
        where.compartment_name = c->name;
    }
    if (const std::optional<int> frame = io::nearest_frame(map, p_world)) {
        const io::FrameLine& f = numbered(map.frames, *frame);
        where.frame = f.number;
        where.from_frame_m = f.axis.dot(p_world - f.point);
    }
    if (const std::optional<int> longitudinal = io::nearest_longitudinal(map, p_world)) {
        const io::FrameLine& l = numbered(map.longitudinals, *longitudinal);
        const Eigen::Vector3d d = p_world - l.point;
        where.longitudinal = l.number;
        where.from_longitudinal_m = (d - l.axis.dot(d) * l.axis).norm();
    }
    where.height_above_floor_m = p_world.z() - floor_z(map);
    return where;
}

}  // namespace scantling::localization
