#include "scantling/localize_defects.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/png.hpp>
#include <scantling/localization/fused_track.hpp>

namespace scantling::app {
namespace {

namespace fs = std::filesystem;
namespace loc = localization;

/// Two VIO samples farther apart than this are a dropout: no pose is interpolated across it.
constexpr double kMaxVioGap_s = 0.2;

/// The depth frames of a recording placed in the world through the fused trajectory, one at a
/// time (consecutive images mostly share their nearest frame).
class DepthInWorld {
  public:
    DepthInWorld(const io::Recording& r, const LocalizeRun& run, const Eigen::Isometry3d& T_bd)
        : recording_(r), run_(run), T_body_depth_(T_bd) {}

    /// The frame nearest to `stamp_s` within `max_offset_s`, or nullptr (reason set).
    const PointCloud* near(double stamp_s, double max_offset_s, std::string& reason) {
        const std::vector<double>& stamps = recording_.depth_frames().stamps_s;
        const auto it = std::lower_bound(stamps.begin(), stamps.end(), stamp_s);
        std::size_t i = static_cast<std::size_t>(it - stamps.begin());
        if (i == stamps.size() || (i > 0 && stamp_s - stamps[i - 1] < stamps[i] - stamp_s)) --i;
        if (std::abs(stamps[i] - stamp_s) > max_offset_s) {
            reason = "no_depth_frame";
            return nullptr;
        }
        if (index_ != i) load(i);
        if (!pose_ok_) reason = "no_pose";
        return pose_ok_ ? &cloud_ : nullptr;
    }

  private:
    void load(std::size_t i) {
        index_ = i;
        cloud_ = PointCloud{};
        const auto state =
            loc::fused_state_at(run_.fused, recording_.depth_frames().stamps_s[i], kMaxVioGap_s);
        pose_ok_ = state.has_value();
        if (!pose_ok_) return;
        const Eigen::Isometry3d T_world_depth = state->T_world_body * T_body_depth_;
        for (const Eigen::Vector3d& p : recording_.read_depth_frame(i).points) {
            if (p.allFinite()) cloud_.points.push_back(T_world_depth * p);
        }
    }

