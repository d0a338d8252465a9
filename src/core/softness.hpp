// Soft constraints (Box2D v3 "soft step", Catto's Solver2D notes): a constraint with position
// error C is treated as a spring-damper of natural frequency f (Hz) and damping ratio zeta,
// integrated implicitly over the substep h. With omega = 2 pi f:
//   bias_rate     = omega / (2 zeta + h omega)                   (velocity bias = bias_rate * C)
//   mass_scale    = h omega (2 zeta + h omega) / (1 + h omega (2 zeta + h omega))
//   impulse_scale = 1 / (1 + h omega (2 zeta + h omega))
// and the impulse is  -mass_scale * m_eff * (Cdot + bias) - impulse_scale * accumulated.
// A rigid constraint is bias 0, mass_scale 1, impulse_scale 0 (used in the relax pass).
#pragma once

#include <cmath>

namespace ragdoll_sim {

struct Softness {
  double bias_rate = 0.0;
  double mass_scale = 1.0;
  double impulse_scale = 0.0;

  static Softness make(double hertz, double zeta, double h) {
    if (hertz <= 0.0) return {};
    double omega = 2.0 * M_PI * hertz;
    double a1 = 2.0 * zeta + h * omega;
    double a2 = h * omega * a1;
    double a3 = 1.0 / (1.0 + a2);
    return {omega / a1, a2 * a3, a3};
  }
  // What one sweep uses: these terms in the biased pass, a rigid constraint in the relax pass.
  Softness orRigid(bool use_bias) const { return use_bias ? *this : Softness(); }
};

}  // namespace ragdoll_sim
