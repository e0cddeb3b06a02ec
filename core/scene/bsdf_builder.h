// <bsdf> elements of a shape: the reflection model and its parameters (core/materials/bsdf.h).
//
// <bsdf type="diffuse">         albedo (colour, 0.5)
// <bsdf type="phong">           the assignment's dev scenes: albedo (0.5) × diffuseCoef (1) renders;
//                               specularCoef > 0 warns (no Phong lobe), shininess is ignored
// <bsdf type="microfacet">      the Nori family's: kd (colour in [0, 1], 0.5), alpha (roughness, 0.1),
//                               intIOR (1.5046), extIOR (1.000277)
// <bsdf type="roughconductor">  Mitsuba 3's: distribution (beckmann | ggx, beckmann), alpha (0.1),
//                               specular_reflectance or specularReflectance (colour, 1)
// alpha is in [1e-6, 1000], indices of refraction finite and > 0; a bad value is an error at its line.
// No <bsdf>: diffuse, albedo 0.5. Properties a type does not read warn (e.g. Mitsuba's eta and k).
#pragma once

#include <string>
#include <vector>

#include "core/materials/bsdf.h"
#include "core/scene/scene_desc.h"

namespace penumbra {

Bsdf buildBsdf(const SceneNode* bsdf, std::vector<std::string>& warnings);

// The accepted <bsdf> types, for messages.
const char* bsdfTypesAccepted();

}  // namespace penumbra
