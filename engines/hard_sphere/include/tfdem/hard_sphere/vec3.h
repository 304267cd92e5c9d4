// A 3-vector of doubles for the hard-sphere engine's kinematics (header only).
#ifndef TFDEM_HARD_SPHERE_VEC3_H
#define TFDEM_HARD_SPHERE_VEC3_H

#include <cmath>

namespace tfdem::hard_sphere {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  double &operator[](int a) { return a == 0 ? x : a == 1 ? y : z; }
  double operator[](int a) const { return a == 0 ? x : a == 1 ? y : z; }
  Vec3 &operator+=(const Vec3 &o) {
    x += o.x, y += o.y, z += o.z;
    return *this;
  }
  Vec3 &operator-=(const Vec3 &o) {
    x -= o.x, y -= o.y, z -= o.z;
    return *this;
  }
};

inline Vec3 operator+(Vec3 a, const Vec3 &b) { return a += b; }
inline Vec3 operator-(Vec3 a, const Vec3 &b) { return a -= b; }
inline Vec3 operator-(const Vec3 &a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(double s, const Vec3 &a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3 &a, const Vec3 &b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3 &a) { return std::sqrt(dot(a, a)); }

}  // namespace tfdem::hard_sphere

#endif
