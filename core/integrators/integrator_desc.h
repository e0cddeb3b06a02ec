// Which estimator renders the image: an integrator type and one value per sampling axis. Plain
// data: the viewer edits each axis live and the row renderer resolves the description to one
// concrete integrator type per render (no per-sample dispatch). Each axis's spellings, labels and
// help live in its own table (core/render/strategy_axes.h).
#pragma once

#include <cstdint>

namespace penumbra {

enum class IntegratorType : uint8_t {
  Direct,   // direct illumination from every emitter
  Ao,       // ambient occlusion
  Simple,   // point and directional lights only
  Normals,  // the shading normal as a colour
};

// How `direct` estimates the area-light integral ∫ Le f cos θ dω.
enum class Estimator : uint8_t {
  Hemisphere,  // hemisphere directions (by `warp`), traced to the lights they hit
  Bsdf,        // the surface's own directions (its BSDF's sampling), traced to the lights they hit
  Light,       // directions towards the lights, by `lightMeasure`, one or all lights per sample
  Mis,         // multiple importance sampling of `lightMeasure` and BSDF-sampled directions
};

// The distribution of hemisphere directions (`ao`, and `direct` by Hemisphere).
enum class HemisphereWarp : uint8_t { Uniform, Cosine };

// How light sampling measures its directions: uniform on the light's area, uniform in the solid
// angle it subtends, or in proportion to cos θ over that solid angle (projected solid angle).
enum class LightMeasure : uint8_t { Area, SolidAngle, ProjectedSolidAngle };

// Which lights one light-sampling draw samples: every light (All), or one light chosen per shading
// sample (core/lights/light_selection.h). MIS always samples every light
// (core/integrators/mis_integrator.h says why).
enum class LightSelection : uint8_t { All, Uniform, Power, Bvh };

// The MIS weight of the two techniques (core/integrators/mis_weight.h).
enum class MisHeuristic : uint8_t { Balance, Power };

struct IntegratorDesc {
  IntegratorType type = IntegratorType::Direct;
  Estimator estimator = Estimator::Light;                // direct
  HemisphereWarp warp = HemisphereWarp::Cosine;          // ao; direct by Hemisphere
  LightMeasure lightMeasure = LightMeasure::SolidAngle;  // direct by Light or Mis
  LightSelection lightSelection = LightSelection::All;   // direct by Light
  MisHeuristic heuristic = MisHeuristic::Power;          // direct by Mis
  int samples = 1;  // shading samples per camera sample (ao: shadingSamples, direct: nSamples)
  // MIS counts per camera sample: light-sampling directions per area light, and BSDF-sampled
  // directions shared by all lights (0 turns MIS into the other technique alone).
  int lightSamples = 1;
  int bsdfSamples = 1;

  // Which axes this description reads: an axis that does not apply keeps its value (the viewer
  // returns to it) but neither renders nor compares.
  constexpr bool usesEstimator() const { return type == IntegratorType::Direct; }
  constexpr bool usesWarp() const {
    return type == IntegratorType::Ao || (usesEstimator() && estimator == Estimator::Hemisphere);
  }
  constexpr bool usesLightMeasure() const { return usesEstimator() && estimator != Estimator::Hemisphere; }
  constexpr bool usesLightSelection() const { return usesEstimator() && estimator == Estimator::Light; }
  constexpr bool usesMisAxes() const { return usesEstimator() && estimator == Estimator::Mis; }
  constexpr bool usesSamples() const { return type == IntegratorType::Direct || type == IntegratorType::Ao; }

  // Equal when they render the same estimator: the axes that apply, and the counts.
  constexpr bool operator==(const IntegratorDesc& o) const {
    return type == o.type && (!usesEstimator() || estimator == o.estimator) &&
           (!usesWarp() || warp == o.warp) && (!usesLightMeasure() || lightMeasure == o.lightMeasure) &&
           (!usesLightSelection() || lightSelection == o.lightSelection) &&
           (!usesMisAxes() ||
            (heuristic == o.heuristic && lightSamples == o.lightSamples && bsdfSamples == o.bsdfSamples)) &&
           (!usesSamples() || samples == o.samples);
  }
};

// Descriptions by their axes, with counts 1 (tests, the stiff-case catalogue, bench).
constexpr IntegratorDesc directByHemisphere(HemisphereWarp warp) {
  IntegratorDesc d;
  d.estimator = Estimator::Hemisphere;
  d.warp = warp;
  return d;
}
constexpr IntegratorDesc directByBsdf() {
  IntegratorDesc d;
  d.estimator = Estimator::Bsdf;
  return d;
}
constexpr IntegratorDesc directByLight(LightMeasure measure, LightSelection selection = LightSelection::All) {
  IntegratorDesc d;
  d.lightMeasure = measure;
  d.lightSelection = selection;
  return d;
}
constexpr IntegratorDesc directByMis(LightMeasure measure, MisHeuristic heuristic) {
  IntegratorDesc d;
  d.estimator = Estimator::Mis;
  d.lightMeasure = measure;
  d.heuristic = heuristic;
  return d;
}
constexpr IntegratorDesc aoBy(HemisphereWarp warp) {
  IntegratorDesc d;
  d.type = IntegratorType::Ao;
  d.warp = warp;
  return d;
}
constexpr IntegratorDesc integratorOfType(IntegratorType type) {
  IntegratorDesc d;
  d.type = type;
  return d;
}
// `axes` with `samples` shading samples per camera sample.
constexpr IntegratorDesc withSamples(IntegratorDesc axes, int samples) {
  axes.samples = samples;
  return axes;
}
// The type and axes of `axes` with the counts of `counts`.
constexpr IntegratorDesc withCountsOf(IntegratorDesc axes, const IntegratorDesc& counts) {
  axes.samples = counts.samples;
  axes.lightSamples = counts.lightSamples;
  axes.bsdfSamples = counts.bsdfSamples;
  return axes;
}

}  // namespace penumbra
