#pragma once
// Scenario checks that a key range cannot express (scenario_world_size.cpp).

#include <string_view>

#include <scantling/sim/scenario.hpp>

namespace scantling::sim::detail {

/// Throws ConfigError naming the keys whose product sizes the world mesh (storage-tank
/// courses x segments, Moebius segments, urban facade windows) when it exceeds
/// limits::kMaxWorldElements, and a plate stiffener spacing that is neither 0 nor at least
/// limits::kMinStructureSpacing_m. Call after the world's own validate().
void check_world_size(const WorldSpec& spec, std::string_view prefix);

}  // namespace scantling::sim::detail
