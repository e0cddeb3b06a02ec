// Checks the closed form I(θ, α) against things that do not depend on it: brute-force quadrature of
// ∫ max(0, n·ω) dω over the spherical cap, limits, regime continuity and independent identities.
#include "core/lights/sphere_cap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/math/vec.h"

namespace penumbra {
namespace {

// Gauss-Legendre nodes/weights on [-1, 1] by Newton iteration on P_n.
struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(n), w(n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPiD * (i + 0.75) / (n + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[i] = z;
      w[i] = 2 / ((1 - z * z) * dp * dp);
    }
  }
  // ∫_a^b f, split into `panels` equal panels.
  template <class F>
  double integrate(F&& f, double a, double b, int panels) const {
    double sum = 0, h = (b - a) / panels;
    for (int p = 0; p < panels; ++p) {
      double lo = a + p * h, mid = lo + 0.5 * h;
      for (size_t i = 0; i < x.size(); ++i) sum += w[i] * f(mid + 0.5 * h * x[i]);
    }
    return sum * 0.5 * h;
  }
};

// Brute-force ∫_cap max(0, n·ω) dω in the cap's own coordinates: t = 1 - cos β ∈ [0, 1 - cos α]
// (β measured from the direction to the centre), φ ∈ [0, 2π) around it, dω = dt dφ, and
// n·ω = (1 - t) cos θ + sin β sin θ cos φ. The φ integral is taken numerically over the part of the
// ring above the horizon (found by bisection on the sign of n·ω, not from any formula), and the t range
// is split where rings start crossing the horizon so each piece is smooth apart from endpoint roots.
double quadratureI(double cosTheta, double sinAlpha) {
  static const GaussLegendre gl(24);
  const double sinTheta = std::sqrt((1 - cosTheta) * (1 + cosTheta));
  const double cosAlpha = std::sqrt((1 - sinAlpha) * (1 + sinAlpha));
  const double T = sinAlpha * sinAlpha / (1 + cosAlpha);
  auto ring = [&](double t) {
    const double sinBeta = std::sqrt(std::max(0.0, t * (2 - t)));
    auto f = [&](double phi) { return (1 - t) * cosTheta + sinBeta * sinTheta * std::cos(phi); };
    // f is decreasing in φ on [0, π]: find where it changes sign.
    double hi;
    if (f(kPiD) >= 0)
      hi = kPiD;
    else if (f(0) <= 0)
      return 0.0;
    else {
      double a = 0, b = kPiD;
      for (int i = 0; i < 200 && b - a > 1e-17; ++i) {
        double m = 0.5 * (a + b);
        (f(m) > 0 ? a : b) = m;
      }
      hi = 0.5 * (a + b);
    }
    return 2 * gl.integrate([&](double phi) { return std::max(0.0, f(phi)); }, 0, hi, 8);
  };
  // Rings cross the horizon for β > |π/2 - θ|, i.e. t > 1 - sin θ.
  const double tk = cosTheta * cosTheta / (1 + sinTheta);
  // Substitute t = a + (b - a) s² near each end to tame the √ behaviour of the clipped ring length.
  auto piece = [&](double a, double b) {
    if (b <= a) return 0.0;
    const double m = 0.5 * (a + b);
    auto lower = [&](double s) { return ring(a + (m - a) * s * s) * 2 * s * (m - a); };
    auto upper = [&](double s) { return ring(b - (b - m) * s * s) * 2 * s * (b - m); };
    return gl.integrate(lower, 0, 1, 40) + gl.integrate(upper, 0, 1, 40);
  };
  if (tk > 0 && tk < T) return piece(0, tk) + piece(tk, T);
  return piece(0, T);
}

struct Case {
  double theta, sinAlpha;
};

TEST(SphereCapClosedForm, SphereLightMatchesQuadrature) {
  std::vector<Case> cases;
  for (double sa : {0.999, 0.9, 0.7, 0.5, 0.3, 0.1, 0.01, 1e-3}) {
    const double alpha = std::asin(sa);
    // Fully above, straddling (several offsets around the horizon), fully below, and θ = π/2.
    for (double theta : {0.0, 0.3, 1.0, kPiD / 2 - 1.2 * alpha, kPiD / 2 - 0.8 * alpha,
                         kPiD / 2 - 0.3 * alpha, kPiD / 2, kPiD / 2 + 0.3 * alpha, kPiD / 2 + 0.8 * alpha,
                         kPiD / 2 + 0.99 * alpha, kPiD / 2 + 1.2 * alpha, 2.5})
      if (theta >= 0 && theta <= kPiD) cases.push_back({theta, sa});
  }
  for (const Case& c : cases) {
    const double cosTheta = c.theta == kPiD / 2 ? 0.0 : std::cos(c.theta);
    const double I = sphereLightIrradianceFactor(cosTheta, c.sinAlpha);
    const double Q = quadratureI(cosTheta, c.sinAlpha);
    // Scale of I is π sin²α; demand agreement to 1e-9 of that scale.
    const double scale = kPiD * c.sinAlpha * c.sinAlpha;
    EXPECT_NEAR(I, Q, 1e-9 * scale) << "theta=" << c.theta << " sinAlpha=" << c.sinAlpha;
    EXPECT_GE(I, 0.0);
  }
}

TEST(SphereCapClosedForm, HorizonCase) {
  for (double sa : {0.999, 0.9, 0.5, 0.1, 1e-2, 1e-3, 1e-5}) {
    const double alpha = std::asin(sa);
    const double I = sphereLightIrradianceFactor(0.0, sa);
    EXPECT_NEAR(I, sphereLightHorizonFactor(alpha), 1e-13 * sa * sa) << sa;
    if (sa >= 0.1) {
      EXPECT_NEAR(I, alpha - std::sin(alpha) * std::cos(alpha), 1e-14);
    }
    // Leading order 2α³/3 for tiny α.
    if (sa <= 1e-3) {
      EXPECT_NEAR(I / (2.0 / 3.0 * alpha * alpha * alpha), 1.0, 1e-5);
    }
  }
}

TEST(SphereCapClosedForm, AtanMinusIdentitySeriesMatchesDirect) {
  for (double w : {0.0999, 0.09, 0.05, 0.03}) EXPECT_NEAR(atanMinusIdentity(w), std::atan(w) - w, 1e-15);
  // Tiny w: leading term -w³/3 (direct evaluation would return 0 or noise here).
  EXPECT_NEAR(atanMinusIdentity(1e-6) / (-1e-18 / 3), 1.0, 1e-11);
  EXPECT_EQ(atanMinusIdentity(0.0), 0.0);
}

TEST(SphereCapClosedForm, RegimeBoundariesAreContinuous) {
  for (double sa : {0.9, 0.5, 0.1, 1e-3}) {
    const double scale = kPiD * sa * sa;
    for (double sign : {1.0, -1.0}) {
      const double edge = sign * sa;
      const double inside = sphereLightIrradianceFactor(edge * (1 - 1e-12), sa);
      const double outside = sphereLightIrradianceFactor(edge * (1 + 1e-12), sa);
      EXPECT_NEAR(inside, outside, 1e-9 * scale) << "sinAlpha=" << sa << " sign=" << sign;
      EXPECT_NEAR(inside, sign > 0 ? kPiD * sa * sa * sa : 0.0, 1e-9 * scale);
    }
  }
}

TEST(SphereCapClosedForm, StableAndDirectStraddlingFormsAgree) {
  // Moderate α: both forms accurate -> agree to rounding.
  for (double sa : {0.9, 0.5, 0.2}) {
    const double ca = std::sqrt(1 - sa * sa);
    for (double f : {-0.9, -0.5, 0.0, 0.5, 0.9}) {
      const double ct = f * sa, st = std::sqrt(1 - ct * ct);
      EXPECT_NEAR(sphereLightIrradianceFactor(ct, st, sa, ca), sphereLightStraddlingDirect(ct, st, sa, ca),
                  1e-14)
          << sa << " " << f;
    }
  }
  // Tiny α: the direct form cancels catastrophically, the stable one stays on the quadrature.
  const double sa = 1e-4, ca = std::sqrt(1 - sa * sa), ct = 0.0, st = 1.0;
  const double stable = sphereLightIrradianceFactor(ct, st, sa, ca);
  EXPECT_NEAR(stable / sphereLightHorizonFactor(std::asin(sa)), 1.0, 1e-12);
  EXPECT_NEAR(sphereLightStraddlingDirect(ct, st, sa, ca), stable, 1e-15);  // only absolutely close
}

}  // namespace
}  // namespace penumbra
