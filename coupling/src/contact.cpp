#include "tfdem/contact.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tfdem::contact {
namespace {

constexpr double kPi = 3.14159265358979323846;

void require_positive(double value, const char *name) {
  if (!(value > 0.0))
    throw std::invalid_argument(std::string(name) + " must be > 0, got " + std::to_string(value));
}

void require_restitution(double e, const char *name) {
  if (!(e >= 0.0 && e <= 1.0))
    throw std::invalid_argument(std::string(name) + " must be in [0, 1], got " + std::to_string(e));
}

// sqrt(pi^2 + ln^2 e), finite for e in (0, 1].
double log_restitution_norm(double e) {
  const double log_e = std::log(e);
  return std::sqrt(kPi * kPi + log_e * log_e);
}

// Squared damped angular frequency k/m - gamma^2/4 (1/s^2); <= 0 when overdamped.
double damped_frequency_squared(double stiffness, double damping, double effective_mass) {
  const double gamma = damping / effective_mass;
  return stiffness / effective_mass - 0.25 * gamma * gamma;
}

}  // namespace

double effective_mass(double mass_a, double mass_b) {
  require_positive(mass_a, "mass_a");
  if (std::isinf(mass_b)) return mass_a;
  require_positive(mass_b, "mass_b");
  return mass_a * mass_b / (mass_a + mass_b);
}

double sphere_mass(double diameter, double density) {
  require_positive(diameter, "diameter");
  require_positive(density, "density");
  return density * kPi * diameter * diameter * diameter / 6.0;
}

double normal_damping(double stiffness, double restitution, double effective_mass) {
  require_positive(stiffness, "stiffness");
  require_positive(effective_mass, "effective_mass");
  require_restitution(restitution, "restitution");
  const double critical_half = std::sqrt(effective_mass * stiffness);
  if (restitution == 0.0) return 2.0 * critical_half;
  return -2.0 * std::log(restitution) * critical_half / log_restitution_norm(restitution);
}

double restitution_from_damping(double stiffness, double damping, double effective_mass) {
  require_positive(stiffness, "stiffness");
  require_positive(effective_mass, "effective_mass");
  if (damping < 0.0) throw std::invalid_argument("damping must be >= 0");
  if (damped_frequency_squared(stiffness, damping, effective_mass) <= 0.0) return 0.0;
  const double gamma = damping / effective_mass;
  return std::exp(-0.5 * gamma * contact_time_from_damping(stiffness, damping, effective_mass));
}

double contact_time_from_damping(double stiffness, double damping, double effective_mass) {
  require_positive(stiffness, "stiffness");
  require_positive(effective_mass, "effective_mass");
  const double omega_squared = damped_frequency_squared(stiffness, damping, effective_mass);
  if (omega_squared <= 0.0) return std::numeric_limits<double>::infinity();
  return kPi / std::sqrt(omega_squared);
}

double contact_time(double stiffness, double restitution, double effective_mass) {
  require_positive(stiffness, "stiffness");
  require_positive(effective_mass, "effective_mass");
  require_restitution(restitution, "restitution");
  if (restitution == 0.0) return std::numeric_limits<double>::infinity();
  const double norm = log_restitution_norm(restitution);
  return std::sqrt(effective_mass * norm * norm / stiffness);
}

double tangential_stiffness(double normal_stiffness, double normal_restitution,
                            double tangential_restitution) {
  require_positive(normal_stiffness, "normal_stiffness");
  require_restitution(normal_restitution, "normal_restitution");
  require_restitution(tangential_restitution, "tangential_restitution");
  if (normal_restitution == 0.0 || tangential_restitution == 0.0)
    throw std::invalid_argument("equal contact times need restitution coefficients > 0");
  const double nt = log_restitution_norm(tangential_restitution);
  const double nn = log_restitution_norm(normal_restitution);
  return normal_stiffness * (2.0 / 7.0) * (nt * nt) / (nn * nn);
}

double tangential_damping(double tangential_stiffness, double tangential_restitution,
                          double effective_mass) {
  return normal_damping(tangential_stiffness, tangential_restitution, 2.0 / 7.0 * effective_mass);
}

double effective_modulus(double young_a, double poisson_a, double young_b, double poisson_b) {
  require_positive(young_a, "young_a");
  require_positive(young_b, "young_b");
  for (const double nu : {poisson_a, poisson_b})
    if (!(nu > -1.0 && nu < 0.5)) throw std::invalid_argument("Poisson's ratio must be in (-1, 0.5)");
  return 1.0 / ((1.0 - poisson_a * poisson_a) / young_a + (1.0 - poisson_b * poisson_b) / young_b);
}

double hertz_contact_time(double modulus, double radius, double mass, double impact_speed) {
  require_positive(modulus, "effective_modulus");
  require_positive(radius, "effective_radius");
  require_positive(mass, "effective_mass");
  require_positive(impact_speed, "impact_speed");
  return 2.868 * std::pow(mass * mass / (radius * modulus * modulus * impact_speed), 0.2);
}

double linear_impact_overlap(double stiffness, double effective_mass, double impact_speed) {
  require_positive(stiffness, "stiffness");
  require_positive(effective_mass, "effective_mass");
  if (impact_speed < 0.0) throw std::invalid_argument("impact_speed must be >= 0");
  return impact_speed * std::sqrt(effective_mass / stiffness);
}

double hertz_impact_overlap(double modulus, double radius, double mass, double impact_speed) {
  require_positive(modulus, "effective_modulus");
  require_positive(radius, "effective_radius");
  require_positive(mass, "effective_mass");
  if (impact_speed < 0.0) throw std::invalid_argument("impact_speed must be >= 0");
  return std::pow(15.0 * mass * impact_speed * impact_speed / (16.0 * modulus * std::sqrt(radius)), 0.4);
}

double recommended_time_step(double contact_time, double steps_per_contact) {
  require_positive(contact_time, "contact_time");
  require_positive(steps_per_contact, "steps_per_contact");
  return contact_time / steps_per_contact;
}

}  // namespace tfdem::contact
