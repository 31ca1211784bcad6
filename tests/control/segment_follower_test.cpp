// The crawler's segment-frame path follower (control/segment_follower.hpp, SPEC §6), driving a
// kinematic unicycle that crawls on the facet of the segment it is commanded to follow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/control/segment_follower.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

constexpr double kDtS = 0.02;              // the simulation step
constexpr double kSettledYM = 0.005;       // |y| after 10 s (a 0.1 m start offset, 20° off)
constexpr double kMeanCrossTrackM = 0.03;  // the brief's bound on a whole run
constexpr double kSameRunM = 1e-9;         // one run in different planes: only rounding may differ
constexpr double kDeg = std::numbers::pi / 180.0;

// A plane: origin and in-plane axes u, w with u × w = n, its normal.
struct Plane {
    Eigen::Vector3d origin, u, w, n;
    Eigen::Vector3d at(double a, double b) const { return origin + a * u + b * w; }
    Eigen::Matrix3d axes() const { return (Eigen::Matrix3d() << u, w, n).finished(); }
};

const Plane kFloor{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                   Eigen::Vector3d::UnitZ()};
// A vertical wall (normal −y), the segments running up it.
const Plane kWall{{0.5, 0.0, 0.2},
                  Eigen::Vector3d::UnitZ(),
                  -Eigen::Vector3d::UnitX(),
                  -Eigen::Vector3d::UnitY()};

Plane tilted_plane() {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    return {{1.0, -2.0, 0.5}, R.col(0), R.col(1), R.col(2)};
}

// A polyline through in-plane points (a, b).
std::vector<PathSegment> polyline(const Plane& plane, const std::vector<Eigen::Vector2d>& points) {
    std::vector<PathSegment> path;
    for (std::size_t i = 1; i < points.size(); ++i) {
        path.push_back({plane.at(points[i - 1].x(), points[i - 1].y()),
                        plane.at(points[i].x(), points[i].y()), plane.n});
    }
    return path;
}

// On the plane at (a, b), heading yaw from u, body z = the plane's normal.
Eigen::Isometry3d pose_on(const Plane& plane, double a, double b, double yaw_rad) {
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.linear() = plane.axes() * Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ());
    T_world_body.translation() = plane.at(a, b);
    return T_world_body;
}

// The unicycle: first seated on the facet (body z turned onto its normal, the position projected
// onto it: crossing a fold), then x += v x_body dt and a turn of ω dt about the normal.
void crawl(Eigen::Isometry3d& T_world_body, const FollowerCommand& command,
           const PathSegment& facet) {
    const Eigen::Vector3d n = facet.normal_world.normalized();
    const Eigen::Quaterniond seat =
        Eigen::Quaterniond::FromTwoVectors(T_world_body.linear().col(2), n);
    T_world_body.linear() = seat.toRotationMatrix() * T_world_body.linear();
    Eigen::Vector3d p = T_world_body.translation();
    p -= (p - facet.begin_world_m).dot(n) * n;
    T_world_body.translation() = p + command.v_mps * kDtS * T_world_body.linear().col(0);
    T_world_body.linear() =
        Eigen::AngleAxisd(command.omega_radps * kDtS, n).matrix() * T_world_body.linear();
}

struct Trace {
    std::vector<FollowerCommand> commands;   // one per step, the last one done (if it finished)
    std::vector<Eigen::Vector3d> p_world_m;  // the pose each command was computed for
};

Trace simulate(SegmentFollower& follower, Eigen::Isometry3d T_world_body, double duration_s) {
    Trace run;
    for (int step = 0; step * kDtS < duration_s; ++step) {
        const FollowerCommand command = follower.update(T_world_body);
        run.commands.push_back(command);
        run.p_world_m.push_back(T_world_body.translation());
        if (command.done) break;
        crawl(T_world_body, command, follower.path()[command.segment]);
    }
    return run;
}

