// A BSDF's direction sampling seen as a warp of the unit square, so that it is checked like every
// other warp (`penumbra warp microfacet|roughconductor`, the tests, the warp inspector): the viewer
// direction wo is fixed at the incident angle θ in the xz-plane, wo = (sin θ, 0, cos θ), and each
// point u maps to the sampled wi, or to the zero vector where the BSDF rejects the draw (a direction
// reflected below the surface). The density is pdfBsdf, which integrates to 1 minus the rejected mass.
#pragma once

#include <string>

#include "core/materials/bsdf.h"
#include "core/sampling/chi2.h"

namespace penumbra {

// The incident angles a BSDF warp takes (90° would put wo in the surface, where f is 0).
inline constexpr double kMaxIncidentDegrees = 89.99;
// The roughness a BSDF warp takes: lobes narrower than α = 1e-3 are finer than the χ² test's
// (φ, cos θ) histogram and its quadrature resolve (scenes take α down to kMinAlpha; `penumbra check`
// covers those by the albedo identity instead).
inline constexpr double kMinWarpAlpha = 1e-3;

struct BsdfWarp {
  Bsdf bsdf;
  float incidentDegrees = 30.f;

  Vec3 wo() const;
  Vec3 sample(Vec2 u) const;        // wi, or (0, 0, 0) for a rejected draw
  float pdf(const Vec3& wi) const;  // pdfBsdf(bsdf, wo(), wi)
};

// "microfacet, roughconductor": the BSDFs `penumbra warp` takes as a TYPE.
const char* bsdfWarpTypeList();
bool isBsdfWarpName(const std::string& name);

// The χ² set-up of a BSDF warp: the upper hemisphere in (φ, 1 - cos θ), rejected draws as a cell of
// their own; the sample and density as the χ² test's functions.
Chi2Domain bsdfChi2Domain();
SampleFunction bsdfSampleFunction(const BsdfWarp& warp);
PdfFunction bsdfPdfFunction(const BsdfWarp& warp, double scale = 1.0);

// The user's inputs, checked: an Error names `option` of each value out of its range.
struct BsdfWarpInputs {
  std::string type;                       // microfacet | roughconductor
  std::string distribution = "beckmann";  // roughconductor: beckmann | ggx
  double alpha = 0.1;
  double kd = 0.5;  // microfacet's diffuse reflectance (grey)
  double incidentDegrees = 30.0;
  double intIOR = 1.5046, extIOR = 1.000277;  // microfacet
};
// What each input is called in messages: the CLI's options by default (Python names its arguments).
struct BsdfInputNames {
  const char* alpha = "--param";
  const char* incident = "--incident";
  const char* kd = "--kd";
  const char* intIOR = "--int-ior";
  const char* extIOR = "--ext-ior";
  const char* distribution = "--distribution";
};
BsdfWarp checkedBsdfWarp(const BsdfWarpInputs& in, const BsdfInputNames& names = {});
// A short description: "microfacet alpha 0.1 kd 0.5 at 30°".
std::string describeBsdfWarp(const BsdfWarp& warp);

}  // namespace penumbra
