#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/ray_caster.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace scantling::sim {
namespace {

// The double-precision plane refinement makes ranges exact to rounding; 1e-9 m leaves room for
// the few operations involved at room scale (metres).
constexpr double kRangeTol_m = 1e-9;
constexpr double kNormalTol = 1e-12;
constexpr double kInf = std::numeric_limits<double>::infinity();

const Eigen::Vector3d kRoomMin(-2.0, -1.5, -1.0);
const Eigen::Vector3d kRoomMax(3.0, 2.0, 1.5);

// Adds the axis-aligned rectangle face `axis = value` of the box [lo, hi], split into n x n
// quads (shared grid vertices), tagged `tag`. Orientation does not matter to the caster.
void add_face(TriangleMesh& mesh, std::vector<int>& tags, int axis, bool high,
              const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n, int tag) {
    const int a = (axis + 1) % 3;
    const int b = (axis + 2) % 3;
    const int base = static_cast<int>(mesh.vertices.size());
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            Eigen::Vector3d p;
            p[axis] = high ? hi[axis] : lo[axis];
            p[a] = lo[a] + (hi[a] - lo[a]) * i / n;
            p[b] = lo[b] + (hi[b] - lo[b]) * j / n;
            mesh.vertices.push_back(p);
        }
    }
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const int v00 = base + i * (n + 1) + j;
            const int v10 = v00 + n + 1;
            mesh.triangles.emplace_back(v00, v10, v10 + 1);
            mesh.triangles.emplace_back(v00, v10 + 1, v00 + 1);
            tags.push_back(tag);
            tags.push_back(tag);
        }
    }
}

struct TaggedMesh {
    TriangleMesh mesh;
    std::vector<int> tags;
};

// Box room with walls tagged 0..5 = (-x, +x, -y, +y, -z, +z).
TaggedMesh box_room(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n = 1) {
    TaggedMesh room;
    for (int axis = 0; axis < 3; ++axis) {
        add_face(room.mesh, room.tags, axis, false, lo, hi, n, 2 * axis);
        add_face(room.mesh, room.tags, axis, true, lo, hi, n, 2 * axis + 1);
    }
    return room;
}

Eigen::Vector3d unit_axis(int axis, double sign) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d[axis] = sign;
    return d;
}

TEST(RayCaster, AxisRaysFromInsideHitEveryWallAtTheExactDistance) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax);
    const RayCaster caster(room.mesh, room.tags);
    const Eigen::Vector3d origin(0.3, 0.2, 0.1);
    for (int axis = 0; axis < 3; ++axis) {
        for (const double sign : {-1.0, 1.0}) {
            const Eigen::Vector3d d = unit_axis(axis, sign);
            const RayHit hit = caster.cast(origin, d, 10.0);
            const double wall = sign > 0 ? kRoomMax[axis] : kRoomMin[axis];
            ASSERT_TRUE(hit.hit);
            EXPECT_NEAR(hit.range_m, std::abs(wall - origin[axis]), kRangeTol_m);
            EXPECT_NEAR(hit.point[axis], wall, kRangeTol_m);
            EXPECT_TRUE(hit.normal.isApprox(-d, kNormalTol)) << hit.normal.transpose();
            EXPECT_EQ(hit.surface_tag, 2 * axis + (sign > 0 ? 1 : 0));
            EXPECT_LT(hit.triangle, room.mesh.num_triangles());
        }
    }
}

TEST(RayCaster, ObliqueRayHitsTheFirstPlaneItReaches) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax);
    const RayCaster caster(room.mesh, room.tags);
    const Eigen::Vector3d origin(0.0, 0.0, 0.0);
    const Eigen::Vector3d d = Eigen::Vector3d(1.0, 1.0, 1.0).normalized();
    // Planes x = 3, y = 2, z = 1.5 are reached at t = 3√3, 2√3, 1.5√3: the ceiling is first.
    const RayHit hit = caster.cast(origin, d, 100.0);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(hit.range_m, 1.5 * std::sqrt(3.0), kRangeTol_m);
    EXPECT_EQ(hit.surface_tag, 5);
    EXPECT_TRUE(hit.normal.isApprox(-Eigen::Vector3d::UnitZ(), kNormalTol));
    EXPECT_NEAR(hit.normal.norm(), 1.0, kNormalTol);
}

TEST(RayCaster, SurfacesBeyondMaxRangeOrBeforeMinRangeAreMisses) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax);
    const RayCaster caster(room.mesh, room.tags);
    const RayHit short_ray = caster.cast(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 2.99);
    EXPECT_FALSE(short_ray.hit);
    EXPECT_EQ(short_ray.range_m, kInf);
    EXPECT_EQ(short_ray.surface_tag, -1);
    // From a point 1 mm in front of the -x wall looking at it, a 2 mm min range skips it.
    const Ray skip{Eigen::Vector3d(-1.999, 0.0, 0.0), -Eigen::Vector3d::UnitX(), 10.0, 0.002};
    EXPECT_FALSE(caster.cast(skip).hit);
    const RayHit infinite =
        caster.cast(Ray{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), kInf, 0.0});
    ASSERT_TRUE(infinite.hit);
    EXPECT_NEAR(infinite.range_m, 2.0, kRangeTol_m);
}

