#include "tfdem/hard_sphere/collision.h"

#include <limits>

namespace tfdem::hard_sphere {
namespace {

// The impulse of eqs. 20-21 for the contact-point relative velocity v0 (before) along n.
Impulse impulse(const Vec3 &v0, const Vec3 &n, double reduced_mass, const CollisionLaw &law) {
  Impulse j;
  const double normal = dot(v0, n);
  if (normal >= 0) return j;  // not approaching
  const double jn = -(1 + law.restitution) * reduced_mass * normal;
  const Vec3 tangential = v0 - normal * n;
  const double slip = norm(tangential);
  j.on_a = jn * n;
  if (slip == 0) {
    j.sticking = true;
    return j;
  }
  const Vec3 t = (1 / slip) * tangential;
  const double stick = 2.0 / 7.0 * (1 + law.tangential_restitution) * reduced_mass * slip;
  j.sticking = law.friction * jn >= stick;
  j.on_a += (j.sticking ? -stick : -law.friction * jn) * t;
  return j;
}

// The contact-point relative velocity of eq. 11.
Vec3 contact_velocity(const Sphere &a, const Sphere &b, const Vec3 &n) {
  return (a.velocity - b.velocity) - cross(a.radius * a.spin + b.radius * b.spin, n);
}

// Spin change of a solid sphere (I = 2/5 m R^2) from impulse J at its contact point -R n
// (n from the other body to it): I dw = -R n x J.
Vec3 spin_change(const Sphere &s, const Vec3 &n, const Vec3 &j) {
  const double inertia = 0.4 * s.mass * s.radius * s.radius;
  return (-s.radius / inertia) * cross(n, j);
}

}  // namespace

Impulse collide(Sphere &a, Sphere &b, const Vec3 &n, const CollisionLaw &law) {
  const double reduced = 1 / (1 / a.mass + 1 / b.mass);  // m_ab, eq. 16
  const Impulse j = impulse(contact_velocity(a, b, n), n, reduced, law);
  a.velocity += (1 / a.mass) * j.on_a;
  b.velocity -= (1 / b.mass) * j.on_a;
  a.spin += spin_change(a, n, j.on_a);
  b.spin += spin_change(b, n, j.on_a);  // -J at b's contact point +R_b n: the same form
  return j;
}

Impulse collide_with_wall(Sphere &a, const Vec3 &n, const CollisionLaw &law) {
  const Vec3 v0 = a.velocity - cross(a.radius * a.spin, n);
  const Impulse j = impulse(v0, n, a.mass, law);  // m_ab = m_a for a wall
  a.velocity += (1 / a.mass) * j.on_a;
  a.spin += spin_change(a, n, j.on_a);
  return j;
}

}  // namespace tfdem::hard_sphere
