// Linear spring-dashpot contact relations (soft-sphere DEM).
//
// References: seed 000 = Hybrid TF-DEM paper (J. Fluids Eng. 129, 2007), eq. 21-26;
// seed 001 = Deen et al., Chem. Eng. Sci. 62 (2007), eq. 16, 24-27, 30, 41-43.
// Damping eta is absolute (force per velocity, N s/m) unless named per_mass (1/s).
#ifndef TFDEM_CONTACT_H
#define TFDEM_CONTACT_H

namespace tfdem::contact {

// Reduced mass m_ab = (1/m_a + 1/m_b)^-1 (seed 001 eq. 16); a wall is m_b = infinity.
double effective_mass(double mass_a, double mass_b);

// Mass of a sphere of diameter d and density rho: rho pi d^3 / 6.
double sphere_mass(double diameter, double density);

// Normal damping eta_n (N s/m) giving restitution e_n (seed 001 eq. 27):
// eta_n = -2 ln(e_n) sqrt(m_ab k_n) / sqrt(pi^2 + ln^2 e_n); e_n = 0 gives 2 sqrt(m_ab k_n).
double normal_damping(double stiffness, double restitution, double effective_mass);

// Restitution of a linear spring-dashpot with absolute damping eta_n (seed 000 eq. 25-26):
// e_n = exp(-gamma t_c / 2) with gamma = eta_n / m_eff, t_c = pi (k_n/m_eff - gamma^2/4)^-1/2.
// Returns 0 for an overdamped contact (no rebound).
double restitution_from_damping(double stiffness, double damping, double effective_mass);

// Contact duration of a damped linear contact, seed 000 eq. 26 (same as seed 001 eq. 41
// with e_n from eq. 25): t_c = pi / sqrt(k_n/m_eff - (eta_n/m_eff)^2 / 4).
double contact_time_from_damping(double stiffness, double damping, double effective_mass);

// Contact duration for restitution e_n (seed 001 eq. 41): sqrt(m_ab (pi^2 + ln^2 e_n) / k_n).
double contact_time(double stiffness, double restitution, double effective_mass);

// Tangential stiffness giving the normal contact time for tangential restitution beta_0
// (seed 001 eq. 43): k_t = k_n (2/7) (pi^2 + ln^2 beta_0) / (pi^2 + ln^2 e_n).
double tangential_stiffness(double normal_stiffness, double normal_restitution,
                            double tangential_restitution);

// Tangential damping (seed 001 eq. 30): eq. 27 with m_ab replaced by (2/7) m_ab and k_n by k_t.
double tangential_damping(double tangential_stiffness, double tangential_restitution,
                          double effective_mass);

// Duration of an elastic Hertz contact (Johnson, Contact Mechanics, 1985, sec. 11.4; the
// nonlinear contact f(delta/d) = sqrt(delta/d) of seed 000 eq. 21): normal force
// (4/3) E* sqrt(R*) delta^(3/2), duration t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5) at impact
// speed v, with the effective modulus 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b and
// radius 1/R* = 1/R_a + 1/R_b (a wall: R_b infinite). It shortens as v grows; damping
// lengthens it, so the elastic value bounds it from below.
double effective_modulus(double young_a, double poisson_a, double young_b, double poisson_b);
double hertz_contact_time(double effective_modulus, double effective_radius, double effective_mass,
                          double impact_speed);

// Deepest overlap of a head-on impact at `impact_speed`, elastic (damping makes it shallower,
// so this bounds it): linear, m_eff delta'' = -k_n delta gives delta = v sqrt(m_eff/k_n);
// Hertz, (1/2) m_eff v^2 = (8/15) E* sqrt(R*) delta^(5/2) gives
// delta = (15 m_eff v^2 / (16 E* sqrt(R*)))^(2/5) (Johnson, Contact Mechanics, sec. 11.4).
double linear_impact_overlap(double stiffness, double effective_mass, double impact_speed);
double hertz_impact_overlap(double effective_modulus, double effective_radius, double effective_mass,
                            double impact_speed);

// DEM time step resolving a contact with `steps_per_contact` steps (dt = t_c / steps).
double recommended_time_step(double contact_time, double steps_per_contact);

}  // namespace tfdem::contact

#endif