TEST(RayCaster, SingleTriangleIsHitFromBothSidesWithTheNormalFacingTheRay) {
    TriangleMesh tri;
    tri.vertices = {{0, -1, -1}, {0, 1, -1}, {0, 0, 1}};
    tri.triangles = {{0, 1, 2}};  // normal +x
    const RayCaster caster(tri);
    const RayHit front = caster.cast({2, 0, 0}, {-1, 0, 0}, 5.0);
    const RayHit back = caster.cast({-3, 0, 0}, {1, 0, 0}, 5.0);
    ASSERT_TRUE(front.hit);
    ASSERT_TRUE(back.hit);
    EXPECT_NEAR(front.range_m, 2.0, kRangeTol_m);
    EXPECT_NEAR(back.range_m, 3.0, kRangeTol_m);
    EXPECT_TRUE(front.normal.isApprox(Eigen::Vector3d::UnitX(), kNormalTol));
    EXPECT_TRUE(back.normal.isApprox(-Eigen::Vector3d::UnitX(), kNormalTol));
    EXPECT_EQ(front.surface_tag, 0);  // no tags given
}

TEST(RayCaster, RaysThroughSharedEdgesAndVerticesDoNotLeakOutOfAClosedRoom) {
    constexpr int kGrid = 8;
    const TaggedMesh room = box_room(kRoomMin, kRoomMax, kGrid);
    const RayCaster caster(room.mesh, room.tags);
    const Eigen::Vector3d origin(0.25, 0.25, 0.25);
    int casts = 0;
    for (const auto& tri : room.mesh.triangles) {  // every vertex and edge midpoint
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d& v = room.mesh.vertices[tri[k]];
            const Eigen::Vector3d& w = room.mesh.vertices[tri[(k + 1) % 3]];
            for (const Eigen::Vector3d& target : {v, Eigen::Vector3d(0.5 * (v + w))}) {
                const RayHit hit = caster.cast(origin, (target - origin).normalized(), 100.0);
                ASSERT_TRUE(hit.hit) << "leak towards " << target.transpose();
                EXPECT_NEAR(hit.range_m, (target - origin).norm(), 1e-6);
                ++casts;
            }
        }
    }
    EXPECT_GT(casts, 1000);
}

TEST(RayCaster, FarFromTheOriginRangesStayAccurate) {
    const Eigen::Vector3d shift(2.0e5, -1.0e5, 50.0);  // a world placed in UTM-like coordinates
    const TaggedMesh room = box_room(kRoomMin + shift, kRoomMax + shift);
    const RayCaster caster(room.mesh, room.tags);
    const RayHit hit = caster.cast(shift, Eigen::Vector3d(0.6, 0.8, 0.0), 100.0);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(hit.range_m, 2.0 / 0.8, 1e-6);  // y = 2 is reached before x = 3
}

std::vector<Ray> random_rays(std::size_t n) {
    Rng rng(7);
    std::vector<Ray> rays(n);
    for (auto& ray : rays) {
        ray.origin =
            Eigen::Vector3d(rng.uniform(-1.9, 2.9), rng.uniform(-1.4, 1.9), rng.uniform(-0.9, 1.4));
        ray.direction = rng.normal3(1.0).normalized();
        ray.max_range_m = rng.uniform(0.5, 5.0);
    }
    return rays;
}

TEST(RayCaster, BatchResultsAreIdenticalForOneAndTwoThreadsAndMatchSingleCasts) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax, 4);
    const RayCaster caster(room.mesh, room.tags);
    const std::vector<Ray> rays = random_rays(5000);
    const auto serial = caster.cast_batch(rays, ParallelConfig{1});
    const auto parallel = caster.cast_batch(rays, ParallelConfig{2});
    ASSERT_EQ(serial.size(), rays.size());
    int hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const RayHit single = caster.cast(rays[i]);
        EXPECT_EQ(serial[i].hit, parallel[i].hit);
        EXPECT_EQ(serial[i].range_m, parallel[i].range_m);
        EXPECT_EQ(serial[i].triangle, parallel[i].triangle);
        EXPECT_EQ(serial[i].range_m, single.range_m);
        hits += serial[i].hit ? 1 : 0;
    }
    EXPECT_GT(hits, 1000);  // both outcomes occur
    EXPECT_LT(hits, 4900);
}

