#pragma once
// The simulated vehicle of the control tests: a first-order velocity loop (time constant τ,
// 0.3 s like sim/mav_dynamics.hpp's), the command held over each step and integrated exactly,
// plus an additive disturbance velocity (a crude wind: it moves the position directly).
//   v(t + dt) = v_cmd + (v − v_cmd) e^(−dt/τ)
//   p(t + dt) = p + v_cmd dt + (v − v_cmd) τ (1 − e^(−dt/τ)) + d dt
#include <Eigen/Core>
#include <cmath>

namespace scantling::control::test {

template <typename Vector>
struct VelocityPlant {
    Vector p;
    Vector v;
    double tau_s = 0.3;

    void step(const Vector& v_cmd, double dt_s, const Vector& disturbance) {
        const double decay = std::exp(-dt_s / tau_s);
        p = p + v_cmd * dt_s + (v - v_cmd) * (tau_s * (1.0 - decay)) + disturbance * dt_s;
        v = v_cmd + (v - v_cmd) * decay;
    }
};

using ScalarPlant = VelocityPlant<double>;
using Plant3d = VelocityPlant<Eigen::Vector3d>;

}  // namespace scantling::control::test
