// The parsed scene description: plain data, one node per XML object element, with source lines.
// The builder (elsewhere) decides which type="..." names exist and turns nodes into objects.
#pragma once

#include <string>
#include <vector>

#include "core/scene/property.h"

namespace penumbra {

struct SceneNode {
  // One of: scene, shape, bsdf, emitter, camera, sampler, integrator, rfilter ("mesh" is read as
  // "shape").
  std::string tag;
  std::string type;       // the type="..." attribute (empty for the root <scene>)
  std::string typeSetBy;  // "--set integrator.type=ao" when an override gave the type
  PropertyList props;
  std::vector<SceneNode> children;  // nested objects in document order
  std::string file;                 // the XML file name used in messages
  int line = 0;
  // Directory of the XML file; relative paths (OBJ filename) resolve against it. Set on every node.
  std::string baseDir;

  // First direct child with this tag, or nullptr.
  const SceneNode* child(const std::string& childTag) const {
    for (const SceneNode& c : children)
      if (c.tag == childTag) return &c;
    return nullptr;
  }
};

}  // namespace penumbra
