#include "core/analysis/reference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "core/analysis/closed_forms.h"
#include "core/image/image_io.h"
#include "core/integrators/shading_point.h"
#include "core/math/error.h"
#include "core/render/camera.h"
#include "core/render/filter.h"
#include "core/scene/xml_parser.h"

namespace penumbra {

namespace fs = std::filesystem;

IntegratorDesc referenceEstimator(const IntegratorDesc& sceneIntegrator, const Scene& scene) {
  return referenceStrategy(sceneIntegrator, scene.hasGlossySurfaces());
}

namespace {

// The closed form is direct illumination from sphere lights: any strategy of the direct integrator.
bool hasDirectClosedForm(const IntegratorDesc& d) {
  return d.type == IntegratorType::Direct;
}

void fnv(uint64_t& h, const char* data, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= uint8_t(data[i]);
    h *= 1099511628211ull;
  }
}

SceneNode stripEstimator(const SceneNode& node) {
  SceneNode out = node;
  out.children.clear();
  for (const SceneNode& c : node.children) {
    if (c.tag == "sampler") continue;  // sample count, seed, sampler kind: estimator settings
    if (c.tag == "integrator") {
      SceneNode integrator;
      integrator.tag = c.tag;
      integrator.type = c.type;  // ao vs direct changes the quantity; measure/warp/nSamples do not
      integrator.file = c.file;
      integrator.baseDir = c.baseDir;
      out.children.push_back(integrator);
      continue;
    }
    out.children.push_back(stripEstimator(c));
  }
  return out;
}

void hashFiles(uint64_t& h, const SceneNode& node) {
  if (const Property* p = node.props.find({"filename"})) {
    fs::path path = p->stringValue;
    if (path.is_relative() && !node.baseDir.empty()) path = fs::path(node.baseDir) / path;
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fnv(h, bytes.data(), bytes.size());
  }
  for (const SceneNode& c : node.children) hashFiles(h, c);
}

std::string hex16(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)h);
  return buf;
}

}  // namespace

std::string sceneContentHash(const SceneNode& desc) {
  uint64_t h = 1469598103934665603ull;
  std::string xml = writeSceneXml(stripEstimator(desc));
  fnv(h, xml.data(), xml.size());
  hashFiles(h, desc);
  return hex16(h);
}

std::string referenceCachePath(const LoadedScene& scene, const std::string& cacheDir) {
  std::string base = scene.path.empty() ? std::string("builtin-scene.xml") : scene.path;
  std::string name = base + ".ref-" + sceneContentHash(scene.desc) + ".exr";
  if (cacheDir.empty()) return name;
  return (fs::path(cacheDir) / fs::path(name).filename()).string();
}

std::string standardErrorPath(const std::string& referencePath) {
  fs::path p(referencePath);
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".exr" || ext == ".pfm") p.replace_extension();
  return p.string() + ".stderr.exr";
}

