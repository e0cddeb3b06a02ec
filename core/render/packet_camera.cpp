#include "core/render/packet_camera.h"

namespace penumbra {

PacketCamera makePacketCamera(const PerspectiveCamera& camera, const FilterSampler& filter) {
  PacketCamera c{};
  for (int i = 0; i < 3; ++i) {
    c.origin[i] = camera.origin()[i];
    c.right[i] = camera.right()[i];
    c.up[i] = camera.up()[i];
    c.forward[i] = camera.forward()[i];
  }
  c.tanHalfX = camera.tanHalfFov().x;
  c.tanHalfY = camera.tanHalfFov().y;
  c.invWidth = camera.inverseSize().x;
  c.invHeight = camera.inverseSize().y;
  c.nearClip = camera.desc().nearClip;
  c.farClip = camera.desc().farClip;
  c.filter = filter.tables();
  return c;
}

}  // namespace penumbra
