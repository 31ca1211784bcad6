// libFuzzer target: read_kitti_bin on arbitrary bytes (KITTI velodyne float32 records).
#include <scantling/io/kitti.hpp>

#include "fuzz_support.hpp"
#include "invariants.hpp"

namespace {
constexpr std::size_t kRecordBytes = 16;  // float32 x, y, z, reflectance (kitti.hpp)
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "input.bin");
    fuzz::expect_only_scantling_errors([&] {
        const PointCloud cloud = io::read_kitti_bin(path);
        fuzz::require_consistent_cloud(cloud, "read_kitti_bin");
        // Accepted only when the size is a whole number of records, one point each.
        if (size % kRecordBytes != 0 || cloud.size() != size / kRecordBytes) {
            fuzz::report_finding(
                "read_kitti_bin accepted a file of " + std::to_string(size) + " bytes",
                std::to_string(cloud.size()) + " points");
        }
    });
    return 0;
}
