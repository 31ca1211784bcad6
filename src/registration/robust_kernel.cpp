#include <scantling/registration/robust_kernel.hpp>

#include <array>
#include <cmath>
#include <utility>

#include "detail/config_checks.hpp"

namespace scantling::registration {
namespace {

constexpr detail::EnumNames<RobustKernel, 5> kNames = {{
    {RobustKernel::kNone, "none"},
    {RobustKernel::kHuber, "huber"},
    {RobustKernel::kCauchy, "cauchy"},
    {RobustKernel::kGemanMcClure, "geman_mcclure"},
    {RobustKernel::kTukey, "tukey"},
}};

double huber_loss(double r, double s) {
    const double a = std::abs(r);
    return a <= s ? 0.5 * r * r : s * (a - 0.5 * s);
}

double tukey_loss(double r, double s) {
    if (std::abs(r) >= s) return s * s / 6.0;
    const double u = 1.0 - (r / s) * (r / s);
    return s * s / 6.0 * (1.0 - u * u * u);
}

}  // namespace

std::string_view to_string(RobustKernel kernel) { return detail::enum_name(kNames, kernel); }

RobustKernel robust_kernel_from_string(std::string_view name, std::string_view field) {
    return detail::enum_value(kNames, name, field);
}

double robust_weight(RobustKernel kernel, double residual, double scale) {
    const double a = std::abs(residual);
    switch (kernel) {
        case RobustKernel::kNone:
            return 1.0;
        case RobustKernel::kHuber:
            return a <= scale ? 1.0 : scale / a;
        case RobustKernel::kCauchy:
            return 1.0 / (1.0 + (a / scale) * (a / scale));
        case RobustKernel::kGemanMcClure: {
            const double f = scale * scale / (scale * scale + a * a);
            return f * f;
        }
        case RobustKernel::kTukey: {
            if (a >= scale) return 0.0;
            const double u = 1.0 - (a / scale) * (a / scale);
            return u * u;
        }
    }
    return 1.0;
}

double robust_loss(RobustKernel kernel, double residual, double scale) {
    const double r2 = residual * residual;
    const double s2 = scale * scale;
    switch (kernel) {
        case RobustKernel::kNone:
            return 0.5 * r2;
        case RobustKernel::kHuber:
            return huber_loss(residual, scale);
        case RobustKernel::kCauchy:
            return 0.5 * s2 * std::log1p(r2 / s2);
        case RobustKernel::kGemanMcClure:
            return 0.5 * s2 * r2 / (s2 + r2);
        case RobustKernel::kTukey:
            return tukey_loss(residual, scale);
    }
    return 0.5 * r2;
}

}  // namespace scantling::registration
