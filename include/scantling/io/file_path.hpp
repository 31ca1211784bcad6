#pragma once
/// @file Small path helpers shared by the readers, writers and the CLI.

#include <string>

namespace scantling::io {

/// Extension of `path` with its dot, lower-cased ("scan.PCD" → ".pcd"; "" when none).
std::string lower_extension(const std::string& path);

}  // namespace scantling::io
