#include "core/scene/scaling_scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/sampling/rng.h"

namespace penumbra {

std::vector<ScalingSphere> scalingSceneSpheres(int lightCount, uint64_t seed) {
  std::vector<ScalingSphere> out;
  if (lightCount <= 0) return out;
  const int cols = static_cast<int>(std::ceil(std::sqrt(double(lightCount))));
  const int rows = (lightCount + cols - 1) / cols;
  const float cellX = 20.f / float(cols), cellZ = 20.f / float(rows);
  const float cell = std::min(cellX, cellZ);
  Rng rng(seed, 0x5ca11e5ULL);
  out.reserve(2 * size_t(lightCount));
  for (int i = 0; i < lightCount; ++i) {
    const float x0 = -10.f + cellX * float(i % cols), z0 = -10.f + cellZ * float(i / cols);
    ScalingSphere light;
    light.sphere.radius = std::min(0.15f * cell, 0.5f);
    light.sphere.center = Vec3(x0 + cellX * (0.2f + 0.6f * rng.nextFloat()), 2.f + 2.f * rng.nextFloat(),
                               z0 + cellZ * (0.2f + 0.6f * rng.nextFloat()));
    // Power varies over about 20x between lights, with a tint; the total stays roughly constant in n.
    const float level = 2.f * std::pow(20.f, rng.nextFloat());
    light.radiance = level * Color3(1.f, 0.6f + 0.4f * rng.nextFloat(), 0.6f + 0.4f * rng.nextFloat());
    out.push_back(light);
    ScalingSphere blocker;
    blocker.sphere.radius = std::min(0.25f * cell, 0.3f);
    blocker.sphere.center = Vec3(x0 + cellX * (0.25f + 0.5f * rng.nextFloat()), 0.4f + 0.8f * rng.nextFloat(),
                                 z0 + cellZ * (0.25f + 0.5f * rng.nextFloat()));
    out.push_back(blocker);
  }
  return out;
}

std::string scalingSceneXml(int lightCount, int resolution, int samplesPerPixel, uint64_t seed) {
  std::ostringstream xml;
  xml.precision(9);
  xml << "<scene>\n"
      << "  <sampler type=\"independent\"><integer name=\"sampleCount\" value=\"" << samplesPerPixel
      << "\"/></sampler>\n"
      << "  <integrator type=\"direct\"><string name=\"measure\" value=\"solid-angle\"/></integrator>\n"
      << "  <camera type=\"perspective\">\n"
      << "    <transform name=\"toWorld\"><lookat target=\"0,0,-1\" origin=\"0,16,17\" "
         "up=\"0,1,0\"/></transform>\n"
      << "    <float name=\"fov\" value=\"50\"/>\n"
      << "    <integer name=\"width\" value=\"" << resolution << "\"/>\n"
      << "    <integer name=\"height\" value=\"" << resolution << "\"/>\n"
      << "  </camera>\n"
      << "  <shape type=\"plane\"><bsdf type=\"diffuse\"/>"
      << "<transform name=\"toWorld\"><scale value=\"10,1,10\"/></transform></shape>\n";
  for (const ScalingSphere& s : scalingSceneSpheres(lightCount, seed)) {
    const Vec3& c = s.sphere.center;
    xml << "  <shape type=\"sphere\"><point name=\"center\" value=\"" << c.x << "," << c.y << "," << c.z
        << "\"/><float name=\"radius\" value=\"" << s.sphere.radius << "\"/>";
    if (s.radiance.x > 0.f)
      xml << "<emitter type=\"area\"><color name=\"radiance\" value=\"" << s.radiance.x << "," << s.radiance.y
          << "," << s.radiance.z << "\"/></emitter>";
    else
      xml << "<bsdf type=\"diffuse\"/>";
    xml << "</shape>\n";
  }
  xml << "</scene>\n";
  return xml.str();
}

}  // namespace penumbra