Reference renderReference(const LoadedScene& scene, RenderLimits limits, int threads, uint64_t seed,
                          CancelFlag cancel) {
  if (limits.targetSpp == 0 && limits.seconds <= 0) throw Error("renderReference: no spp or time limit");
  RenderSettings settings = scene.settings;
  settings.integrator = referenceEstimator(scene.settings.integrator, *scene.scene);
  settings.seed = seed;
  const auto job = std::make_shared<const RenderJob>(scene.scene, settings, limits);
  Engine engine;
  engine.start(job, limits, threads);
  while (cancel && !engine.progress().finished) {
    if (cancelRequested(cancel)) {
      engine.cancel();
      throw Cancelled();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  engine.wait();
  RenderProgress p = engine.progress();
  Reference ref;
  ref.mean = engine.film().mean(p.spp);
  ref.standardError = engine.film().standardError(p.spp);
  ref.source = "rendered " + strategyLabel(job->settings.integrator) + " " + std::to_string(p.spp) + " spp";
  return ref;
}

void writeReference(const std::string& path, const Reference& ref, const ImageMetadata& metadata,
                    ExrCompression compression) {
  ImageMetadata meta = metadata;
  meta.add("reference", ref.source);
  if (imageFormatFromPath(path) == ImageFormat::Exr)
    writeExr(path, ref.mean, meta, ExrPixelType::Float, compression);
  else
    writeImage(path, ref.mean, meta);
  if (!ref.standardError.empty())
    writeExr(standardErrorPath(path), ref.standardError, meta, ExrPixelType::Float, compression);
}

Reference readReference(const std::string& path) {
  Reference ref;
  ImageMetadata meta;
  bool exr = imageFormatFromPath(path) == ImageFormat::Exr;
  ref.mean = exr ? readExr(path, &meta) : readImage(path);
  std::string se = standardErrorPath(path);
  if (fs::exists(se)) {
    ref.standardError = readImage(se);
    if (ref.standardError.width != ref.mean.width || ref.standardError.height != ref.mean.height)
      throw Error(se + ": standard error image does not match " + path);
  }
  ref.source = "file " + path;
  if (const std::string* how = meta.find("reference")) ref.source += " (" + *how + ")";
  checkReferenceValues(ref, "reference " + path);
  return ref;
}

namespace {

// Throws when a value of `image` fails `valid`: the count and the first one (in row-major order).
template <class Valid>
void checkValues(const Image& image, const std::string& what, const char* expected, Valid valid) {
  std::size_t bad = 0, first = 0;
  for (std::size_t i = 0; i < image.rgb.size(); ++i)
    if (!valid(image.rgb[i]) && bad++ == 0) first = i;
  if (bad == 0) return;
  const std::size_t pixel = first / 3;
  char value[32];
  std::snprintf(value, sizeof value, "%g", double(image.rgb[first]));
  throw Error(what + ": " + std::to_string(bad) + " of " + std::to_string(image.rgb.size()) +
              (bad == 1 ? " values is not " : " values are not ") + expected + "; the first at pixel (" +
              std::to_string(pixel % std::size_t(image.width)) + ", " +
              std::to_string(pixel / std::size_t(image.width)) + ") channel " + "RGB"[first % 3] + ": " +
              value);
}

}  // namespace

void checkReferenceValues(const Reference& ref, const std::string& what) {
  checkValues(ref.mean, what, "finite", [](float v) { return std::isfinite(v); });
  checkValues(ref.standardError, what + " (standard error)", "finite and non-negative",
              [](float v) { return std::isfinite(v) && v >= 0.f; });
}

bool hasClosedFormReference(const LoadedScene& scene) {
  if (scene.path.empty()) return false;
  fs::path dir = fs::path(scene.path).parent_path();
  if (dir.filename() != "analytic" || !hasDirectClosedForm(scene.settings.integrator)) return false;
  for (const SurfaceMaterial& m : scene.scene->materials)
    if (!m.bsdf.isDiffuse()) return false;
  return true;
}

Reference closedFormReference(const LoadedScene& loaded, int grid, CancelFlag cancel) {
  if (!hasDirectClosedForm(loaded.settings.integrator))
    throw Error("closed-form reference: only the direct integrator is supported");
  const Scene& scene = *loaded.scene;
  if (scene.hasDeltaLights()) throw Error("closed-form reference: the scene has point or directional lights");
  for (const SurfaceMaterial& m : scene.materials)
    if (!m.bsdf.isDiffuse())
      throw Error(
          "closed-form reference: the scene has a glossy surface (the closed forms are for diffuse ones)");
  PerspectiveCamera camera(loaded.settings.camera);
  FilterSampler filter(loaded.settings.filter);
  Reference ref;
  ref.mean = Image(camera.width(), camera.height());
  ref.source = "closed-form";
  const double invN = 1.0 / (double(grid) * grid);
  for (int y = 0; y < camera.height(); ++y)
    for (int x = 0; x < camera.width(); ++x) {
      throwIfCancelled(cancel);
      glm::dvec3 sum(0.0);
      for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
          float weight;
          Vec2 u((float(i) + 0.5f) / float(grid), (float(j) + 0.5f) / float(grid));
          Vec2 offset = filter.sample(u, weight);
          Ray ray = camera.generateRay(Vec2(float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y));
          SurfaceHit hit;
          if (!scene.geometry.intersect(ray, hit)) continue;
          const SurfaceMaterial& m = scene.materials[hit.objectId];
          glm::dvec3 L(0.0);
          L += glm::dvec3(emittedAt(scene, m, hit, ray));
          if (m.bsdf.reflects()) {
            ShadingPoint sp(scene, ray, hit);
            glm::dvec3 E(0.0);
            for (std::size_t k = 0; k < scene.sphereLights.size(); ++k) {
              if (int32_t(k) == m.sphereLight) continue;
              const SphereLight& light = scene.sphereLights[k];
              double I = sphereLightIrradianceFactor(glm::dvec3(sp.hit.p), glm::dvec3(sp.ns),
                                                     glm::dvec3(light.sphere.center), light.sphere.radius);
              E += glm::dvec3(light.radiance) * I;
            }
            for (const PolygonLight& light : scene.polygonLights)
              E += glm::dvec3(light.radiance) *
                   polygonLightIrradianceFactor(light, glm::dvec3(sp.hit.p), glm::dvec3(sp.ns));
            L += glm::dvec3(m.bsdf.albedo) * (1.0 / kPiD) * E;
          }
          sum += L * double(weight);
        }
      ref.mean.set(x, y, Color3(sum * invN));
    }
  return ref;
}

std::vector<uint8_t> emitterMask(const LoadedScene& loaded, CancelFlag cancel) {
  const Scene& scene = *loaded.scene;
  PerspectiveCamera camera(loaded.settings.camera);
  const int w = camera.width(), h = camera.height();
  std::vector<uint8_t> direct(std::size_t(w) * h, 0);
  for (int y = 0; y < h && !cancelRequested(cancel); ++y)
    for (int x = 0; x < w; ++x)
      for (int j = 0; j < 3 && !direct[std::size_t(y) * w + x]; ++j)
        for (int i = 0; i < 3; ++i) {
          Ray ray = camera.generateRay(
              Vec2(float(x) + (float(i) + 0.5f) / 3.f, float(y) + (float(j) + 0.5f) / 3.f));
          SurfaceHit hit;
          if (scene.geometry.intersect(ray, hit) && scene.materials[hit.objectId].emits()) {
            direct[std::size_t(y) * w + x] = 1;
            break;
          }
        }
  throwIfCancelled(cancel);
  int r = int(std::ceil(loaded.settings.filter.radius));
  std::vector<uint8_t> mask(direct.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!direct[std::size_t(y) * w + x]) continue;
      for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx)
          mask[std::size_t(yy) * w + xx] = 1;
    }
  return mask;
}

