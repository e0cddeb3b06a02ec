#include "core/scene/scene_writer.h"

#include <algorithm>
#include <filesystem>
#include <string_view>
#include <vector>

#include "core/math/error.h"
#include "core/render/strategy_axes.h"
#include "core/scene/scene_builder.h"
#include "core/scene/xml_parser.h"

namespace penumbra {

namespace fs = std::filesystem;

namespace {

Property makeProp(const std::string& name, PropertyType type, const std::string& text) {
  Property p;
  if (!parsePropertyValue(type, text, p)) throw Error("internal: cannot encode " + name + " = " + text);
  p.name = name;
  p.used = true;
  return p;
}

Property floatProp(const std::string& name, float value) {
  return makeProp(name, PropertyType::Float, formatFloat(value));
}

// Replaces (or adds) the named properties: the description's own ones are dropped, the new ones
// follow the properties that stay.
void replaceProps(SceneNode& node, const std::vector<Property>& props) {
  PropertyList out;
  out.setContext(node.file, node.tag, node.type);
  for (const Property& p : node.props.properties())
    if (std::none_of(props.begin(), props.end(), [&](const Property& q) { return q.name == p.name; }))
      out.add(p);
  for (const Property& p : props) out.add(p);
  node.props = std::move(out);
}

SceneNode& childOrNew(SceneNode& parent, const std::string& tag, const std::string& type) {
  for (SceneNode& c : parent.children)
    if (c.tag == tag) return c;
  SceneNode n;
  n.tag = tag;
  n.type = type;
  n.file = parent.file;
  n.baseDir = parent.baseDir;
  n.props.setContext(n.file, n.tag, n.type);
  parent.children.push_back(std::move(n));
  return parent.children.back();
}

std::string matrixText(const glm::mat4& m) {  // row-major, 16 numbers
  std::string s;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) s += (s.empty() ? "" : " ") + formatFloat(m[c][r]);
  return s;
}

// The camera's toWorld as written: the given lookat when it is the camera, else the description's
// own <lookat> while the camera is still the description's, else the matrix.
Property toWorldProp(const SceneNode* describedCamera, const glm::mat4& toWorld,
                     const std::optional<CameraLookAt>& lookAt) {
  Property p = makeProp("toWorld", PropertyType::Transform, matrixText(toWorld));
  if (lookAt) {
    p.hasLookAt = true;
    p.lookAtOrigin = lookAt->origin;
    p.lookAtTarget = lookAt->target;
    p.lookAtUp = lookAt->up;
    if (isItsLookAt(p)) return p;
    p.hasLookAt = false;
  }
  if (describedCamera)
    if (const Property* own = describedCamera->props.find({"toWorld"}))
      if (own->type == PropertyType::Transform && own->hasLookAt && own->matrix == toWorld) return *own;
  return p;
}

void writeCamera(SceneNode& root, const RenderSettings& s, const RenderSettings* described,
                 const std::optional<CameraLookAt>& lookAt) {
  const SceneNode* before = root.child("camera");
  const CameraDesc& c = s.camera;
  std::vector<Property> props = {toWorldProp(before, c.toWorld, lookAt), floatProp("fov", c.fovDegrees),
                                 makeProp("width", PropertyType::Integer, std::to_string(c.width)),
                                 makeProp("height", PropertyType::Integer, std::to_string(c.height))};
  // The clip planes: where the description names them or they differ from its values (its own
  // spelling of a value that did not change stays).
  auto clip = [&](const char* name, float value, float describedValue) {
    const Property* own = before ? before->props.find({name}) : nullptr;
    if (own && (own->type == PropertyType::Float || own->type == PropertyType::Integer) &&
        float(own->type == PropertyType::Float ? own->floatValue : double(own->intValue)) == value)
      props.push_back(*own);
    else if (own || !described || value != describedValue)
      props.push_back(floatProp(name, value));
  };
  clip("nearClip", c.nearClip, described ? described->camera.nearClip : 0.f);
  clip("farClip", c.farClip, described ? described->camera.farClip : 0.f);
  SceneNode& cam = childOrNew(root, "camera", "perspective");
  replaceProps(cam, props);

  if (described && s.filter == described->filter) return;
  const FilterDesc& f = s.filter;
  SceneNode& rf = childOrNew(cam, "rfilter", filterTypeName(f.type));
  rf.type = filterTypeName(f.type);
  rf.props = PropertyList();
  rf.props.setContext(rf.file, rf.tag, rf.type);
  rf.props.add(floatProp("radius", f.radius));
  if (f.type == FilterType::Gaussian) rf.props.add(floatProp("stddev", f.stddev));
  if (f.type == FilterType::Mitchell) {
    rf.props.add(floatProp("B", f.B));
    rf.props.add(floatProp("C", f.C));
  }
}

void writeSampler(SceneNode& root, const RenderSettings& s) {
  const std::string type = samplerKindName(s.samplerKind);
  SceneNode& smp = childOrNew(root, "sampler", type);
  smp.type = type;
  replaceProps(smp, {makeProp("sampleCount", PropertyType::Integer, std::to_string(s.sampleCount)),
                     makeProp("seed", PropertyType::Integer, std::to_string(s.seed))});
}

// The strategy's canonical properties. A property of the description's integrator that its own
// strategy did not read (`used` as the description built) and the written one does not read either
// stays as it was, so the file reads back as it did (with the same "not used" warning).
void writeIntegrator(SceneNode& root, const RenderSettings& s, bool describedBuilt) {
  const std::string type(nameOf(s.integrator.type));
  SceneNode& integ = childOrNew(root, "integrator", type);
  std::vector<Property> unread;
  if (describedBuilt)
    for (const Property& p : integ.props.properties())
      if (!p.used && !integratorReads(s.integrator, p.name)) unread.push_back(p);
  integ.type = type;
  integ.props = PropertyList();
  integ.props.setContext(integ.file, integ.tag, integ.type);
  for (const CanonicalProperty& p : canonicalProperties(s.integrator))
    integ.props.add(
        makeProp(std::string(p.name), p.isInteger ? PropertyType::Integer : PropertyType::String, p.value));
  for (const Property& p : unread) integ.props.add(p);
}

void rebaseNode(SceneNode& node, const fs::path& dir) {
  PropertyList out;
  out.setContext(node.file, node.tag, node.type);
  bool changed = false;
  for (Property p : node.props.properties()) {
    if (p.type == PropertyType::String && !p.stringValue.empty() && fs::path(p.stringValue).is_relative()) {
      std::error_code ec;
      fs::path file = fs::absolute(fs::path(node.baseDir.empty() ? "." : node.baseDir) / p.stringValue, ec);
      if (!ec && fs::is_regular_file(file, ec)) {
        file = fs::weakly_canonical(file, ec);
        fs::path rel = file.lexically_relative(dir);
        p.stringValue = (rel.empty() ? file : rel).generic_string();
        changed = true;
      }
    }
    out.add(p);
  }
  if (changed) node.props = std::move(out);
  for (SceneNode& c : node.children) rebaseNode(c, dir);
  node.baseDir = dir.string();
}

}  // namespace

