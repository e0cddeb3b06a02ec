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

}  // namespace penumbra