    const io::Recording& recording_;
    const LocalizeRun& run_;
    Eigen::Isometry3d T_body_depth_;
    std::optional<std::size_t> index_;
    PointCloud cloud_;
    bool pose_ok_ = false;
};

/// The compartment of the last frame event at or before `stamp_s` that had one.
int compartment_at(const std::vector<loc::FrameEvent>& events, double stamp_s) {
    int compartment = -1;
    for (const loc::FrameEvent& e : events) {
        if (e.stamp_s > stamp_s) break;
        if (e.compartment >= 0) compartment = e.compartment;
    }
    return compartment;
}

std::string reason_key(const std::string& reason) { return reason.substr(0, reason.find(':')); }

/// Surveyed defects with their truth, when the world lists the defect.
std::vector<SurveyedDefect> place(const std::vector<loc::MappedDefect>& mapped,
                                  const io::StructuralMap* structure,
                                  const std::vector<loc::FrameEvent>& events) {
    std::vector<SurveyedDefect> out;
    for (const loc::MappedDefect& d : mapped) {
        SurveyedDefect s{.mapped = d, .location = {}, .error_m = {}, .true_location = {}};
        if (structure == nullptr) {
            s.location.height_above_floor_m = d.position_world.z();
            out.push_back(std::move(s));
            continue;
        }
        s.location = loc::locate_in_structure(*structure, d.position_world,
                                              compartment_at(events, d.best_view.stamp_s));
        if (d.defect_id >= 0 && static_cast<std::size_t>(d.defect_id) < structure->defects.size()) {
            const io::Defect& truth = structure->defects[static_cast<std::size_t>(d.defect_id)];
            s.error_m = (d.position_world - truth.centre).norm();
            s.true_location = loc::locate_in_structure(*structure, truth.centre, truth.compartment);
        }
        out.push_back(std::move(s));
    }
    return out;
}

}  // namespace

DefectSurvey survey_defects(const io::Recording& recording, const LocalizeRun& run,
                            const Eigen::Isometry3d& T_body_depth,
                            const io::StructuralMap* structure,
                            const loc::DefectLiftingConfig& config) {
    config.validate();
    DefectSurvey survey;
    survey.sightings = recording.defect_sightings().size();
    if (survey.sightings == 0) {
        survey.note = "no defect sightings (images/defect_sightings.csv)";
        return survey;
    }
    if (!recording.image_intrinsics() || !recording.image_T_body_sensor()) {
        survey.note = "no images/camera.json or images/T_body_sensor.txt: sightings not lifted";
        return survey;
    }
    loc::DefectMap map;
    DepthInWorld depth(recording, run, T_body_depth);
    for (const io::DefectSighting& s : recording.defect_sightings()) {
        const auto state = loc::fused_state_at(run.fused, s.stamp_s, kMaxVioGap_s);
        std::string reason;
        const PointCloud* cloud =
            state ? depth.near(s.stamp_s, config.max_frame_offset_s, reason) : nullptr;
        if (!state) reason = "no_pose";
        if (cloud != nullptr) {
            const loc::LiftingView view{
                .intrinsics = *recording.image_intrinsics(),
                .T_world_camera = state->T_world_body * *recording.image_T_body_sensor(),
                .p_world_body = state->T_world_body.translation(),
                .body_covariance = state->covariance};
            loc::LiftResult lifted = loc::lift_defect(s, view, *cloud, config);
            if (lifted.observation) {
                map.add(std::move(*lifted.observation));
                ++survey.lifted;
                continue;
            }
            reason = lifted.reason;
        }
        ++survey.not_lifted[reason_key(reason)];
    }
    survey.defects = place(map.defects(), structure, run.events);
    return survey;
}

namespace {

nlohmann::ordered_json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// What was written for one defect beside the JSON.
struct DefectFiles {
    bool crop = false, cloud = false;
    std::string crop_error;  ///< why there is no crop ("" when there is one or nothing to crop)
};

nlohmann::ordered_json defect_json(const SurveyedDefect& s, const DefectFiles& files) {
    const loc::MappedDefect& d = s.mapped;
    const loc::SurveyLocation& l = s.location;
    nlohmann::ordered_json j;
    j["id"] = d.defect_id;
    j["position_m"] = vector_json(d.position_world);
    j["covariance_m2"] = {vector_json(d.covariance.row(0).transpose()),
                          vector_json(d.covariance.row(1).transpose()),
                          vector_json(d.covariance.row(2).transpose())};
    j["largest_sigma_m"] = d.largest_sigma_m();
    j["normal"] = vector_json(d.normal_world);
    j["views"] = d.views;
    j["outlier_views"] = d.outlier_views;
    j["first_seen_s"] = d.first_seen_s;
    j["last_seen_s"] = d.last_seen_s;
    j["location"] = {{"compartment", l.compartment},
                     {"compartment_name", l.compartment_name},
                     {"frame", l.frame},
                     {"from_frame_m", l.from_frame_m},
                     {"longitudinal", l.longitudinal},
                     {"from_longitudinal_m", l.from_longitudinal_m},
                     {"height_above_floor_m", l.height_above_floor_m},
                     {"text", l.text()}};
    j["best_view"] = {{"image", d.best_view.image},
                      {"stamp_s", d.best_view.stamp_s},
                      {"pixel", {d.best_view.pixel.x(), d.best_view.pixel.y()}},
                      {"range_m", d.best_view.range_m}};
    j["crop"] = files.crop ? nlohmann::ordered_json(fmt::format("defects/{}/crop.png", d.defect_id))
                           : nlohmann::ordered_json(nullptr);
    if (!files.crop_error.empty()) j["crop_error"] = files.crop_error;
    j["cloud"] = files.cloud
                     ? nlohmann::ordered_json(fmt::format("defects/{}/cloud.ply", d.defect_id))
                     : nlohmann::ordered_json(nullptr);
    if (s.error_m) {
        j["truth"] = {{"error_m", *s.error_m},
                      {"frame", s.true_location->frame},
                      {"longitudinal", s.true_location->longitudinal},
                      {"right_frame", s.right_frame()},
                      {"right_longitudinal", s.right_longitudinal()}};
    }
    return j;
}

std::string defects_json(const DefectSurvey& survey, const std::vector<DefectFiles>& files) {
    nlohmann::ordered_json j;
    j["sightings"] = survey.sightings;
    j["lifted"] = survey.lifted;
    j["not_lifted"] = survey.not_lifted;
    if (!survey.note.empty()) j["note"] = survey.note;
    j["defects"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < survey.defects.size(); ++i) {
        j["defects"].push_back(defect_json(survey.defects[i], files[i]));
    }
    return j.dump(2) + "\n";
}

void write_defects_csv(std::ostream& out, const DefectSurvey& survey) {
    out << "id,x,y,z,largest_sigma_m,views,compartment,compartment_name,frame,from_frame_m,"
           "longitudinal,from_longitudinal_m,height_above_floor_m,error_m,right_frame,"
           "right_longitudinal\n";
    for (const SurveyedDefect& s : survey.defects) {
        const Eigen::Vector3d& p = s.mapped.position_world;
        const loc::SurveyLocation& l = s.location;
        std::string name = l.compartment_name;
        std::replace(name.begin(), name.end(), ',', ';');
        out << fmt::format("{},{:.4f},{:.4f},{:.4f},{:.4f},{},{},{},{},{:.3f},{},{:.3f},{:.3f},",
                           s.mapped.defect_id, p.x(), p.y(), p.z(), s.mapped.largest_sigma_m(),
                           s.mapped.views, l.compartment, name, l.frame, l.from_frame_m,
                           l.longitudinal, l.from_longitudinal_m, l.height_above_floor_m);
        out << (s.error_m ? fmt::format("{:.4f},{},{}\n", *s.error_m, s.right_frame() ? 1 : 0,
                                        s.right_longitudinal() ? 1 : 0)
                          : std::string(",,\n"));
    }
}

/// The best view's image around the defect: 2.5 radii each side, at least 32 px. An unreadable
/// image costs the crop, not the survey (the error goes into defects.json).
void write_crop(const fs::path& path, const loc::DefectObservation& view,
                const io::Recording& recording, DefectFiles& files) {
    io::RgbImage image;
    try {
        image = io::read_png(recording.image_path(view.image));
    } catch (const Error& e) {
        files.crop_error = e.what();
        return;
    }
    const int half = static_cast<int>(std::ceil(std::max(2.5 * view.radius_px, 16.0)));
    const io::RgbImage cut =
        io::crop(image, static_cast<int>(std::lround(view.pixel.x())) - half,
                 static_cast<int>(std::lround(view.pixel.y())) - half, 2 * half + 1, 2 * half + 1);
    if (cut.width == 0) return;
    fs::create_directories(path.parent_path());
    io::write_png(path.string(), cut);
    files.crop = true;
}

}  // namespace

void write_defects(const fs::path& dir, const DefectSurvey& survey,
                   const io::Recording& recording) {
    std::vector<DefectFiles> files(survey.defects.size());
    for (std::size_t i = 0; i < survey.defects.size(); ++i) {
        const loc::MappedDefect& d = survey.defects[i].mapped;
        const fs::path folder = dir / "defects" / std::to_string(d.defect_id);
        write_crop(folder / "crop.png", d.best_view, recording, files[i]);
        if (!d.best_view.local_cloud_world.empty()) {
            fs::create_directories(folder);
            io::write_cloud((folder / "cloud.ply").string(), d.best_view.local_cloud_world);
            files[i].cloud = true;
        }
    }
    io::write_file_atomically((dir / "defects.json").string(),
                              [&](std::ostream& s) { s << defects_json(survey, files); });
    io::write_file_atomically((dir / "defects.csv").string(),
                              [&](std::ostream& s) { write_defects_csv(s, survey); });
}

void print_defects(std::ostream& out, const DefectSurvey& survey) {
    if (!survey.note.empty()) {
        out << "defects: " << survey.note << "\n";
        return;
    }
    out << fmt::format("defects: {} sightings, {} lifted, {} defects", survey.sightings,
                       survey.lifted, survey.defects.size());
    for (const auto& [reason, count] : survey.not_lifted)
        out << fmt::format(", {} {}", count, reason);
    out << "\n";
    std::vector<double> errors;
    std::size_t right_frame = 0, right_longitudinal = 0;
    for (const SurveyedDefect& s : survey.defects) {
        out << fmt::format("  defect {}: {} ({} views, sigma {:.3f} m){}\n", s.mapped.defect_id,
                           s.location.text(), s.mapped.views, s.mapped.largest_sigma_m(),
                           s.error_m ? fmt::format(", error {:.3f} m", *s.error_m) : "");
        if (!s.error_m) continue;
        errors.push_back(*s.error_m);
        right_frame += s.right_frame() ? 1 : 0;
        right_longitudinal += s.right_longitudinal() ? 1 : 0;
    }
    if (errors.empty()) return;
    const ErrorStats e = error_stats(errors);
    out << fmt::format(
        "defect position error: mean {:.4f} p95 {:.4f} max {:.4f} m (n = {}); right frame "
        "{}/{}, right longitudinal {}/{}\n",
        e.mean, e.p95, e.max, e.count, right_frame, errors.size(), right_longitudinal,
        errors.size());
}

}  // namespace scantling::app
