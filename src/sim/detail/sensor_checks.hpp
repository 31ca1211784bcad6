#pragma once
// Config checks shared by the simulator (sensors, vehicles, worlds): each throws ConfigError
// "<prefix>.<field> = <value>, expected <what>".

#include <string>
#include <string_view>

namespace scantling::sim::detail {

void require(bool ok, std::string_view prefix, std::string_view field, double value,
             std::string_view expected);
void require_positive(std::string_view prefix, std::string_view field, double value);
void require_non_negative(std::string_view prefix, std::string_view field, double value);
void require_probability(std::string_view prefix, std::string_view field, double value);
/// min in [0, max) and max > 0, both finite (max may not be infinite: rays need a bound).
void require_range_window(std::string_view prefix, double min_range_m, double max_range_m);
/// An angle in (0, max_rad).
void require_angle(std::string_view prefix, std::string_view field, double value_rad,
                   double max_rad);
std::string sub(std::string_view prefix, std::string_view field);

}  // namespace scantling::sim::detail