TEST(RayCaster, OccludedReportsSurfacesBetweenTwoPointsButNotAtTheEnds) {
    TaggedMesh world = box_room(kRoomMin, kRoomMax);
    // A partition x = 0.5 covering y, z in [-0.5, 0.5].
    add_face(world.mesh, world.tags, 0, false, {0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 1, 6);
    const RayCaster caster(world.mesh, world.tags);
    EXPECT_TRUE(caster.occluded({0, 0, 0}, {1, 0, 0}));
    EXPECT_TRUE(caster.occluded({1, 0, 0}, {0, 0, 0}));
    EXPECT_FALSE(caster.occluded({0, 0.8, 0}, {1, 0.8, 0}));  // passes beside the partition
    EXPECT_FALSE(caster.occluded({0, 0, 0}, {0.5, 0, 0}));    // ends on the partition
    EXPECT_FALSE(caster.occluded({0, 0, 0}, {0, 0, 1.5}));    // ends on the ceiling
    EXPECT_TRUE(caster.occluded({0, 0, 0}, {0, 0, 1.6}));     // passes through the ceiling
    EXPECT_FALSE(caster.occluded({0, 0, 0}, {0, 0, 0}));
}

TEST(RayCaster, MovedCasterKeepsWorking) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax);
    RayCaster first(room.mesh, room.tags);
    RayCaster second = std::move(first);
    EXPECT_TRUE(second.cast(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 5.0).hit);
    RayCaster third(TriangleMesh{});
    third = std::move(second);
    EXPECT_EQ(third.num_triangles(), room.mesh.num_triangles());
    EXPECT_NEAR(third.bounds().max.x(), kRoomMax.x(), 0.0);
}

TEST(RayCaster, EmptyMeshMissesEverything) {
    const RayCaster caster(TriangleMesh{});
    EXPECT_FALSE(caster.cast(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 1e3).hit);
    EXPECT_FALSE(caster.occluded({0, 0, 0}, {5, 0, 0}));
    EXPECT_EQ(caster.num_triangles(), 0u);
}

TEST(RayCaster, RejectsInvalidInput) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax);
    const RayCaster caster(room.mesh, room.tags);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(caster.cast({0, 0, 0}, {1, 1, 0}, 5.0), InputError);
    EXPECT_THROW(caster.cast({nan, 0, 0}, {1, 0, 0}, 5.0), InputError);
    EXPECT_THROW(caster.cast({0, 0, 0}, {1, 0, 0}, 0.0), InputError);
    EXPECT_THROW(caster.cast({0, 0, 0}, {1, 0, 0}, nan), InputError);
    EXPECT_THROW(caster.cast(Ray{{0, 0, 0}, {1, 0, 0}, 1.0, 2.0}), InputError);
    EXPECT_THROW(caster.occluded({0, 0, 0}, {nan, 0, 0}), InputError);
    std::vector<Ray> rays(3);
    rays[2].direction = {0, 0, 2};
    std::vector<RayHit> out(3);
    EXPECT_THROW(caster.cast_batch(rays, out), InputError);
    std::vector<RayHit> short_out(2);
    rays[2].direction = {0, 0, 1};
    EXPECT_THROW(caster.cast_batch(rays, short_out), InputError);
    EXPECT_THROW(caster.cast_batch(rays, out, ParallelConfig{-1}), ConfigError);

    // A large batch is checked in parallel chunks: the first bad ray is named on any count.
    std::vector<Ray> many(10000);
    for (auto& ray : many) ray.max_range_m = 5.0;
    many[9000].min_range_m = -1.0;
    many[5000].direction = {0, 0, 2};
    std::vector<RayHit> many_out(many.size());
    for (int threads : {1, 2}) {
        try {
            caster.cast_batch(many, many_out, ParallelConfig{threads});
            ADD_FAILURE() << "no error on " << threads << " thread(s)";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("ray 5000: |direction| = 2"), std::string::npos)
                << e.what();
        }
    }

    const std::vector<int> wrong_tags(room.mesh.num_triangles() - 1, 0);
    EXPECT_THROW(RayCaster(room.mesh, wrong_tags), InputError);
    TriangleMesh broken = room.mesh;
    broken.triangles[0][1] = 1000;
    EXPECT_THROW(RayCaster{broken}, InputError);
    RayCasterConfig config;
    config.build_parallel.num_threads = -2;
    EXPECT_THROW(RayCaster(room.mesh, room.tags, config), ConfigError);
}

TEST(RayCaster, MediumQualityAndNonRobustBuildsGiveTheSameRanges) {
    const TaggedMesh room = box_room(kRoomMin, kRoomMax, 3);
    RayCasterConfig config;
    config.build_quality = BuildQuality::Medium;
    config.robust = false;
    config.build_parallel.num_threads = 1;
    const RayCaster fast(room.mesh, room.tags, config);
    const RayCaster robust(room.mesh, room.tags);
    for (const Ray& ray : random_rays(500)) {
        const RayHit a = fast.cast(ray);
        const RayHit b = robust.cast(ray);
        EXPECT_EQ(a.hit, b.hit);
        if (a.hit && b.hit) {
            EXPECT_NEAR(a.range_m, b.range_m, kRangeTol_m);
        }
    }
}

}  // namespace
}  // namespace scantling::sim
