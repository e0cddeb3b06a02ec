#include "core/scene/glossy_bsdfs.h"

#include "core/math/error.h"
#include "core/scene/bsdf_builder.h"

namespace penumbra {

namespace {

bool isGlossy(const SceneNode& bsdf) {
  return bsdf.type == "microfacet" || bsdf.type == "roughconductor";
}

// Calls f(shape, bsdf, shapeIndex) for each shape with a glossy <bsdf>, in document order.
template <class Desc, class F>
void forEachGlossy(Desc& desc, const F& f) {
  size_t shapeIndex = 0;
  for (auto& shape : desc.children) {
    if (shape.tag != "shape") continue;
    for (auto& child : shape.children)
      if (child.tag == "bsdf" && isGlossy(child)) {
        f(shape, child, shapeIndex);
        break;
      }
    ++shapeIndex;
  }
}

}  // namespace

std::vector<GlossyBsdfEntry> glossyBsdfs(const SceneNode& desc) {
  std::vector<GlossyBsdfEntry> out;
  std::vector<std::string> warnings;
  forEachGlossy(desc, [&](const SceneNode& shape, const SceneNode& bsdf, size_t shapeIndex) {
    GlossyBsdfEntry e;
    e.label = "shape " + std::to_string(shapeIndex) + " (" + shape.type + ")";
    if (const Property* name = shape.props.find({"name"})) e.label += " \"" + name->stringValue + "\"";
    e.bsdf = buildBsdf(&bsdf, warnings);
    out.push_back(std::move(e));
  });
  return out;
}

void setGlossyBsdfProperty(SceneNode& desc, size_t index, std::string_view name, std::string_view value,
                           const std::string& setBy) {
  size_t i = 0;
  bool done = false;
  forEachGlossy(desc, [&](SceneNode&, SceneNode& bsdf, size_t) {
    if (i++ != index || done) return;
    done = true;
    // A colour the file does not have is added as a colour, so that a saved scene writes a <color>
    // (set() would infer a string from the text).
    const bool colour = name == "kd" || name == "specularReflectance" || name == "specular_reflectance";
    if (!colour || bsdf.props.find({name})) return bsdf.props.set(name, value, setBy);
    Property p;
    p.name = std::string(name);
    p.type = PropertyType::Color;
    p.setBy = setBy;
    if (!parsePropertyValue(PropertyType::Color, value, p))
      throw Error(setBy + ": expected a colour like \"0.5, 0.5, 0.5\", got \"" + std::string(value) + "\"");
    bsdf.props.add(std::move(p));
  });
  if (!done) throw Error(setBy + ": the scene has no glossy <bsdf> number " + std::to_string(index));
}

}  // namespace penumbra