void rebaseFilePaths(SceneNode& root, const std::string& dir) {
  std::error_code ec;
  fs::path abs = fs::absolute(dir.empty() ? "." : dir, ec);
  fs::path canonical = fs::weakly_canonical(abs, ec);
  rebaseNode(root, ec ? abs : canonical);
}

SceneNode sceneWithSettings(const SceneNode& desc, const RenderSettings& settings,
                            const SceneWriteOptions& options) {
  SceneNode root = desc;
  // What the description gives by itself, for the settings written only where they differ; a
  // description that does not build has them all written.
  std::optional<RenderSettings> described;
  if (const SceneNode* integ = root.child("integrator"))
    for (const Property& p : integ->props.properties()) p.used = false;  // marked again by the build
  try {
    described = buildSettings(root);
  } catch (const Error&) {
  }
  if (!options.outputDir.empty()) rebaseFilePaths(root, options.outputDir);
  writeCamera(root, settings, described ? &*described : nullptr, options.cameraLookAt);
  writeSampler(root, settings);
  writeIntegrator(root, settings, described.has_value());
  return root;
}

std::string writeScene(const SceneNode& desc, const RenderSettings& settings,
                       const SceneWriteOptions& options) {
  return writeSceneXml(sceneWithSettings(desc, settings, options));
}

}  // namespace penumbra
