// libFuzzer target: read_ply on arbitrary bytes (ascii and binary PLY, clouds and meshes).
#include <scantling/io/ply.hpp>

#include "fuzz_support.hpp"
#include "invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "input.ply");
    fuzz::expect_only_scantling_errors([&] {
        const io::PlyData ply = io::read_ply(path);
        fuzz::require_consistent_cloud(ply.cloud, "read_ply");
        fuzz::require_faces_in_range(ply.faces, ply.cloud.size(), "read_ply");
    });
    return 0;
}
