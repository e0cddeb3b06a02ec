// Nori-style scene XML → SceneNode tree (tinyxml2), the reverse (writeSceneXml), and --set overrides.
//
// Checked here: well-formed XML, known tags, property types, name/value attributes, strict values,
// transform operations, and tag nesting:
//   scene   : shape (alias mesh), emitter, camera, sampler, integrator  (camera/sampler/integrator at
//             most once)
//   shape   : bsdf (at most once), emitter (at most once)
//   camera  : rfilter (at most once)
//   others  : no nested objects
// Not checked here: which type="..." names exist and value ranges (the builder does that, with
// PropertyList::lineOf for the line).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <glm/mat4x4.hpp>

#include "core/scene/scene_desc.h"

namespace tinyxml2 {
class XMLElement;
}

namespace penumbra {

// The largest scene file parseSceneFile reads (meshes live in their own files; hand-written scenes are
// far below this). What writes scene files (penumbra bench --write-scaling-scene) keeps to it too.
inline constexpr uint64_t kMaxSceneFileBytes = uint64_t(64) << 20;

// Parses a scene file. The file name in messages is `path` as given; baseDir is its directory.
SceneNode parseSceneFile(const std::string& path);
// Parses XML text. `nameForErrors` is the file name used in messages; `baseDir` is recorded on every
// node for resolving relative paths.
SceneNode parseSceneString(const std::string& xml, const std::string& nameForErrors,
                           const std::string& baseDir);

// Serialises a tree back to XML that parseSceneString reads to the same tree (transforms are
// written as a single <matrix>, or as their <lookat> when they are exactly one; floats with
// round-trip precision).
std::string writeSceneXml(const SceneNode& root);

// Applies a --set override "tag.property=value": key = "tag.property" (e.g. "sampler.sampleCount",
// "integrator.measure", "camera.fov"; "mesh" means "shape"). It applies to the first object with
// that tag in document order (depth first). Error if the key is malformed or there is no such object.
void applyOverride(SceneNode& root, std::string_view key, std::string_view value);

// Resolves a path from the scene (e.g. an OBJ filename) against the node's baseDir; absolute paths
// are returned unchanged.
std::string resolveScenePath(const SceneNode& node, const std::string& relative);

// Builds the matrix of a <transform> element (children applied in document order, each new
// operation left-multiplying: M = op * M). Errors carry `file` and the element's line.
struct Property;
// `lookat` (optional) receives the <lookat> target and up, when there is one.
glm::mat4 parseTransformElement(const tinyxml2::XMLElement& element, const std::string& file,
                                Property* lookat = nullptr);

// Nori's lookAt: camera-to-world matrix with columns (left, up, dir, origin). Throws Error(file, line)
// when target == origin or up is parallel to the viewing direction.
glm::mat4 lookAtMatrix(const Vec3& origin, const Vec3& target, const Vec3& up, const std::string& file,
                       int line);

// Whether a transform property is exactly its <lookat> (up to float rounding of the same
// construction), so that writing the <lookat> instead of the matrix reads back to the same transform.
// writeSceneXml writes such a transform as its <lookat>.
bool isItsLookAt(const Property& transform);

}  // namespace penumbra
