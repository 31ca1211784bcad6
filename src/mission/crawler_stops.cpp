// The crawler stack's stop-and-map stops (crawler_stack.hpp).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <scantling/mission/crawler_stack.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scantling::mission {
namespace {

/// Obstacles mapped this close to one the operator cleared are the same one seen again, or its
/// occlusion shadow (an enclosed region without returns behind it, marked negative), m.
constexpr double kClearedRadiusM = 0.25;

/// The crawler has moved off a stop's place: its cloud no longer shows what is ahead, m.
constexpr double kStopHereM = 0.01;

std::size_t count(const std::vector<perception::MappedObstacle>& obstacles,
                  perception::SurfaceLabel label) {
    std::size_t n = 0;
    for (const auto& o : obstacles) n += o.label == label;
    return n;
}

/// True when `o` was mapped within kClearedRadiusM of one of `places`: the same obstacle seen
/// again, or its shadow.
bool near_any(const std::vector<Eigen::Vector3d>& places, const perception::MappedObstacle& o) {
    return std::any_of(places.begin(), places.end(), [&](const Eigen::Vector3d& c) {
        return (c - o.centroid_world_m).norm() < kClearedRadiusM;
    });
}

/// The disc around an obstacle's cluster: half its extent's diagonal, m.
double footprint_radius(const perception::MappedObstacle& o) {
    return 0.5 * (o.max_body_xy_m - o.min_body_xy_m).norm();
}

std::string stop_json(const perception::StopMap& s) {
    return fmt::format(
        R"({{"stop":{},"frames":{},"points":{},"status":"{}","positive":{},"negative":{},)"
        R"("icp_applied":{},"icp_status":"{}"}})",
        s.index, s.num_frames, s.detection.points.size(),
        s.detection.status == perception::SurfaceStatus::kOk ? "ok" : "no surface",
        count(s.obstacles, perception::SurfaceLabel::kPositive),
        count(s.obstacles, perception::SurfaceLabel::kNegative), s.icp_applied, s.icp_status);
}

}  // namespace

void CrawlerStack::add_lidar_frame(const PointCloud& frame_lidar) {
    if (mapper_) mapper_->add_frame(frame_lidar);
}

void CrawlerStack::add_image(const io::RgbImage& image, const PinholeIntrinsics& intrinsics) {
    if (!texture_) return;
    const Eigen::Isometry3d T_map_body =
        config_.texture.map.T_world_map.inverse() * filter_.estimate().T_world_body;
    const Eigen::Isometry3d T_map_camera = T_map_body * *config_.T_body_camera;
    texture_->add_image(image, intrinsics, T_map_camera);
    if (texture_->in_stop()) texture_->add_stop_image(image, intrinsics, T_map_camera);
}

bool CrawlerStack::cleared(const perception::MappedObstacle& o) const {
    return near_any(cleared_world_m_, o);
}

void CrawlerStack::slow_for_obstacles(CrawlerStackCommand& out, double t_s) {
    const double slow_m = config_.obstacle_slow_distance_m;
    if (slow_m <= 0.0 || obstacles_.empty()) return;
    const Eigen::Isometry3d T_body_world = filter_.estimate().T_world_body.inverse();
    double nearest_m = std::numeric_limits<double>::infinity();
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
        const perception::MappedObstacle& o = obstacles_[i];
        if (cleared(o) || near_any(passing_world_m_, o)) continue;
        const Eigen::Vector3d p = T_body_world * o.centroid_world_m;
        const double radius_m = footprint_radius(o);
        if (p.x() <= 0.0 || std::abs(p.y()) > config_.corridor_half_width_m + radius_m) continue;
        if (p.x() - radius_m < nearest_m) {
            nearest_m = p.x() - radius_m;
            nearest = i;
        }
    }
    const double stop_m = config_.obstacle_stop_distance_m;
    const double scale = std::clamp((nearest_m - stop_m) / (slow_m - stop_m), 0.0, 1.0);
    out.forward_mps *= scale;
    if (scale > 0.0) return;
    out.forward_mps = 0.0;
    out.yaw_rate_radps = 0.0;
    std::string why = "replanning is off";
    if (config_.replan_around_obstacles && replan_around(nearest, t_s, out.events, why)) return;
    blocking_ = nearest;
    const Eigen::Vector3d& p = obstacles_[nearest].centroid_world_m;
    const nlohmann::ordered_json json{
        {"at", {p.x(), p.y(), p.z()}},
        {"distance_m", nearest_m},
        {"reason", "an obstacle ahead and no detour (" + why +
                       "): paused for the operator, a resume drives on"}};
    out.events.push_back({t_s, "obstacle_blocks_path", json.dump()});
    change_state(control::MissionState::kPaused, "obstacle ahead", t_s, out.events);
}

