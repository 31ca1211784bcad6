// libFuzzer target: read_pcd on arbitrary bytes (ascii, binary and binary_compressed PCD).
#include <scantling/io/pcd.hpp>

#include "fuzz_support.hpp"
#include "invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "input.pcd");
    fuzz::expect_only_scantling_errors(
        [&] { fuzz::require_consistent_cloud(io::read_pcd(path), "read_pcd"); });
    return 0;
}
