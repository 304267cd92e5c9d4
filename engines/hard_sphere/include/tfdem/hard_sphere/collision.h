// One binary hard-sphere collision (seed 001 sec. 3.3, eqs. 11-21, after Hoomans et al. 1996):
// an instantaneous impulse J between two solid spheres (I = 2/5 m R^2), or a sphere and a wall
// (infinite mass, at rest), closed by three coefficients:
//   normal restitution     v_ab.n = -e_n (v_ab,0.n)                       (eq. 17, 0 <= e_n <= 1)
//   friction               |n x J| = -mu (n.J) while sliding               (eq. 18, mu >= 0)
//   tangential restitution n x v_ab = -beta_0 (n x v_ab,0) when sticking   (eq. 19, 0 <= beta_0 <= 1)
// with the contact-point relative velocity v_ab = (v_a - v_b) - (R_a w_a + R_b w_b) x n (eq. 11),
// n the unit vector from b to a and t the direction of v_ab,0's tangential part (eq. 12). Then
//   J_n = -(1 + e_n) m_ab (v_ab,0.n)                                                  (eq. 20)
//   J_t = -(2/7)(1 + beta_0) m_ab (v_ab,0.t)  if mu J_n >= (2/7)(1 + beta_0) m_ab (v_ab,0.t)
//         -mu J_n                             otherwise (sliding)                     (eq. 21)
// and m_a dv_a = J = -m_b dv_b (eq. 13). Spins: the impulse acts at each sphere's contact point,
// so I dw = -R n x J for both spheres; this gives eq. 15, v_ab - v_ab,0 = (7 J - 5 n (J.n))/(2 m_ab)
// (the printed eq. 14 carries the OCR's sign slip for b). Stateless: values in, values out.
#ifndef TFDEM_HARD_SPHERE_COLLISION_H
#define TFDEM_HARD_SPHERE_COLLISION_H

#include "tfdem/hard_sphere/vec3.h"

namespace tfdem::hard_sphere {

struct Sphere {
  Vec3 velocity, spin;  // m/s, rad/s
  double radius = 0;    // m
  double mass = 0;      // kg; infinite for a wall
};

struct CollisionLaw {
  double restitution = 1;             // e_n
  double friction = 0;                // mu
  double tangential_restitution = 0;  // beta_0
};

// The impulse on a (-impulse on b), and whether the collision stuck (eq. 21's first case).
struct Impulse {
  Vec3 on_a;
  bool sticking = false;
};

// The collision of a and b touching along n (unit, from b to a): their velocities and spins
// after it. A pair that is not approaching (v_ab,0.n >= 0) is left as it is (zero impulse).
Impulse collide(Sphere &a, Sphere &b, const Vec3 &n, const CollisionLaw &law);

// A sphere hitting a wall whose unit normal n points from the wall into the domain.
Impulse collide_with_wall(Sphere &a, const Vec3 &n, const CollisionLaw &law);

}  // namespace tfdem::hard_sphere

#endif