Reference obtainReference(const LoadedScene& scene, const ReferenceRequest& request,
                          void (*log)(const std::string&)) {
  auto say = [&](const std::string& s) {
    if (log) log(s);
  };
  const auto& cam = scene.settings.camera;
  auto checkSize = [&](const Reference& ref, const std::string& what) {
    if (ref.mean.width != cam.width || ref.mean.height != cam.height)
      throw Error(what + " is " + std::to_string(ref.mean.width) + "x" + std::to_string(ref.mean.height) +
                  " but the scene renders " + std::to_string(cam.width) + "x" + std::to_string(cam.height));
  };
  if (request.path == "closed-form" || (request.path.empty() && hasClosedFormReference(scene))) {
    say("reference: closed form");
    return closedFormReference(scene, 16, request.cancel);
  }
  if (!request.path.empty()) {
    Reference ref = readReference(request.path);
    checkSize(ref, "reference " + request.path);
    say("reference: " + request.path +
        (ref.standardError.empty() ? " (no standard error)" : " (with standard error)"));
    return ref;
  }
  std::string cache = referenceCachePath(scene, request.cacheDir);
  if (fs::exists(cache)) {
    Reference ref = readReference(cache);
    checkSize(ref, "cached reference " + cache);
    ref.source = "cache " + ref.source.substr(5);  // "file PATH (how)" -> "cache PATH (how)"
    say("reference: cached " + cache);
    return ref;
  }
  if (!request.renderIfMissing) throw Error("no reference for this scene (expected " + cache + ")");
  // Make the cache's directory before minutes of rendering, so a missing one loses no work.
  const fs::path cacheDir = fs::path(cache).parent_path();
  std::error_code ec;
  if (!cacheDir.empty()) fs::create_directories(cacheDir, ec);
  if (ec) throw Error(cache + ": cannot create the reference cache's directory: " + ec.message());
  say("reference: rendering " + std::to_string(request.referenceSpp) + " spp of " +
      strategyLabel(referenceEstimator(scene.settings.integrator, *scene.scene)) + " into " + cache);
  Reference ref = renderReference(scene, RenderLimits{request.referenceSpp, request.referenceSeconds},
                                  request.threads, kReferenceSeed, request.cancel);
  ImageMetadata meta;
  meta.add("sceneHash", sceneContentHash(scene.desc));
  writeReference(cache, ref, meta);
  return ref;
}

}  // namespace penumbra
