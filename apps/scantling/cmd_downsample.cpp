#include <scantling/core/error.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {

void run_downsample(const ConvertOptions& options, std::ostream& out) {
    if (!options.voxel_size_m) throw ConfigError("downsample: --voxel SIZE_M is required");
    run_convert(options, out);
}

}  // namespace scantling::app
