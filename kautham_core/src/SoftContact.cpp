#include "kautham/core/SoftContact.h"

namespace kautham::core {

double contactSpring(const SoftContact& contact, double step) {
  return contact.erp / (step * contact.cfm);
}

double contactDamper(const SoftContact& contact) { return (1.0 - contact.erp) / contact.cfm; }

SoftContact softContactAtStep(const SoftContact& contact, double givenStep, double step) {
  if (!(contact.cfm > 0.0)) return contact;
  const double kp = contactSpring(contact, givenStep);
  const double kd = contactDamper(contact);
  // ERP = h kp / (h kp + kd), CFM = 1 / (h kp + kd).
  const double denominator = step * kp + kd;
  return {step * kp / denominator, 1.0 / denominator};
}

}  // namespace kautham::core
