#include "app/ui/viewer_output.h"

#include <filesystem>

#include "app/ui/light_share_map.h"
#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/error.h"

namespace penumbra::ui {

std::string saveSnapshotImage(const std::string& path, const FilmSnapshot& snapshot, bool lightShare,
                              const RenderSettings& settings, const std::string& scenePath, float exposure) {
  if (snapshot.mean.empty()) throw Error(path + ": nothing rendered yet");
  ImageMetadata meta;
  for (auto& [k, v] : describeSettings(settings)) meta.add(k, v);
  meta.add("spp", std::to_string(snapshot.spp));
  meta.add("seconds", std::to_string(snapshot.seconds));
  meta.add("scene", scenePath.empty() ? "<built-in>" : scenePath);
  if (lightShare) {
    // EXR/PFM: the split (R light, G cosine, B the rest, as luminance); PNG: the false-colour map.
    meta.add("output", "mis-light-share");
    if (imageFormatFromPath(path) == ImageFormat::Png) {
      writeImage(path, lightShareMapImage(snapshot.mean), meta, 0.f);
      return "saved " + path + " (MIS light share, " + std::to_string(snapshot.spp) + " spp)";
    }
  }
  writeImage(path, snapshot.mean, meta, exposure);
  return "saved " + path + " (" + std::to_string(snapshot.spp) + " spp)";
}

std::string saveSceneFile(const std::string& path, const SceneNode& desc, const RenderSettings& settings,
                          const std::optional<CameraLookAt>& cameraLookAt) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  const std::string xml = writeScene(desc, settings, {dir.empty() ? "." : dir.string(), cameraLookAt});
  writeBytesAtomically(path, xml.data(), xml.size());
  return "saved " + path;
}

}  // namespace penumbra::ui
