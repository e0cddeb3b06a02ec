// Checks the geometric front end of the closed forms (the angle forms are checked against quadrature
// in core/lights/sphere_cap_test.cpp) and the AO forms: limits and independent identities.
#include "core/analysis/closed_forms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <cmath>

#include "core/math/vec.h"

namespace penumbra {
namespace {

TEST(ClosedForms, GeometricFrontEnd) {
  const glm::dvec3 c(0.3, -0.2, 2.0);
  const double r = 0.7;
  // Points around the sphere with various normals: compare with the (cos θ, sin α) form.
  for (double px : {-3.0, 0.0, 1.5})
    for (double nz : {1.0, 0.2, 0.0, -0.3}) {
      const glm::dvec3 x(px, 0.5, 0.4), n = glm::normalize(glm::dvec3(0.3, 0.1, nz));
      const double d = glm::length(c - x);
      const double cosTheta = glm::dot(n, c - x) / d;
      EXPECT_NEAR(sphereLightIrradianceFactor(x, n, c, r), sphereLightIrradianceFactor(cosTheta, r / d),
                  1e-12);
      // Unnormalised n gives the same answer.
      EXPECT_NEAR(sphereLightIrradianceFactor(x, 5.0 * n, c, r), sphereLightIrradianceFactor(x, n, c, r),
                  1e-13);
    }
  // Inside: one-sided 0, two-sided π.
  EXPECT_EQ(sphereLightIrradianceFactor(c + glm::dvec3(0.1, 0, 0), glm::dvec3(0, 0, 1), c, r), 0.0);
  EXPECT_EQ(sphereLightIrradianceFactor(c + glm::dvec3(0.1, 0, 0), glm::dvec3(0, 0, 1), c, r, true), kPiD);
  EXPECT_EQ(sphereLightIrradianceFactor(c, glm::dvec3(0, 0, 1), c, r), 0.0);
}

TEST(ClosedForms, SurfaceLimitFromOutside) {
  const glm::dvec3 c(1.0, 2.0, 3.0);
  for (double r : {1.0, 1e-3, 250.0})
    for (double theta : {0.0, 0.4, kPiD / 2, 2.0, 3.0}) {
      // The deviation from the limit is O(cos α) ≈ √(2 eps), at most ≈ 2 cos α (attained at θ = π/2).
      // x just outside the sphere, in direction -u from c; n at angle θ from (c - x).
      const glm::dvec3 u = glm::normalize(glm::dvec3(0.2, -0.5, 0.8));
      const glm::dvec3 perp = glm::normalize(glm::cross(u, glm::dvec3(1, 0, 0)));
      const glm::dvec3 n = std::cos(theta) * u + std::sin(theta) * perp;
      const double limit = 0.5 * kPiD * (1 + std::cos(theta));
      EXPECT_NEAR(sphereLightIrradianceFactor(c - r * u, n, c, r), limit, 1e-12);
      double prevErr = 1e300;
      for (double eps : {1e-6, 1e-8}) {
        const glm::dvec3 x = c - r * (1 + eps) * u;
        const double I = sphereLightIrradianceFactor(x, n, c, r);
        const double cosAlpha = std::sqrt(eps * (2 + eps)) / (1 + eps);
        const double err = std::abs(I - limit);
        EXPECT_LE(err, 2.01 * cosAlpha + 1e-12) << "r=" << r << " theta=" << theta << " eps=" << eps;
        EXPECT_LE(err, prevErr + 1e-12);
        prevErr = err;
      }
    }
}

TEST(ClosedForms, EqualPowerAtAFarPoint) {
  // Le r² fixed -> same E at a fixed far point, for any r (fully above the horizon).
  const glm::dvec3 x(0, 0, 0), c(3.0, 4.0, 12.0);  // d = 13
  for (const glm::dvec3& n : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(1, 0, 0.3))}) {
    const double ref = sphereLightIrradianceFactor(x, n, c, 1.0) * 1.0;
    EXPECT_GT(ref, 0.0);
    for (double r : {1e-3, 1e-6}) {
      const double Le = 1.0 / (r * r);
      EXPECT_NEAR(Le * sphereLightIrradianceFactor(x, n, c, r) / ref, 1.0, 1e-12) << r;
    }
  }
}

