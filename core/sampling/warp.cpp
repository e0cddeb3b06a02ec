// Planar warps, the type table and the dispatch. Spherical warps live in warp_sphere.cpp.
#include "core/sampling/warp.h"

#include <cmath>

#include "core/math/float_util.h"
#include "core/sampling/warp_util.h"

namespace penumbra {

namespace {

struct WarpInfo {
  WarpType type;
  const char* name;
  bool spherical;
  bool hasParameter;
};

constexpr WarpInfo kWarps[kWarpTypeCount] = {
    {WarpType::UniformSquare, "uniform-square", false, false},
    {WarpType::Tent, "tent", false, false},
    {WarpType::UniformDisk, "uniform-disk", false, false},
    {WarpType::ConcentricDisk, "concentric-disk", false, false},
    {WarpType::UniformSphere, "uniform-sphere", true, false},
    {WarpType::UniformHemisphere, "uniform-hemisphere", true, false},
    {WarpType::CosineHemisphere, "cosine-hemisphere", true, false},
    {WarpType::UniformCone, "uniform-cone", true, true},
    {WarpType::Beckmann, "beckmann", true, true},
};

const WarpInfo& info(WarpType type) {
  return kWarps[static_cast<int>(type)];
}

// 1-D tent on [-1, 1] with density 1 - |x|. Uses the midpoint-centred input (see warp_util.h) so
// u = 0 and u = 1 - 2^-24 land strictly inside (-1, 1), where the density is positive.
inline float tent1D(float u) {
  if (u < 0.5f) return safeSqrt(2.f * u + 0x1p-24f) - 1.f;  // CDF (x+1)^2/2 on [-1, 0]
  return 1.f - safeSqrt(2.f - 2.f * u - 0x1p-24f);          // CDF 1-(1-x)^2/2 on [0, 1]
}

inline float tent1DInverse(float x) {
  float u =
      x < 0.f ? 0.5f * ((x + 1.f) * (x + 1.f) - 0x1p-24f) : 1.f - 0.5f * ((1.f - x) * (1.f - x) + 0x1p-24f);
  return clampUnit(u);
}

inline float tent1DPdf(float x) {
  return std::fabs(x) <= 1.f ? 1.f - std::fabs(x) : 0.f;
}

}  // namespace

const char* warpTypeName(WarpType type) {
  int i = static_cast<int>(type);
  return i >= 0 && i < kWarpTypeCount ? kWarps[i].name : "unknown";
}

bool parseWarpType(const std::string& name, WarpType& out) {
  for (const WarpInfo& w : kWarps) {
    if (name == w.name) {
      out = w.type;
      return true;
    }
  }
  return false;
}

bool warpIsSpherical(WarpType type) {
  return info(type).spherical;
}
bool warpHasParameter(WarpType type) {
  return info(type).hasParameter;
}

Vec3 Warp::warp(WarpType type, Vec2 sample, float param) {
  switch (type) {
    case WarpType::UniformSquare:
      return Vec3(squareToUniformSquare(sample), 0.f);
    case WarpType::Tent:
      return Vec3(squareToTent(sample), 0.f);
    case WarpType::UniformDisk:
      return Vec3(squareToUniformDisk(sample), 0.f);
    case WarpType::ConcentricDisk:
      return Vec3(squareToConcentricDisk(sample), 0.f);
    case WarpType::UniformSphere:
      return squareToUniformSphere(sample);
    case WarpType::UniformHemisphere:
      return squareToUniformHemisphere(sample);
    case WarpType::CosineHemisphere:
      return squareToCosineHemisphere(sample);
    case WarpType::UniformCone:
      return squareToUniformCone(sample, param);
    case WarpType::Beckmann:
      return squareToBeckmann(sample, param);
  }
  return Vec3(0.f);
}

float Warp::pdf(WarpType type, const Vec3& v, float param) {
  Vec2 p(v.x, v.y);
  switch (type) {
    case WarpType::UniformSquare:
      return squareToUniformSquarePdf(p);
    case WarpType::Tent:
      return squareToTentPdf(p);
    case WarpType::UniformDisk:
      return squareToUniformDiskPdf(p);
    case WarpType::ConcentricDisk:
      return squareToConcentricDiskPdf(p);
    case WarpType::UniformSphere:
      return squareToUniformSpherePdf(v);
    case WarpType::UniformHemisphere:
      return squareToUniformHemispherePdf(v);
    case WarpType::CosineHemisphere:
      return squareToCosineHemispherePdf(v);
    case WarpType::UniformCone:
      return squareToUniformConePdf(v, param);
    case WarpType::Beckmann:
      return squareToBeckmannPdf(v, param);
  }
  return 0.f;
}

// ---- uniform square: identity; pdf = 1 on [0,1]^2, 0 elsewhere ----------------------------------
Vec2 Warp::squareToUniformSquare(Vec2 sample) {
  return sample;
}

float Warp::squareToUniformSquarePdf(Vec2 p) {
  return p.x >= 0.f && p.x <= 1.f && p.y >= 0.f && p.y <= 1.f ? 1.f : 0.f;
}

// ---- tent: separable; pdf = (1 - |x|)(1 - |y|) on [-1,1]^2, 0 elsewhere -------------------------
Vec2 Warp::squareToTent(Vec2 sample) {
  return Vec2(tent1D(sample.x), tent1D(sample.y));
}

float Warp::squareToTentPdf(Vec2 p) {
  return tent1DPdf(p.x) * tent1DPdf(p.y);
}

Vec2 Warp::tentToSquare(Vec2 p) {
  return Vec2(tent1DInverse(p.x), tent1DInverse(p.y));
}

// ---- uniform disk (polar, r = sqrt(u1), phi = 2 pi u2): pdf = 1/pi for x^2+y^2 <= 1 --------------
Vec2 Warp::squareToUniformDisk(Vec2 sample) {
  float r = safeSqrt(sample.x);
  const SinCos phi = sinCosTurns(sample.y);
  return Vec2(r * phi.cos, r * phi.sin);
}

float Warp::squareToUniformDiskPdf(Vec2 p) {
  return insideUnitDisk(p) ? kInvPi : 0.f;
}

Vec2 Warp::uniformDiskToSquare(Vec2 p) {
  return Vec2(clampUnit(p.x * p.x + p.y * p.y), phiToUnit(p.y, p.x));
}

// ---- concentric disk (Shirley & Chiu 1997): squares to rings; pdf = 1/pi for x^2+y^2 <= 1 -------
Vec2 Warp::squareToConcentricDisk(Vec2 sample) {
  float rho;
  return concentricPoint(sample, rho);
}

float Warp::squareToConcentricDiskPdf(Vec2 p) {
  return insideUnitDisk(p) ? kInvPi : 0.f;
}

Vec2 Warp::concentricDiskToSquare(Vec2 p) {
  float r = std::sqrt(p.x * p.x + p.y * p.y);
  float phi = std::atan2(p.y, p.x);
  if (phi < -kPiOver4) phi += 2.f * kPi;  // phi in [-pi/4, 7pi/4)
  float a, b;
  if (phi < kPiOver4) {  // right wedge: a = r, theta = pi/4 b/a
    a = r;
    b = phi / kPiOver4 * r;
  } else if (phi < 3.f * kPiOver4) {  // top wedge: b = r, theta = pi/2 - pi/4 a/b
    b = r;
    a = (kPiOver2 - phi) / kPiOver4 * r;
  } else if (phi < 5.f * kPiOver4) {  // left wedge: a = -r, theta = phi - pi
    a = -r;
    b = -(phi - kPi) / kPiOver4 * r;
  } else {  // bottom wedge: b = -r, theta = phi - pi
    b = -r;
    a = -(kPiOver2 - (phi - kPi)) / kPiOver4 * r;
  }
  return Vec2(centredSampleInverse(a), centredSampleInverse(b));
}

}  // namespace penumbra
