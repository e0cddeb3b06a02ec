#include "core/render/packet_scene.h"

#include "core/integrators/sampling_loops.h"
#include "core/math/vec.h"
#include "core/render/strategy_axes.h"

namespace penumbra {

namespace {

// The kernel of the job's strategy, or false when no kernel computes it.
bool kernelOf(const IntegratorDesc& d, PacketKernel& kernel) {
  const bool cosine = d.warp == HemisphereWarp::Cosine;
  if (d.type == IntegratorType::Ao) {
    kernel = cosine ? PacketKernel::AoCosine : PacketKernel::AoUniform;
    return true;
  }
  if (d.type == IntegratorType::Simple) {
    kernel = PacketKernel::Simple;
    return true;
  }
  if (d.type == IntegratorType::Normals) {
    kernel = PacketKernel::Normals;
    return true;
  }
  if (d.type != IntegratorType::Direct) return false;
  switch (d.estimator) {
    case Estimator::Hemisphere:
      kernel = cosine ? PacketKernel::HemisphereCosine : PacketKernel::HemisphereUniform;
      return true;
    case Estimator::Bsdf:
      kernel = PacketKernel::Bsdf;
      return true;
    case Estimator::Light: {
      const bool all = d.lightSelection == LightSelection::All;
      if (d.lightMeasure == LightMeasure::Area)
        kernel = all ? PacketKernel::LightArea : PacketKernel::LightAreaSelected;
      else if (d.lightMeasure == LightMeasure::SolidAngle)
        kernel = all ? PacketKernel::LightSolidAngle : PacketKernel::LightSolidAngleSelected;
      else
        kernel =
            all ? PacketKernel::LightProjectedSolidAngle : PacketKernel::LightProjectedSolidAngleSelected;
      return true;
    }
    case Estimator::Mis: {
      const bool balance = d.heuristic == MisHeuristic::Balance;
      if (d.lightMeasure == LightMeasure::Area)
        kernel = balance ? PacketKernel::MisAreaBalance : PacketKernel::MisAreaPower;
      else if (d.lightMeasure == LightMeasure::SolidAngle)
        kernel = balance ? PacketKernel::MisSolidAngleBalance : PacketKernel::MisSolidAnglePower;
      else
        kernel =
            balance ? PacketKernel::MisProjectedSolidAngleBalance : PacketKernel::MisProjectedSolidAnglePower;
      return true;
    }
  }
  return false;
}

// No polygon light, or two different ones.
constexpr int32_t kNoPolygonLight = -1, kTwoPolygonLights = -2;

// The polygon light a flat parallelogram's two triangles both are (Scene::polygonLightOf), or one of the
// two codes above.
int32_t quadPolygonLight(const Scene& scene, const Parallelogram& q) {
  const SurfaceMaterial& material = scene.materials[scene.geometry.meshObjectId(q.mesh)];
  if (material.polygonLightsAt < 0) return kNoPolygonLight;
  const size_t at = size_t(material.polygonLightsAt);
  const int32_t low = scene.polygonLightOfPrim[at + q.primLow],
                high = scene.polygonLightOfPrim[at + q.primHigh];
  return low == high ? low : kTwoPolygonLights;
}

}  // namespace

bool packetGeometryQueried(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  if (g.usesEmbree() || g.spheresUseBvh() || g.flatTriangleCount() != 0) return true;
  // Every triangle is in a flat parallelogram: the flat loops see a polygon light's emission when the
  // parallelogram is that light whole.
  for (const Parallelogram& q : g.parallelograms())
    if (quadPolygonLight(scene, q) == kTwoPolygonLights) return true;
  return false;
}

int PacketScene::drawCount() const {
  return penumbra::drawCount(draws);
}

namespace {

// The integrator's sampler requests after the filter's: per light for light sampling of every light,
// the pick's and the light's interleaved for one light per sample, the lights' then the surface's for
// MIS, one request otherwise.
std::vector<DrawRequests> drawRequestsOf(const IntegratorDesc& d, int lights) {
  if (d.type == IntegratorType::Simple || d.type == IntegratorType::Normals) return {};
  if (d.type == IntegratorType::Direct && d.estimator == Estimator::Light)
    return d.lightSelection == LightSelection::All ? std::vector<DrawRequests>{{lights, d.samples}}
                                                   : std::vector<DrawRequests>{{1, d.samples, 2}};
  if (d.type == IntegratorType::Direct && d.estimator == Estimator::Mis)
    return {{lights, d.lightSamples}, {1, d.bsdfSamples}};
  return {{1, d.samples}};
}

}  // namespace

int drawCount(const std::vector<DrawRequests>& requests) {
  int draws = 0;
  for (const DrawRequests& r : requests) draws += std::max(r.repeats, 0) * std::max(r.n, 0) * r.parts;
  return draws;
}

std::string packetUnsupportedReason(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  PacketKernel kernel;
  if (!kernelOf(d, kernel)) return "no packet kernel for " + strategyLabel(d);
  const Scene& scene = *job.scene;
  if (drawCount(drawRequestsOf(d, int(scene.areaLightCount()))) > kMaxPacketDraws)
    return "more shading samples per camera sample than a packet carries (" +
           std::to_string(kMaxPacketDraws) + ")";
  return {};
}

namespace {

PacketLightBvh packetLightBvh(const LightBvh& bvh) {
  PacketLightBvh b;
  for (const LightBvhNode& node : bvh.nodes) {
    const DVec3 lo(node.lo), hi(node.hi);
    const DVec3 c = 0.5 * (lo + hi);
    b.centreX.push_back(c.x);
    b.centreY.push_back(c.y);
    b.centreZ.push_back(c.z);
    b.radius2.push_back(0.25 * glm::dot(hi - lo, hi - lo));
    b.power.push_back(node.power);
    b.axisX.push_back(node.coneAxis.x);
    b.axisY.push_back(node.coneAxis.y);
    b.axisZ.push_back(node.coneAxis.z);
    b.cosCone.push_back(node.cosConeAngle);
    b.child.push_back(node.child);
    b.leaf.push_back(node.leaf ? 1.0 : 0.0);
  }
  return b;
}

}  // namespace

PacketLightTable packetLightTable(const UniformLightSelection& selection) {
  const uint32_t n = selection.count;
  PacketLightTable t;
  t.keep.assign(n, 1.0);
  t.pmf.assign(n, 1.0 / double(n));
  for (uint32_t i = 0; i < n; ++i) t.alias.push_back(double(i));
  return t;
}

PacketLightTable packetLightTable(const PowerLightSelection& selection) {
  PacketLightTable t;
  for (const AliasTable::Bin& bin : selection.table.bins) {
    t.keep.push_back(bin.keep);
    t.alias.push_back(double(bin.alias));
    t.pmf.push_back(bin.pmf);
  }
  return t;
}

PacketScene makePacketScene(const RenderJob& job) {
  const Scene& scene = *job.scene;
  const SceneGeometry& g = scene.geometry;
  PacketScene p;
  kernelOf(job.settings.integrator, p.kernel);
  p.scene = &scene;
  p.geometryQueried = packetGeometryQueried(scene);
  p.selection = job.settings.integrator.lightSelection;
  if (p.selection == LightSelection::Bvh) p.lightBvh = packetLightBvh(scene.lightBvh);
  if (p.selection == LightSelection::Uniform) p.lightTable = packetLightTable(scene.uniformSelection);
  if (p.selection == LightSelection::Power) p.lightTable = packetLightTable(scene.powerSelection);
  p.samples = job.settings.integrator.samples;
  p.lightSamples = job.settings.integrator.lightSamples;
  p.bsdfSamples = job.settings.integrator.bsdfSamples;
  p.draws = drawRequestsOf(job.settings.integrator, int(scene.areaLightCount()));
  p.rayLengthBound = scene.rayLengthBound;
  // A light-share job of a strategy without that output renders radiance, as the scalar loop does.
  p.lightShare = job.output == RenderOutput::MisLightShare && offersLightShare(job.settings.integrator);
  for (size_t i = 0; i < g.spheres().size() && !p.geometryQueried; ++i) {
    const Sphere& s = g.spheres()[i];
    p.spheres.push_back({{s.center.x, s.center.y, s.center.z},
                         s.radius,
                         maxAbsComponent(s.center) + s.radius,
                         g.sphereObjectId(i)});
  }
  if (!p.geometryQueried)
    for (const Parallelogram& q : g.parallelograms())
      p.quads.push_back({q, g.meshObjectId(q.mesh), quadPolygonLight(scene, q)});
  for (const SurfaceMaterial& m : scene.materials) {
    PacketObject o{};
    const Color3 a = m.bsdf.albedo * kInvPi;
    o.albedoOverPi[0] = a.x, o.albedoOverPi[1] = a.y, o.albedoOverPi[2] = a.z;
    o.glossy = !m.bsdf.isDiffuse();
    o.emitter = m.emits();
    o.shades = o.glossy ? m.bsdf.reflects() : !isBlack(m.bsdf.albedo);  // directRadiance's two tests
    p.anyGlossy = p.anyGlossy || o.glossy;
    o.emits = m.sphereLight >= 0;
    o.light = m.sphereLight;
    if (o.emits) {
      const Color3& Le = scene.sphereLights[m.sphereLight].radiance;
      o.radiance[0] = Le.x, o.radiance[1] = Le.y, o.radiance[2] = Le.z;
      o.radianceNonBlack = !isBlack(Le);
    }
    p.objects.push_back(o);
  }
  for (const PointLight& l : scene.pointLights)
    p.pointLights.push_back({{l.position.x, l.position.y, l.position.z},
                             {l.intensity.x, l.intensity.y, l.intensity.z},
                             maxAbsComponent(l.position)});
  for (const DirectionalLight& l : scene.directionalLights)
    p.directionalLights.push_back({{l.direction.x, l.direction.y, l.direction.z},
                                   {l.irradiance.x, l.irradiance.y, l.irradiance.z},
                                   isBlack(l.irradiance)});
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
  for (const PolygonLight& l : scene.polygonLights) p.polygons.push_back(packetPolygonLight(l));
  return p;
}

PacketPolygonLight packetPolygonLight(const PolygonLight& l) {
  PacketPolygonLight pl{};
  for (int c = 0; c < 3; ++c) {
    pl.p0[c] = l.p0[c], pl.e1[c] = l.e1[c], pl.e2[c] = l.e2[c], pl.n[c] = l.n[c];
    pl.radiance[c] = l.radiance[c];
  }
  pl.area = l.area;
  pl.scale = lightScaleOf(l);
  pl.parallelogram = l.parallelogram;
  pl.skipped = isBlack(l.radiance) || !l.valid();
  return pl;
}

}  // namespace penumbra
