// References for error measurement: the image an estimate is compared with.
//
//  (a) rendered: many spp of the lowest-variance estimator available for the scene's integrator
//      (direct: solid-angle light sampling; ao: cosine-weighted hemisphere), kept with its per-pixel
//      standard error so that the metrics can subtract the reference's own noise. Cached next to the
//      scene as  <scene.xml>.ref-<hash>.exr  (mean, float RGB) and  <scene.xml>.ref-<hash>.stderr.exr
//      (standard error of the mean, float RGB), where <hash> is sceneContentHash(): the scene's
//      content minus the estimator settings.
//  (b) user-given: any EXR or PFM of the right size (no standard error unless a sibling
//      <name>.stderr.exr exists).
//  (c) closed form, for the analytic scenes in scenes/analytic/: every pixel's filtered value is
//      computed by tracing camera rays at a 16x16 stratified grid of filter samples (the same
//      FilterSampler the renderer uses) and evaluating, at each hit point, the closed form of
//      closed_forms.h: albedo/pi * sum over area lights of Le * (sphere I(θ, α), polygon Ω⊥). Exact only
//      when nothing occludes the lights (true for the shipped scenes); emitters seen directly
//      contribute their radiance. Quadrature error of the 256-point average is < 1e-5 relative
//      for the shipped scenes (smooth irradiance, ~30 px per unit).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image/image.h"
#include "core/image/image_io.h"
#include "core/integrators/integrator_desc.h"
#include "core/math/cancellation.h"
#include "core/render/engine.h"
#include "core/scene/scene_builder.h"

namespace penumbra {

struct Reference {
  Image mean;
  Image standardError;  // empty when exact (closed form) or unknown (user file without a sibling)
  std::string source;   // "closed-form", "cache <path>", "rendered <label> <spp> spp", "file <path>"
};

// The estimator a rendered reference of `scene` uses: the lowest-variance one for the scene's
// integrator type and surfaces (referenceStrategy).
IntegratorDesc referenceEstimator(const IntegratorDesc& sceneIntegrator, const Scene& scene);

// 16 hex digits: FNV-1a over writeSceneXml of the description with the sampler removed and the
// integrator reduced to its type, followed by the bytes of every file a "filename" property names.
std::string sceneContentHash(const SceneNode& desc);
// <scene path>.ref-<hash>.exr, or <cacheDir>/<scene file name>.ref-<hash>.exr when cacheDir is set.
std::string referenceCachePath(const LoadedScene& scene, const std::string& cacheDir = "");
// <path without .exr/.pfm>.stderr.exr
std::string standardErrorPath(const std::string& referencePath);

// Seed of rendered references. It must differ from the seeds of the runs measured against the
// reference: with the same seed, the reference estimator's run would repeat the reference's own
// samples and its error would be grossly underestimated. Scenes and `converge` default to small seeds.
inline constexpr uint64_t kReferenceSeed = 0x5EEDF00D12345678ull;

// (a) Renders a reference (limits as in Engine::start; at least one of them must be set). Throws
// Cancelled once `cancel` is set.
Reference renderReference(const LoadedScene& scene, RenderLimits limits, int threads = 0,
                          uint64_t seed = kReferenceSeed, CancelFlag cancel = nullptr);
// Writes the mean to `path` and the standard error (if any) to standardErrorPath(path), both atomically,
// the mean first; `compression` applies to every EXR written.
void writeReference(const std::string& path, const Reference& ref, const ImageMetadata& metadata = {},
                    ExrCompression compression = ExrCompression::Zip);
// (b) Reads a reference image and, if present, its sibling standard error, and checks their values
// (checkReferenceValues). Throws Error.
Reference readReference(const std::string& path);

// What an image measured against must hold: a finite mean (negative values are allowed: a pixel filter
// with negative lobes, mitchell, makes them) and a finite, non-negative standard error. Throws Error
// naming `what`, how many values break that, and the first of them (pixel x, y, channel and value).
void checkReferenceValues(const Reference& ref, const std::string& what);

// (c) True for scenes under a directory named "analytic" (the closed form is valid there).
bool hasClosedFormReference(const LoadedScene& scene);
// Throws Error for integrators other than direct (the AO closed forms are not wired up), Cancelled
// once `cancel` is set (checked per pixel).
Reference closedFormReference(const LoadedScene& scene, int grid = 16, CancelFlag cancel = nullptr);

// Nonzero for pixels whose estimate can contain radiance of an emitter seen directly by the camera:
// 3x3 camera rays per pixel find the pixels that see an emitter, then the mask is dilated by the
// pixel filter's radius (rounded up), because a pixel's samples land anywhere within that radius.
// Throws Cancelled once `cancel` is set (checked per row).
std::vector<uint8_t> emitterMask(const LoadedScene& scene, CancelFlag cancel = nullptr);

// How `penumbra converge` and the viewer find a reference: an explicit path ("closed-form" forces
// (c)); else the closed form for analytic scenes; else the cache; else render one (referenceSpp
// samples of the reference estimator) and store it in the cache. `log` receives one-line messages.
struct ReferenceRequest {
  std::string path;      // user file or "closed-form"; empty: automatic
  std::string cacheDir;  // empty: next to the scene
  uint32_t referenceSpp = 4096;
  double referenceSeconds = 0;  // if > 0, caps the time spent rendering a missing reference
  bool renderIfMissing = true;
  int threads = 0;
  CancelFlag cancel = nullptr;  // set: throws Cancelled (and writes no cache) within a fraction of a second
};
Reference obtainReference(const LoadedScene& scene, const ReferenceRequest& request,
                          void (*log)(const std::string&) = nullptr);

}  // namespace penumbra
