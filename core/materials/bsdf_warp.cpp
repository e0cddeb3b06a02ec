#include "core/materials/bsdf_warp.h"

#include <cmath>
#include <cstdio>

#include "core/math/error.h"

namespace penumbra {

Vec3 BsdfWarp::wo() const {
  const double t = double(incidentDegrees) * kPiD / 180.0;
  return Vec3(float(std::sin(t)), 0.f, float(std::cos(t)));
}

Vec3 BsdfWarp::sample(Vec2 u) const {
  const BsdfSample s = sampleBsdf(bsdf, wo(), u);
  return s.pdf > 0.f ? s.wi : Vec3(0.f);
}

float BsdfWarp::pdf(const Vec3& wi) const {
  return pdfBsdf(bsdf, wo(), wi);
}

const char* bsdfWarpTypeList() {
  return "microfacet, roughconductor";
}

bool isBsdfWarpName(const std::string& name) {
  return name == "microfacet" || name == "roughconductor";
}

Chi2Domain bsdfChi2Domain() {
  return Chi2Domain::sphere(1.0);
}

// wo is fixed: computed once here rather than at every sample or density of a test.
SampleFunction bsdfSampleFunction(const BsdfWarp& warp) {
  return [bsdf = warp.bsdf, wo = warp.wo()](Vec2 u) {
    const BsdfSample s = sampleBsdf(bsdf, wo, u);
    return s.pdf > 0.f ? s.wi : Vec3(0.f);
  };
}

PdfFunction bsdfPdfFunction(const BsdfWarp& warp, double scale) {
  return [bsdf = warp.bsdf, wo = warp.wo(), scale](const Vec3& wi) {
    return scale * double(pdfBsdf(bsdf, wo, wi));
  };
}

namespace {

[[noreturn]] void outOfRange(const char* option, double value, const char* range) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", value);
  throw Error(std::string(option) + " " + buf + ": must be " + range);
}

}  // namespace

BsdfWarp checkedBsdfWarp(const BsdfWarpInputs& in, const BsdfInputNames& names) {
  if (!isBsdfWarpName(in.type))
    throw Error("unknown BSDF \"" + in.type + "\" (expected one of: " + bsdfWarpTypeList() + ")");
  if (!(in.alpha >= kMinWarpAlpha && in.alpha <= kMaxAlpha))
    outOfRange(names.alpha, in.alpha,
               "in [0.001, 1000] (alpha; narrower lobes are finer than the test's histogram)");
  if (!(in.incidentDegrees >= 0.0 && in.incidentDegrees <= kMaxIncidentDegrees))
    outOfRange(names.incident, in.incidentDegrees, "in [0, 89.99] degrees");
  BsdfWarp w;
  w.incidentDegrees = float(in.incidentDegrees);
  if (in.type == "microfacet") {
    if (!(in.kd >= 0.0 && in.kd <= 1.0)) outOfRange(names.kd, in.kd, "in [0, 1]");
    if (!(in.intIOR > 0.0 && std::isfinite(in.intIOR))) outOfRange(names.intIOR, in.intIOR, "finite and > 0");
    if (!(in.extIOR > 0.0 && std::isfinite(in.extIOR))) outOfRange(names.extIOR, in.extIOR, "finite and > 0");
    w.bsdf = makeMicrofacet(Color3(float(in.kd)), float(in.alpha), float(in.intIOR), float(in.extIOR));
    return w;
  }
  MicrofacetDistribution d;
  if (in.distribution == "beckmann")
    d = MicrofacetDistribution::Beckmann;
  else if (in.distribution == "ggx")
    d = MicrofacetDistribution::Ggx;
  else
    throw Error(std::string(names.distribution) + " " + in.distribution + ": expected one of: beckmann, ggx");
  w.bsdf = makeRoughConductor(d, float(in.alpha), Color3(1.f));
  return w;
}

std::string describeBsdfWarp(const BsdfWarp& w) {
  char buf[160];
  if (w.bsdf.type == BsdfType::Microfacet)
    std::snprintf(buf, sizeof buf, "microfacet  alpha %.9g  kd %.9g  incident %.9g deg", w.bsdf.alpha,
                  w.bsdf.albedo.x, w.incidentDegrees);
  else
    std::snprintf(buf, sizeof buf, "roughconductor %s  alpha %.9g  incident %.9g deg",
                  w.bsdf.distribution == MicrofacetDistribution::Ggx ? "ggx" : "beckmann", w.bsdf.alpha,
                  w.incidentDegrees);
  return buf;
}

}  // namespace penumbra
