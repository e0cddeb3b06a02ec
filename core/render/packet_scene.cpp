#include "core/render/packet_scene.h"

#include "core/integrators/sampling_loops.h"
#include "core/math/vec.h"

namespace penumbra {

std::string packetUnsupportedReason(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  if (job.output != RenderOutput::Radiance) return "the job renders an output other than radiance";
  if (d.type != IntegratorType::Direct || d.estimator != Estimator::Light)
    return "the strategy is not light sampling";
  if (d.lightSelection != LightSelection::All) return "the light selection is not `all`";
  if (d.lightMeasure != LightMeasure::Area && d.lightMeasure != LightMeasure::SolidAngle)
    return "the light measure is not area or solid angle";
  const Scene& scene = *job.scene;
  const SceneGeometry& g = scene.geometry;
  if (g.usesEmbree() || g.spheresUseBvh()) return "the scene's geometry is in a BVH";
  if (g.flatTriangleCount() != 0) return "the scene has triangles outside parallelograms";
  if (scene.hasDeltaLights()) return "the scene has point or directional lights";
  if (!scene.polygonLights.empty()) return "the scene has polygon lights";
  for (const SurfaceMaterial& m : scene.materials)
    if (!m.bsdf.isDiffuse()) return "the scene has a glossy material";
  if (scene.sphereLights.size() * size_t(std::max(d.samples, 1)) > size_t(kMaxPacketDraws))
    return "the scene has more light draws per camera sample than a packet carries";
  return {};
}

PacketScene makePacketScene(const RenderJob& job) {
  const Scene& scene = *job.scene;
  const SceneGeometry& g = scene.geometry;
  PacketScene p;
  p.lightSamples = job.settings.integrator.samples;
  p.measure = job.settings.integrator.lightMeasure;
  for (size_t i = 0; i < g.spheres().size(); ++i) {
    const Sphere& s = g.spheres()[i];
    p.spheres.push_back({{s.center.x, s.center.y, s.center.z},
                         s.radius,
                         maxAbsComponent(s.center) + s.radius,
                         g.sphereObjectId(i)});
  }
  for (const Parallelogram& q : g.parallelograms()) p.quads.push_back({q, g.meshObjectId(q.mesh)});
  for (const SurfaceMaterial& m : scene.materials) {
    PacketObject o{};
    const Color3 a = m.bsdf.albedo * kInvPi;
    o.albedoOverPi[0] = a.x, o.albedoOverPi[1] = a.y, o.albedoOverPi[2] = a.z;
    o.shades = !isBlack(m.bsdf.albedo);
    o.emits = m.sphereLight >= 0;
    if (o.emits) {
      const Color3& Le = scene.sphereLights[m.sphereLight].radiance;
      o.radiance[0] = Le.x, o.radiance[1] = Le.y, o.radiance[2] = Le.z;
    }
    p.objects.push_back(o);
  }
  for (const SphereLight& l : scene.sphereLights) {
    PacketLight pl{};
    pl.center[0] = l.sphere.center.x, pl.center[1] = l.sphere.center.y, pl.center[2] = l.sphere.center.z;
    pl.radius = l.sphere.radius;
    pl.scale = lightScaleOf(l);
    pl.radiance[0] = l.radiance.x, pl.radiance[1] = l.radiance.y, pl.radiance[2] = l.radiance.z;
    pl.black = isBlack(l.radiance);
    pl.geometrySphere = l.geometryIndex;
    p.lights.push_back(pl);
  }
  return p;
}

}  // namespace penumbra