double distance_to_segment(const Eigen::Vector3d& p, const PathSegment& s) {
    const Eigen::Vector3d d = s.end_world_m - s.begin_world_m;
    const double t = std::clamp((p - s.begin_world_m).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (p - (s.begin_world_m + t * d)).norm();
}

double mean_cross_track_m(const Trace& run, const std::vector<PathSegment>& path,
                          const char* name) {
    double sum_m = 0.0, max_m = 0.0;
    for (const Eigen::Vector3d& p : run.p_world_m) {
        double d_m = std::numeric_limits<double>::infinity();
        for (const PathSegment& s : path) d_m = std::min(d_m, distance_to_segment(p, s));
        sum_m += d_m;
        max_m = std::max(max_m, d_m);
    }
    const double mean_m = sum_m / static_cast<double>(run.p_world_m.size());
    std::printf("[ measured ] %s: cross-track mean %.4f m, max %.4f m, %.1f s\n", name, mean_m,
                max_m, static_cast<double>(run.commands.size()) * kDtS);
    return mean_m;
}

// Every segment followed, in order, none skipped, and the path finished.
void expect_visited_in_order(const Trace& run, std::size_t num_segments) {
    ASSERT_FALSE(run.commands.empty());
    EXPECT_EQ(run.commands.front().segment, 0u);
    for (std::size_t i = 1; i < run.commands.size(); ++i) {
        const std::size_t step = run.commands[i].segment - run.commands[i - 1].segment;
        EXPECT_TRUE(step == 0 || step == 1) << "at step " << i;
    }
    EXPECT_TRUE(run.commands.back().done);
    EXPECT_EQ(run.commands.back().segment, num_segments);
}

// Scenario (a) in a plane: a 3 m segment, the robot 0.1 m to its left, heading 20° further away.
Trace straight_run(const Plane& plane) {
    SegmentFollower follower(polyline(plane, {{0.0, 0.0}, {3.0, 0.0}}));
    return simulate(follower, pose_on(plane, 0.0, 0.1, 20.0 * kDeg), 20.0);
}

void expect_settled(const Trace& run) {
    const SegmentFollowerConfig config;
    ASSERT_EQ(run.commands.size(), 1000u);  // 20 s, not finished
    const std::size_t after_10_s = 500;
    for (std::size_t i = after_10_s; i < run.commands.size(); ++i) {
        ASSERT_LT(std::abs(run.commands[i].error.y_m), kSettledYM) << "at " << i * kDtS << " s";
    }
    EXPECT_LT(std::abs(run.commands.back().error.yaw_rad), 1.0 * kDeg);
    EXPECT_GT(run.commands.back().v_mps, 0.99 * config.v_ref_mps);  // straight: full speed
    std::printf("[ measured ] |y| at 10 s %.5f m, at 20 s %.2e m\n",
                std::abs(run.commands[after_10_s].error.y_m),
                std::abs(run.commands.back().error.y_m));
}

TEST(SegmentFollower, ConvergesOntoAStraightSegmentFromAnOffsetAndAHeadingError) {
    const Trace run = straight_run(kFloor);
    expect_settled(run);
    const SegmentFollowerConfig config;
    int hard_turns = 0;
    for (const FollowerCommand& c : run.commands) {
        if (std::abs(c.omega_radps) < config.omega0_radps) continue;
        ++hard_turns;
        EXPECT_LE(c.v_mps, config.v_ref_mps * std::exp(-1.0) + 1e-12);  // v < v_ref while turning
    }
    EXPECT_GT(hard_turns, 0);  // the start turns hard enough to slow down
}

TEST(SegmentFollower, ConvergesTheSameWayOnAVerticalWallAndATiltedPlane) {
    const Trace on_floor = straight_run(kFloor);
    for (const Plane& plane : {kWall, tilted_plane()}) {
        const Trace run = straight_run(plane);
        expect_settled(run);
        ASSERT_EQ(run.commands.size(), on_floor.commands.size());
        for (std::size_t i = 0; i < run.commands.size(); ++i) {
            ASSERT_NEAR(run.commands[i].error.y_m, on_floor.commands[i].error.y_m, kSameRunM);
            ASSERT_NEAR(run.commands[i].error.yaw_rad, on_floor.commands[i].error.yaw_rad,
                        kSameRunM);
            ASSERT_NEAR(run.commands[i].v_mps, on_floor.commands[i].v_mps, kSameRunM);
        }
    }
}

TEST(SegmentFollower, FollowsAnLShapeAndAZigZagVisitingEverySegmentInOrder) {
    const std::vector<std::vector<Eigen::Vector2d>> shapes = {
        {{0.0, 0.0}, {1.5, 0.0}, {1.5, 1.5}},
        {{0.0, 0.0}, {1.0, 0.5}, {2.0, 0.0}, {3.0, 0.5}, {4.0, 0.0}}};
    const char* names[] = {"L-shape", "zig-zag"};
    for (std::size_t k = 0; k < shapes.size(); ++k) {
        const std::vector<PathSegment> path = polyline(kFloor, shapes[k]);
        SegmentFollower follower(path);
        const Eigen::Vector2d first = shapes[k][1] - shapes[k][0];
        const Trace run =
            simulate(follower, pose_on(kFloor, 0.0, 0.0, std::atan2(first.y(), first.x())), 200.0);
        expect_visited_in_order(run, path.size());
        EXPECT_LE(mean_cross_track_m(run, path, names[k]), kMeanCrossTrackM);
        EXPECT_TRUE(follower.done());
    }
}

TEST(SegmentFollower, SwitchesAtTheSegmentEndAndFollowsOnAFoldedFacet) {
    // The floor, then a 30° slope up along x, then across the slope (along y).
    const double slope = 30.0 * kDeg;
    const Eigen::Vector3d up(std::cos(slope), 0.0, std::sin(slope));
    const Eigen::Vector3d slope_normal(-std::sin(slope), 0.0, std::cos(slope));
    const Eigen::Vector3d fold(1.0, 0.0, 0.0);
    const std::vector<PathSegment> path = {
        {Eigen::Vector3d::Zero(), fold, Eigen::Vector3d::UnitZ()},
        {fold, fold + 1.0 * up, slope_normal},
        {fold + 1.0 * up, fold + 1.0 * up + Eigen::Vector3d(0.0, 0.8, 0.0), slope_normal}};
    SegmentFollower follower(path);
    const Trace run = simulate(follower, pose_on(kFloor, 0.0, 0.05, 10.0 * kDeg), 200.0);
    expect_visited_in_order(run, path.size());
    EXPECT_LE(mean_cross_track_m(run, path, "folded plane"), kMeanCrossTrackM);
    const auto switched = std::find_if(run.commands.begin(), run.commands.end(),
                                       [](const FollowerCommand& c) { return c.segment == 1; });
    ASSERT_NE(switched, run.commands.end());
    const std::size_t i = static_cast<std::size_t>(switched - run.commands.begin());
    ASSERT_GT(i, 0u);
    EXPECT_GT(run.p_world_m[i].x(), fold.x());       // x > |E_0 − B_0| on the floor ...
    EXPECT_LE(run.p_world_m[i - 1].x(), fold.x());   // ... for the first time
    EXPECT_LT(std::abs(switched->error.x_m), 0.01);  // and at the start of the slope's frame
    EXPECT_LT((run.p_world_m.back() - path.back().end_world_m).norm(), 0.02);
}

TEST(SegmentFollower, TurnsTowardsTheSegmentAndSlowsDownWhileTurning) {
    const SegmentFollowerConfig config;
    EXPECT_LT(segment_follower_law({0.0, 0.01, 0.0}, config).omega_radps, 0.0);  // left: turn right
    EXPECT_GT(segment_follower_law({0.0, 0.0, -0.1}, config).omega_radps, 0.0);
    const FollowerCommand on_path = segment_follower_law({}, config);
    EXPECT_EQ(on_path.v_mps, config.v_ref_mps);
    const double y_for_omega0_m = config.omega0_radps / config.k_y_per_m_s;
    EXPECT_NEAR(segment_follower_law({0.0, y_for_omega0_m, 0.0}, config).v_mps,
                config.v_ref_mps * std::exp(-1.0), 1e-12);
    EXPECT_EQ(segment_follower_law({0.0, 10.0, 0.0}, config).omega_radps, -config.max_omega_radps);
}

TEST(SegmentFollower, OrthogonalisesANormalThatIsNotQuitePerpendicular) {
    const Eigen::Isometry3d R = segment_frame({{1, 2, 3}, {3, 2, 3}, {0.3, 0.0, 1.0}}, 0);
    EXPECT_TRUE(R.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
    EXPECT_TRUE(R.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(SegmentFollower, AnEmptyPathIsDoneAtOnce) {
    SegmentFollower follower({});
    const FollowerCommand command = follower.update(Eigen::Isometry3d::Identity());
    EXPECT_TRUE(command.done);
    EXPECT_EQ(command.v_mps, 0.0);
    EXPECT_EQ(command.omega_radps, 0.0);
}

template <typename Exception, typename Call>
void expect_throw_naming(Call call, const std::string& name) {
    try {
        call();
        ADD_FAILURE() << "no exception, expected one naming " << name;
    } catch (const Exception& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
}

TEST(SegmentFollower, RefusesBadSegmentsPosesAndConfigsNamingTheField) {
    std::vector<PathSegment> path = polyline(kFloor, {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}});
    std::vector<PathSegment> zero_length = path;
    zero_length[3].end_world_m = zero_length[3].begin_world_m;
    expect_throw_naming<ConfigError>([&] { SegmentFollower f(zero_length); },
                                     "segment_follower.path[3]");
    std::vector<PathSegment> parallel = path;
    parallel[1].normal_world = Eigen::Vector3d::UnitX();
    expect_throw_naming<ConfigError>([&] { SegmentFollower f(parallel); }, "path[1]");
    std::vector<PathSegment> not_finite = path;
    not_finite[2].begin_world_m.y() = std::nan("");
    expect_throw_naming<ConfigError>([&] { SegmentFollower f(not_finite); }, "path[2]");

    SegmentFollower follower(path);
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.translation().x() = std::nan("");
    expect_throw_naming<InputError>([&] { follower.update(T_world_body); }, "T_world_body");

    const std::vector<std::pair<double SegmentFollowerConfig::*, std::string>> fields = {
        {&SegmentFollowerConfig::k_y_per_m_s, "k_y_per_m_s"},
        {&SegmentFollowerConfig::k_yaw_per_s, "k_yaw_per_s"},
        {&SegmentFollowerConfig::v_ref_mps, "v_ref_mps"},
        {&SegmentFollowerConfig::omega0_radps, "omega0_radps"},
        {&SegmentFollowerConfig::max_omega_radps, "max_omega_radps"}};
    for (const auto& [field, name] : fields) {
        for (const double bad : {0.0, -1.0, std::nan("")}) {
            SegmentFollowerConfig config;
            config.*field = bad;
            expect_throw_naming<ConfigError>([&] { SegmentFollower f(path, config); },
                                             "segment_follower." + name);
        }
    }
}

}  // namespace
}  // namespace scantling::control
