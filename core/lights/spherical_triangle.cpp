#include "core/lights/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

bool SphericalTriangle::init(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& x,
                             double minSolidAngle) {
  solidAngle = 0;
  byArea = false;
  origin = DVec3(x);
  p0 = DVec3(v0);
  e1 = DVec3(v1) - p0;
  e2 = DVec3(v2) - p0;
  const DVec3 n = glm::cross(e1, e2);
  const double twiceArea = glm::length(n);
  if (!(twiceArea > 0) || !std::isfinite(twiceArea)) return false;
  normal = n / twiceArea;
  area = 0.5 * twiceArea;
  // Every quantity below from the vertices relative to x and the edge vectors, whose cross products
  // do not cancel for a small triangle far away: d1 × d2 · d0 = d0 · (e1 × e2), d0 × d1 = d0 × e1, ...
  const DVec3 d0 = p0 - origin, d1 = d0 + e1, d2 = d0 + e2;
  const double l0 = glm::length(d0), l1 = glm::length(d1), l2 = glm::length(d2);
  const double det = glm::dot(d0, n);
  if (!(std::fabs(det) > 1e-12 * l0 * twiceArea) || !std::isfinite(det)) return false;  // x in its plane
  a = d0 / l0, b = d1 / l1, c = d2 / l2;
  // Van Oosterom & Strackee: tan(Ω/2) = |a · (b × c)| / (1 + a·b + b·c + c·a).
  solidAngle =
      2 * std::atan2(std::fabs(det) / (l0 * l1 * l2), 1 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
  const double sign = det > 0 ? 1 : -1;
  edgeNormals[0] = sign * glm::cross(d0, e1);
  edgeNormals[1] = sign * glm::cross(d1, e2 - e1);
  edgeNormals[2] = -sign * glm::cross(d0, e2);
  for (DVec3& m : edgeNormals) m = glm::normalize(m);
  if (!(solidAngle > 0)) return false;
  if (solidAngle < minSolidAngle) {
    byArea = true;
    return true;
  }
  // The angle at a between the arcs to b and to c: (d0 × e1) × (d0 × e2) = d0 (d0 · (e1 × e2)).
  const DVec3 nab = glm::cross(d0, e1), nac = glm::cross(d0, e2);
  alpha = std::atan2(l0 * std::fabs(det), glm::dot(nab, nac));
  sinAlpha = std::sin(alpha);
  cosAlpha = std::cos(alpha);
  cosC = glm::dot(a, b);
  cPerp = glm::normalize(e2 - glm::dot(e2, a) * a);  // = (c − (c·a) a) up to scale, without cancellation
  return true;
}

DVec3 SphericalTriangle::sampleDirection(Vec2 u) const {
  if (byArea) {
    const double su = std::sqrt(double(u.x));
    const DVec3 p = p0 + e1 * (su * (1 - double(u.y))) + e2 * (su * double(u.y));
    return glm::normalize(p - origin);
  }
  // Arvo 1995: the sub-triangle a b ĉ of area u.x Ω, ĉ on the arc from a to c.
  const double areaHat = double(u.x) * solidAngle;
  const double s = std::sin(areaHat - alpha), t = std::cos(areaHat - alpha);
  const double uu = t - cosAlpha, vv = s + sinAlpha * cosC;
  const double q =
      std::clamp(((vv * t - uu * s) * cosAlpha - vv) / ((vv * s + uu * t) * sinAlpha), -1.0, 1.0);
  const DVec3 cHat = q * a + std::sqrt(std::max(0.0, (1 - q) * (1 + q))) * cPerp;
  // Then on the arc from b to ĉ, cos to b linear in u.y: 1 − z = u.y (1 − ĉ·b) = u.y |ĉ − b|² / 2.
  const DVec3 toB = cHat - b;
  const double oneMinusZ = double(u.y) * 0.5 * glm::dot(toB, toB);
  const double z = 1 - oneMinusZ;
  const DVec3 side = cHat - glm::dot(cHat, b) * b;
  const double sideLength = glm::length(side);
  if (!(sideLength > 0)) return b;
  return glm::normalize(z * b + std::sqrt(std::max(0.0, oneMinusZ * (1 + z))) * (side / sideLength));
}

double SphericalTriangle::pdfDirection(const DVec3& w) const {
  if (!(solidAngle > 0)) return 0;
  for (const DVec3& m : edgeNormals)
    if (glm::dot(m, w) < -1e-12) return 0;
  if (!byArea) return 1 / solidAngle;
  const double cosLight = glm::dot(normal, w);
  if (cosLight == 0) return 0;
  const double t = glm::dot(normal, p0 - origin) / cosLight;
  if (!(t > 0)) return 0;
  return t * t / (area * std::fabs(cosLight));
}

}  // namespace penumbra
