#pragma once

namespace kautham::core {

/// ODE's soft contact: with step h, ERP and CFM make each contact point a spring and a damper,
/// kp = ERP / (h CFM) and kd = (1 - ERP) / CFM (ODE's manual, "How to use ERP and CFM"). The
/// same ERP and CFM at another step are another spring: Kautham's CFM 0.3 at its 0.03 s steps is
/// three times softer than at 0.01 s.
struct SoftContact {
  double erp = 0.2;
  double cfm = 1e-5;
};

/// The ERP and CFM that give at steps of `step` seconds the spring and damper that `contact`
/// gives at steps of `givenStep`. A hard contact (CFM 0) stays as it is.
SoftContact softContactAtStep(const SoftContact& contact, double givenStep, double step);

/// The spring constant (N/m) and damping (N s/m) of one contact point.
double contactSpring(const SoftContact& contact, double step);
double contactDamper(const SoftContact& contact);

}  // namespace kautham::core
