// Small fixed-size vector math used everywhere in Radiant.
//
// Plain structs with free functions (yocto style). Double precision throughout:
// radiosity form factors and energy balances need it, and the path tracer's cost
// is dominated by Embree, which works in float on its own copy of the geometry.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radiant {

constexpr double kPi = std::numbers::pi;
constexpr double kInvPi = 1.0 / std::numbers::pi;

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 &operator+=(const Vec3 &b) {
    x += b.x;
    y += b.y;
    z += b.z;
    return *this;
  }
  constexpr Vec3 &operator-=(const Vec3 &b) {
    x -= b.x;
    y -= b.y;
    z -= b.z;
    return *this;
  }
  constexpr Vec3 &operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

constexpr Vec3 operator+(const Vec3 &a, const Vec3 &b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(const Vec3 &a, const Vec3 &b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3 operator*(const Vec3 &a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3 operator*(double s, const Vec3 &a) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3 operator/(const Vec3 &a, double s) {
  return {a.x / s, a.y / s, a.z / s};
}
constexpr bool operator==(const Vec3 &a, const Vec3 &b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

constexpr double dot(const Vec3 &a, const Vec3 &b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3 &a, const Vec3 &b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3 &a) {
  return std::sqrt(dot(a, a));
}
inline Vec3 normalize(const Vec3 &a) {
  double l = length(a);
  return l > 0 ? a / l : a;
}
inline bool isFinite(const Vec3 &a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// Orthonormal frame around a unit normal (Duff et al. 2017, "Building an
/// orthonormal basis, revisited"): no branch on a threshold, no singularity.
struct Frame {
  Vec3 tangent, bitangent, normal;

  static Frame fromNormal(const Vec3 &n) {
    double sign = std::copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double b = n.x * n.y * a;
    return {{1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  Vec3 toLocal(const Vec3 &v) const { return {dot(v, tangent), dot(v, bitangent), dot(v, normal)}; }
  Vec3 toWorld(const Vec3 &v) const { return tangent * v.x + bitangent * v.y + normal * v.z; }
};

/// Row-major 4x4 affine transform for object placement in scene files.
struct Transform {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

  Vec3 point(const Vec3 &p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3 vector(const Vec3 &v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  /// Normals transform by the inverse transpose; the cofactor matrix is that up
  /// to a positive scale (for non-mirroring transforms), which normalisation removes.
  Vec3 normal(const Vec3 &n) const {
    Vec3 c0{m[0][0], m[1][0], m[2][0]}, c1{m[0][1], m[1][1], m[2][1]}, c2{m[0][2], m[1][2], m[2][2]};
    Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
    double det = dot(c0, r0);
    Vec3 out = r0 * n.x + r1 * n.y + r2 * n.z;
    return normalize(det < 0 ? -out : out);
  }
  double determinant() const {
    Vec3 c0{m[0][0], m[1][0], m[2][0]}, c1{m[0][1], m[1][1], m[2][1]}, c2{m[0][2], m[1][2], m[2][2]};
    return dot(c0, cross(c1, c2));
  }
  /// this ∘ other: apply `other` first.
  Transform operator*(const Transform &o) const {
    Transform r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) {
        double s = (j == 3) ? m[i][3] : 0.0;
        for (int k = 0; k < 3; ++k) s += m[i][k] * o.m[k][j];
        r.m[i][j] = s;
      }
    return r;
  }
  static Transform translate(const Vec3 &t) {
    Transform r;
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
  }
  static Transform scale(const Vec3 &s) {
    Transform r;
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
  }
  /// Rotation by `degrees` about `axis` (right-handed).
  static Transform rotate(double degrees, const Vec3 &axis) {
    Vec3 a = normalize(axis);
    double t = degrees * kPi / 180.0, c = std::cos(t), s = std::sin(t), C = 1 - c;
    Transform r;
    r.m[0][0] = c + a.x * a.x * C;
    r.m[0][1] = a.x * a.y * C - a.z * s;
    r.m[0][2] = a.x * a.z * C + a.y * s;
    r.m[1][0] = a.y * a.x * C + a.z * s;
    r.m[1][1] = c + a.y * a.y * C;
    r.m[1][2] = a.y * a.z * C - a.x * s;
    r.m[2][0] = a.z * a.x * C - a.y * s;
    r.m[2][1] = a.z * a.y * C + a.x * s;
    r.m[2][2] = c + a.z * a.z * C;
    return r;
  }
};

inline double sqr(double x) {
  return x * x;
}

}  // namespace radiant