TEST(ClosedForms, AoPlaneWithSphereIsOneMinusIOverPi) {
  const glm::dvec3 x(0, 0, 0), n(0, 0, 1);
  // Sphere above, straddling the horizon, and cutting the plane.
  for (const glm::dvec3& c : {glm::dvec3(0, 0, 3), glm::dvec3(2, 0, 0.5), glm::dvec3(2, 0, -0.5)}) {
    const double r = 1.0, d = glm::length(c);
    const double ao = aoPlaneWithSphere(x, n, c, r);
    EXPECT_NEAR(ao, 1 - sphereLightIrradianceFactor(c.z / d, r / d) / kPiD, 1e-14);
    EXPECT_NEAR(ao, aoPlaneWithSphere(c.z / d, r / d), 1e-14);
  }
  // Inside the occluder: fully occluded.
  EXPECT_EQ(aoPlaneWithSphere(x, n, glm::dvec3(0.1, 0, 0), 1.0), 0.0);
}

TEST(ClosedForms, RestingSphereMatchesGeneralPlaneSphere) {
  for (double R : {1.0, 1e-3, 40.0})
    for (double rho : {0.0, 1e-6, 1e-3, 0.1, 0.5, 1.0, 3.0, 100.0}) {
      const double rr = rho * R;
      const glm::dvec3 x(rr, 0, 0), n(0, 0, 1), c(0, 0, R);
      const double general = aoPlaneWithSphere(x, n, c, R);
      const double resting = aoPlaneNearRestingSphere(rr, R);
      EXPECT_NEAR(resting, general, 1e-13) << "R=" << R << " rho/R=" << rho;
      EXPECT_NEAR(resting, 1 - std::pow(R * R / (rr * rr + R * R), 1.5), 1e-14);
    }
  // Small ρ: ≈ 1.5 ρ²/R² with full relative precision.
  EXPECT_NEAR(aoPlaneNearRestingSphere(1e-6, 1.0) / 1.5e-12, 1.0, 1e-9);
  EXPECT_EQ(aoPlaneNearRestingSphere(0.0, 2.0), 0.0);
}

TEST(ClosedForms, RestingConvexBody) {
  for (double psi : {0.0, 0.5, kPiD / 2, 2.5, 3.1})
    EXPECT_NEAR(aoOnRestingConvexBody(psi), (1 + std::cos(psi)) / 2, 1e-15);
  // Near the contact point the cos² form keeps relative precision: (π - ψ)²/4.
  const double e = 1e-7;
  EXPECT_NEAR(aoOnRestingConvexBody(kPiD - e) / (e * e / 4), 1.0, 1e-6);
  // Top of a sphere resting on a plane: unoccluded. Equator: the plane blocks half the cosine lobe.
  EXPECT_DOUBLE_EQ(aoOnRestingConvexBody(0.0), 1.0);
  EXPECT_NEAR(aoOnRestingConvexBody(kPiD / 2), 0.5, 1e-15);
}

// Lambert's formula: a square light straight above x tends to π close up and to A / h² far away; the
// side facing away and the light's plane give 0; two triangles make their quad; a light straddling the
// horizon counts only its part above it.
TEST(ClosedForms, PolygonLightIrradianceFactor) {
  const glm::dvec3 x(0), n(0, 0, 1);
  auto squareAt = [](double h, double a) {  // wound clockwise seen from above: emits downwards
    return std::vector<glm::dvec3>{{-a, -a, h}, {-a, a, h}, {a, a, h}, {a, -a, h}};
  };
  EXPECT_NEAR(polygonLightIrradianceFactor(x, n, squareAt(1e-6, 1)), kPiD, 1e-5);
  EXPECT_NEAR(polygonLightIrradianceFactor(x, n, squareAt(1e3, 0.5)) / (1.0 / 1e6), 1.0, 1e-6);
  std::vector<glm::dvec3> up = squareAt(1, 1);
  std::reverse(up.begin(), up.end());
  EXPECT_EQ(polygonLightIrradianceFactor(x, n, up), 0.0);
  EXPECT_EQ(polygonLightIrradianceFactor(glm::dvec3(0, 0, 1), n, squareAt(1, 1)), 0.0);
  const std::vector<glm::dvec3> quad = squareAt(0.7, 0.4);
  EXPECT_NEAR(polygonLightIrradianceFactor(x, n, quad),
              polygonLightIrradianceFactor(x, n, {quad[0], quad[1], quad[2]}) +
                  polygonLightIrradianceFactor(x, n, {quad[0], quad[2], quad[3]}),
              1e-14);
  // A wall x = 1 facing x, from z = −1 to 1: its upper half's Ω⊥.
  const std::vector<glm::dvec3> wall = {{1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}};
  const std::vector<glm::dvec3> upperHalf = {{1, -1, 0}, {1, -1, 1}, {1, 1, 1}, {1, 1, 0}};
  EXPECT_GT(polygonLightIrradianceFactor(x, n, upperHalf), 0.1);
  EXPECT_NEAR(polygonLightIrradianceFactor(x, n, wall), polygonLightIrradianceFactor(x, n, upperHalf), 1e-15);
}

}  // namespace
}  // namespace penumbra