bool CrawlerStack::replan_around(std::size_t blocking, double t_s, std::vector<StackEvent>& events,
                                 std::string& why) {
    if (!follower_ || follower_->done()) {
        why = "no leg to replan";
        return false;
    }
    // The obstacles still in force; `blocking` renumbered among them.
    std::vector<planning::ObstacleFootprint> footprints;
    std::size_t blocking_footprint = 0;
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
        if (cleared(obstacles_[i])) continue;
        if (i == blocking) blocking_footprint = footprints.size();
        footprints.push_back({obstacles_[i].centroid_world_m, footprint_radius(obstacles_[i])});
    }
    const std::vector<control::PathSegment>& path = follower_->path();
    const std::vector<control::PathSegment> remaining(
        path.begin() + static_cast<long>(follower_->segment_index()), path.end());
    const Eigen::Vector3d p = filter_.estimate().T_world_body.translation();
    const planning::Detour detour = planning::plan_detour(
        surface_, p, remaining, footprints, blocking_footprint, config_.walk, config_.detour);
    if (!detour.found) {
        why = detour.reason;
        return false;
    }
    legs_.at(leg_).segments = detour.path;
    ++legs_revision_;
    follower_.reset();
    passing_world_m_.push_back(obstacles_[blocking].centroid_world_m);
    const Eigen::Vector3d& o = obstacles_[blocking].centroid_world_m;
    events.push_back(
        {t_s, "path_replanned",
         fmt::format(R"({{"around":[{:.3f},{:.3f},{:.3f}],"side":"{}","offset_m":{:.3f},)"
                     R"("length_m":{:.3f},"reason":"an obstacle ahead: passing it"}})",
                     o.x(), o.y(), o.z(), detour.side > 0 ? "left" : "right", detour.offset_m,
                     detour.length_m)});
    return true;
}

void CrawlerStack::count_distance() {
    const Eigen::Vector3d p = filter_.estimate().T_world_body.translation();
    if (last_p_) driven_m_ += (p - *last_p_).norm();
    last_p_ = p;
    if (driven_m_ > kStopHereM) stop_cloud_here_.reset();
}

bool CrawlerStack::stopped_to_map(CrawlerStackCommand& out, double t_s) {
    if (!mapper_) return false;
    if (!stop_began_s_) {
        const bool spacing_done =
            config_.stop_spacing_m > 0.0 && driven_m_ >= config_.stop_spacing_m;
        if (!stop_due_ && !spacing_done) return false;
        stop_began_s_ = t_s;
        stop_due_ = false;
    }
    const double in_stop_s = t_s - *stop_began_s_;
    if (!mapper_->collecting() && in_stop_s >= config_.stop_settle_s &&
        in_stop_s < config_.stop_duration_s) {
        mapper_->begin(t_s, filter_.estimate().T_world_body);
        if (texture_) texture_->begin_stop();
    }
    if (in_stop_s < config_.stop_duration_s) return true;
    if (mapper_->collecting()) {
        out.stop = mapper_->finish(t_s);
        if (texture_) {
            texture_->end_stop(out.stop->detection.grid, config_.texture.map.T_world_map.inverse() *
                                                             out.stop->T_world_body_map);
        }
        out.events.push_back({t_s, "stop_mapped", stop_json(*out.stop)});
        obstacles_.insert(obstacles_.end(), out.stop->obstacles.begin(), out.stop->obstacles.end());
        const bool corridor_ahead =
            std::any_of(tasks_.begin() + static_cast<long>(task_), tasks_.end(),
                        [](const auto& t) { return t.needs_corridor(); });
        if (corridor_ahead) stop_cloud_here_ = out.stop->cloud_body;
        remeasure_corridor(*out.stop, t_s, out.events);
    }
    stop_began_s_.reset();
    driven_m_ = 0.0;
    last_p_.reset();
    return false;
}

}  // namespace scantling::mission
