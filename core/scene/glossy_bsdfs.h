// The glossy <bsdf> elements of a scene description (microfacet, roughconductor), in document order,
// and edits of their properties: what the viewer's Materials panel lists and changes. An edit is
// made to the description, which is then built again, so every check of the scene file applies to
// it and a saved scene keeps it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/materials/bsdf.h"
#include "core/scene/scene_desc.h"

namespace penumbra {

struct GlossyBsdfEntry {
  std::string label;  // "shape 3 (rectangle) \"plate\"": the shape's place among the shapes, its name
  Bsdf bsdf;          // the values as the builder reads them
};

std::vector<GlossyBsdfEntry> glossyBsdfs(const SceneNode& desc);

// Sets property `name` of the `index`-th glossy <bsdf> of `desc` to the text `value`, as --set would
// (a property that exists keeps its type); `setBy` names the edit in later errors. Throws Error
// when there is no such entry.
void setGlossyBsdfProperty(SceneNode& desc, size_t index, std::string_view name, std::string_view value,
                           const std::string& setBy);

}  // namespace penumbra
