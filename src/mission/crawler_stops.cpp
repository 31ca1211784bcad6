// The crawler stack's stop-and-map stops (crawler_stack.hpp).
#include <fmt/format.h>

#include <scantling/mission/crawler_stack.hpp>

namespace scantling::mission {
namespace {

std::size_t count(const std::vector<perception::MappedObstacle>& obstacles,
                  perception::SurfaceLabel label) {
    std::size_t n = 0;
    for (const auto& o : obstacles) n += o.label == label;
    return n;
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

void CrawlerStack::count_distance() {
    const Eigen::Vector3d p = filter_.estimate().T_world_body.translation();
    if (last_p_) driven_m_ += (p - *last_p_).norm();
    last_p_ = p;
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
    }
    stop_began_s_.reset();
    driven_m_ = 0.0;
    last_p_.reset();
    return false;
}

}  // namespace scantling::mission
