// Built against an installed scantling: proves the exported targets and headers are complete.
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/voxel_grid.hpp>

int main() {
    scantling::PointCloud cloud;
    for (int i = 0; i < 100; ++i) cloud.points.emplace_back(0.01 * i, 0.0, 0.0);
    const auto down = scantling::voxel_downsample(cloud, 0.1);
    return down.size() == 10 ? 0 : 1;
}
