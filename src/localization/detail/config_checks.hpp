#pragma once
// The shared ConfigError checks (core/config_checks.hpp), under the names localization uses.
#include <scantling/core/config_checks.hpp>

namespace scantling::localization::detail {

using config_checks::require;
using config_checks::require_count_at_least;
using config_checks::require_non_negative;
using config_checks::require_positive;

}  // namespace scantling::localization::detail
