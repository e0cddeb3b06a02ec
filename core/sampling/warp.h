// Sample warping: maps uniform points of [0,1)^2 to other domains. Every warp sits next to its pdf
// (density with respect to area on the plane, or solid angle on the sphere) and, where one exists,
// its inverse. Names follow the assignment (Nori's Warp class).
#pragma once

#include <string>

#include "core/math/vec.h"

namespace penumbra {

enum class WarpType : uint8_t {
  UniformSquare,
  Tent,
  UniformDisk,
  ConcentricDisk,
  UniformSphere,
  UniformHemisphere,
  CosineHemisphere,
  UniformCone,
  Beckmann,
};
inline constexpr int kWarpTypeCount = 9;

// The assignment's string names: uniform-square, tent, uniform-disk, concentric-disk, uniform-sphere,
// uniform-hemisphere, cosine-hemisphere, uniform-cone, beckmann.
const char* warpTypeName(WarpType type);
bool parseWarpType(const std::string& name, WarpType& out);
// True for warps whose samples lie on the unit sphere (histogrammed in (phi, cos theta)).
bool warpIsSpherical(WarpType type);
// True when the warp takes a parameter (uniform-cone: cos(theta_max); beckmann: alpha).
bool warpHasParameter(WarpType type);

struct Warp {
  // Dispatch by type; `param` is ignored by warps without a parameter. 2-D warps return z = 0.
  static Vec3 warp(WarpType type, Vec2 sample, float param = 0.f);
  static float pdf(WarpType type, const Vec3& v, float param = 0.f);

  static Vec2 squareToUniformSquare(Vec2 sample);
  static float squareToUniformSquarePdf(Vec2 p);

  static Vec2 squareToTent(Vec2 sample);
  static float squareToTentPdf(Vec2 p);
  static Vec2 tentToSquare(Vec2 p);

  static Vec2 squareToUniformDisk(Vec2 sample);
  static float squareToUniformDiskPdf(Vec2 p);
  static Vec2 uniformDiskToSquare(Vec2 p);

  static Vec2 squareToConcentricDisk(Vec2 sample);
  static float squareToConcentricDiskPdf(Vec2 p);
  static Vec2 concentricDiskToSquare(Vec2 p);

  static Vec3 squareToUniformSphere(Vec2 sample);
  static float squareToUniformSpherePdf(const Vec3& v);
  static Vec2 uniformSphereToSquare(const Vec3& v);

  static Vec3 squareToUniformHemisphere(Vec2 sample);
  static float squareToUniformHemispherePdf(const Vec3& v);
  static Vec2 uniformHemisphereToSquare(const Vec3& v);

  static Vec3 squareToCosineHemisphere(Vec2 sample);
  static float squareToCosineHemispherePdf(const Vec3& v);
  static Vec2 cosineHemisphereToSquare(const Vec3& v);

  // Cone around +z with half-angle theta_max. The sin^2 entry is the accurate one for narrow cones:
  // 1 - cos(theta_max) is computed as sin^2 / (1 + cos), never as 1 - sqrt(1 - sin^2).
  static Vec3 squareToUniformCone(Vec2 sample, float cosThetaMax);
  static float squareToUniformConePdf(const Vec3& v, float cosThetaMax);
  static Vec3 squareToUniformConeSin2(Vec2 sample, float sin2ThetaMax);
  static float squareToUniformConeSin2Pdf(const Vec3& v, float sin2ThetaMax);
  static Vec2 uniformConeToSquare(const Vec3& v, float cosThetaMax);

  // Beckmann microfacet normals, density D(h) cos(theta_h) with roughness alpha.
  static Vec3 squareToBeckmann(Vec2 sample, float alpha);
  static float squareToBeckmannPdf(const Vec3& m, float alpha);
  static Vec2 beckmannToSquare(const Vec3& m, float alpha);
};

}  // namespace penumbra
