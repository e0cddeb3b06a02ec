// Uniform solid-angle sampling of a polygon light seen from a point: a triangle by its spherical
// triangle (Arvo), a parallelogram by its spherical rectangle (Ureña et al.; a sheared one as two
// spherical triangles), each falling back to area sampling where its solid angle is too small for
// the map (the thresholds and their measurements are in spherical_triangle.h, spherical_rectangle.h).
#pragma once

#include "core/lights/polygon_light.h"
#include "core/lights/spherical_rectangle.h"
#include "core/lights/spherical_triangle.h"

namespace penumbra {

class PolygonSolidAngle {
 public:
  // False when x does not face the light or the polygon subtends no solid angle there.
  bool init(const PolygonLight& light, const Vec3& x) {
    parallelogram_ = light.parallelogram;
    if (!light.valid() || !light.faces(x)) return false;
    return parallelogram_ ? rectangle_.init(light.p0, light.e1, light.e2, x)
                          : triangle_.init(light.p0, light.p0 + light.e1, light.p0 + light.e2, x);
  }
  DVec3 sampleDirection(Vec2 u) const {
    return parallelogram_ ? rectangle_.sampleDirection(u) : triangle_.sampleDirection(u);
  }
  // Solid-angle density of sampleDirection at unit w (0 where w misses the polygon).
  double pdfDirection(const DVec3& w) const {
    return parallelogram_ ? rectangle_.pdfDirection(w) : triangle_.pdfDirection(w);
  }

 private:
  bool parallelogram_ = false;
  // Only the one of the light's shape is initialised; both are plain data.
  SphericalTriangle triangle_;
  SphericalRectangle rectangle_;
};

}  // namespace penumbra
