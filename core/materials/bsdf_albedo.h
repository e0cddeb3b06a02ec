// Integrals of a BSDF over the hemisphere by quadrature, for tests and `penumbra check`: the
// directional albedo ∫ f(wo, wi) cos θi dωi and the mass of its sampling density ∫ pdf(wo, wi) dωi.
#pragma once

#include <functional>

#include "core/materials/bsdf.h"

namespace penumbra {

// ∫ g(wi) dωi over the upper hemisphere for a g peaked about wo's mirror direction: the midpoint rule
// over half vectors h (wi = wo reflected about h, dωi = 4 |wo·h| dωh) with tan θh = α s and
// s = x / (1 - x) on a grid in (x, φ), so the nodes follow the lobe at every roughness and reach the
// horizon. Wide parts of g (a diffuse lobe) are integrated too, though less finely.
double integrateAboutMirror(const Vec3& wo, double alpha, const std::function<double(const Vec3&)>& g);

// ∫ f(wo, wi) cos θi dωi (first channel), the diffuse part of microfacet in closed form.
double directionalAlbedo(const Bsdf& bsdf, const Vec3& wo);
// ∫ pdfBsdf(wo, wi) dωi: 1 minus the mass of the draws sampleBsdf rejects (the diffuse part in
// closed form).
double sampledMass(const Bsdf& bsdf, const Vec3& wo);

// ∫ f(wo, wi) cos θi dωi (first channel) over the cone of directions within the angle acos(cosMax) of the
// unit vector axis (a uniform sphere light's as seen from the point: times its radiance, the radiance
// reflected from it): the midpoint rule on an n × n grid of equal solid angle in (cos of the angle to
// the axis, azimuth about it), in double but for f.
double coneReflectance(const Bsdf& bsdf, const Vec3& wo, const glm::dvec3& axis, double cosMax, int n = 1500);

}  // namespace penumbra
