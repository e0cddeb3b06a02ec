#include "core/scene/xml_parser.h"
#include "core/math/frame.h"
#include "core/scene/xml_error_text.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/math/bounded_read.h"
#include "core/math/error.h"
#include "core/math/utf8.h"
#include "core/render/render_settings.h"

namespace penumbra {

namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

const char* kObjectTags[] = {"scene",  "shape",   "bsdf",       "emitter",
                             "camera", "sampler", "integrator", "rfilter"};

bool isObjectTag(std::string_view tag) {
  for (const char* t : kObjectTags)
    if (tag == t) return true;
  return tag == "mesh";
}

std::string normaliseTag(std::string_view tag) {
  return tag == "mesh" ? "shape" : std::string(tag);
}

// Children an object may contain, and whether at most one of them is allowed.
bool childAllowed(const std::string& parent, const std::string& child, bool& single) {
  single = false;
  if (parent == "scene") {
    if (child == "shape" || child == "emitter") return true;
    single = true;
    return child == "camera" || child == "sampler" || child == "integrator";
  }
  single = true;
  if (parent == "shape") return child == "bsdf" || child == "emitter";
  if (parent == "camera") return child == "rfilter";
  return false;
}

std::string allowedParents(const std::string& child) {
  if (child == "scene") return "only as the root element";
  if (child == "bsdf") return "inside <shape>";
  if (child == "emitter") return "inside <scene> or <shape>";
  if (child == "rfilter") return "inside <camera>";
  return "inside <scene>";
}

int lineOf(const XMLElement& e) {
  return e.GetLineNum();
}

std::string elementDesc(const XMLElement& e) {
  std::string s = "<" + std::string(e.Name());
  if (const char* n = e.Attribute("name")) s += " name=\"" + std::string(n) + "\"";
  if (const char* t = e.Attribute("type")) s += " type=\"" + std::string(t) + "\"";
  return s + ">";
}

const char* requireAttr(const XMLElement& e, const char* attr, const std::string& file) {
  const char* v = e.Attribute(attr);
  if (!v) throw Error(file, lineOf(e), elementDesc(e) + ": expected a " + attr + "=\"...\" attribute");
  return v;
}

Vec3 vecAttr(const XMLElement& e, const char* attr, const std::string& file) {
  const char* text = requireAttr(e, attr, file);
  Vec3 v;
  if (!parseVec3Value(text, v))
    throw Error(file, lineOf(e),
                elementDesc(e) + ": " + attr + "=\"" + text + "\": expected three numbers like \"1, 2, 3\"");
  return v;
}

float floatAttr(const XMLElement& e, const char* attr, const std::string& file) {
  const char* text = requireAttr(e, attr, file);
  double v;
  if (!parseFloatValue(text, v) || !std::isfinite(static_cast<float>(v)))
    throw Error(file, lineOf(e), elementDesc(e) + ": " + attr + "=\"" + text + "\": expected a number");
  return static_cast<float>(v);
}

// translate/scale: value="x,y,z" (scale also value="s"), or separate x= y= z= attributes.
Vec3 componentsOrValue(const XMLElement& e, const std::string& file, float missing, bool allowScalar) {
  if (const char* text = e.Attribute("value")) {
    Vec3 v;
    if (!parseVec3Value(text, v, allowScalar))
      throw Error(file, lineOf(e),
                  elementDesc(e) + ": value=\"" + std::string(text) + "\": expected " +
                      (allowScalar ? "one number or three numbers like \"1, 2, 3\""
                                   : "three numbers like \"1, 2, 3\""));
    return v;
  }
  const char* names[3] = {"x", "y", "z"};
  Vec3 v(missing);
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    if (e.Attribute(names[k])) {
      v[k] = floatAttr(e, names[k], file);
      any = true;
    }
  }
  if (!any)
    throw Error(file, lineOf(e), elementDesc(e) + ": expected a value=\"...\" or x=, y=, z= attributes");
  return v;
}

struct Parser {
  std::string file;
  std::string baseDir;

  void parseProperty(const XMLElement& e, PropertyType type, SceneNode& node) {
    Property p;
    p.name = requireAttr(e, "name", file);
    p.line = lineOf(e);
    if (p.name.empty()) throw Error(file, p.line, elementDesc(e) + ": expected a non-empty name");
    if (type == PropertyType::Transform) {
      p.type = type;
      p.matrix = parseTransformElement(e, file, &p);
    } else {
      if (e.FirstChildElement())
        throw Error(file, lineOf(*e.FirstChildElement()),
                    "<" + std::string(e.FirstChildElement()->Name()) + "> inside " + elementDesc(e) +
                        ": expected no nested elements in a property");
      const char* text = requireAttr(e, "value", file);
      if (!parsePropertyValue(type, text, p)) {
        std::string expected;
        switch (type) {
          case PropertyType::Boolean:
            expected = "true or false";
            break;
          case PropertyType::Integer:
            expected = "an integer";
            break;
          case PropertyType::Float:
            expected = "a finite number";
            break;
          case PropertyType::Color:
            expected = "a color like \"1, 0.5, 0\" or a grey value";
            break;
          default:
            expected = "three numbers like \"1, 2, 3\"";
            break;
        }
        throw Error(file, p.line, elementDesc(e) + ": expected " + expected + ", got \"" + text + "\"");
      }
    }
    node.props.add(std::move(p));
  }

  SceneNode parseObject(const XMLElement& e) {
    SceneNode node;
    node.tag = normaliseTag(e.Name());
    node.file = file;
    node.line = lineOf(e);
    node.baseDir = baseDir;
    if (node.tag != "scene") {
      const char* t = e.Attribute("type");
      if (!t || !*t)
        throw Error(file, node.line, "<" + std::string(e.Name()) + ">: expected a type=\"...\" attribute");
      node.type = t;
    }
    node.props.setContext(file, node.tag, node.type);
    for (const XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
      std::string_view name = c->Name();
      PropertyType ptype;
      if (parsePropertyType(name, ptype)) {
        parseProperty(*c, ptype, node);
      } else if (isObjectTag(name)) {
        std::string childTag = normaliseTag(name);
        bool single = false;
        if (!childAllowed(node.tag, childTag, single)) {
          throw Error(file, lineOf(*c),
                      "<" + std::string(name) + "> inside <" + node.tag + ">: expected it " +
                          allowedParents(childTag));
        }
        if (single) {
          if (const SceneNode* prev = node.child(childTag)) {
            throw Error(file, lineOf(*c),
                        "second <" + childTag + "> inside <" + node.tag + "> (first at line " +
                            std::to_string(prev->line) + "): expected at most one");
          }
        }
        node.children.push_back(parseObject(*c));
      } else {
        throw Error(
            file, lineOf(*c),
            "unknown tag <" + std::string(name) +
                ">: expected an object (scene, shape, mesh, bsdf, emitter, camera, sampler, integrator, "
                "rfilter) or a property (boolean, integer, float, string, point, vector, color, "
                "transform)");
      }
    }
    return node;
  }
};

std::string dirOf(const std::string& path) {
  fs::path p(path);
  fs::path d = p.parent_path();
  return d.empty() ? std::string(".") : d.string();
}

void writeNode(tinyxml2::XMLPrinter& out, const SceneNode& node) {
  out.OpenElement(node.tag.c_str());
  if (!node.type.empty()) out.PushAttribute("type", node.type.c_str());
  for (const Property& p : node.props.properties()) {
    if (p.type == PropertyType::Transform) {
      out.OpenElement("transform");
      out.PushAttribute("name", p.name.c_str());
      if (isItsLookAt(p)) {
        out.OpenElement("lookat");
        out.PushAttribute("origin", formatVec3(p.lookAtOrigin).c_str());
        out.PushAttribute("target", formatVec3(p.lookAtTarget).c_str());
        out.PushAttribute("up", formatVec3(p.lookAtUp).c_str());
      } else {
        out.OpenElement("matrix");
        out.PushAttribute("value", p.valueText().c_str());
      }
      out.CloseElement();
      out.CloseElement();
    } else {
      out.OpenElement(propertyTypeName(p.type));
      out.PushAttribute("name", p.name.c_str());
      out.PushAttribute("value", p.valueText().c_str());
      out.CloseElement();
    }
  }
  for (const SceneNode& c : node.children) writeNode(out, c);
  out.CloseElement();
}

SceneNode* findFirst(SceneNode& node, const std::string& tag) {
  for (SceneNode& c : node.children) {
    if (c.tag == tag) return &c;
    if (SceneNode* f = findFirst(c, tag)) return f;
  }
  return nullptr;
}

// Refuses a NUL byte, or a character reference to one (&#0;, &#x0;), with its line and column. XML
// allows neither, and tinyxml2 keeps text as C strings: everything after one would be dropped unseen.
void checkNoNulCharacter(const std::string& xml, const std::string& file) {
  size_t at = xml.find('\0');
  std::string what = "a NUL character (byte 0)";
  for (size_t r = xml.find("&#"); r != std::string::npos && r < at; r = xml.find("&#", r + 2)) {
    size_t i = r + 2;
    if (i < xml.size() && xml[i] == 'x') ++i;
    const size_t digits = i;
    while (i < xml.size() && xml[i] == '0') ++i;
    if (i > digits && i < xml.size() && xml[i] == ';') {
      at = r;
      what = "the character reference " + xml.substr(r, i + 1 - r) + " (NUL)";
      break;
    }
  }
  if (at == std::string::npos) return;
  const size_t lineStart = at == 0 ? 0 : xml.rfind('\n', at - 1) + 1;  // npos + 1 == 0: the first line
  const int line = 1 + int(std::count(xml.begin(), xml.begin() + std::ptrdiff_t(at), '\n'));
  throw Error(file, line,
              "column " + std::to_string(at - lineStart + 1) + ": " + what +
                  " is not allowed in a scene (XML text cannot hold one)");
}

}  // namespace

glm::mat4 lookAtMatrix(const Vec3& origin, const Vec3& target, const Vec3& up, const std::string& file,
                       int line) {
  Vec3 d = target - origin;
  float len = glm::length(d);
  if (!(len > 0.f) || !std::isfinite(len))
    throw Error(file, line,
                "<lookat>: expected target different from origin (the viewing direction is undefined)");
  Vec3 dir = d / len;
  float upLen = glm::length(up);
  if (!(upLen > 0.f)) throw Error(file, line, "<lookat>: expected a non-zero up vector");
  Vec3 c = glm::cross(up / upLen, dir);
  float cl = glm::length(c);
  if (!(cl > 1e-6f))
    throw Error(file, line,
                "<lookat>: expected an up vector not parallel to the viewing direction (target - origin)");
  Vec3 left = c / cl;
  Vec3 newUp = glm::normalize(glm::cross(dir, left));
  return cameraToWorld(origin, left, newUp, dir);
}

bool isItsLookAt(const Property& p) {
  if (!p.hasLookAt) return false;
  glm::mat4 m;
  try {
    m = lookAtMatrix(p.lookAtOrigin, p.lookAtTarget, p.lookAtUp, "", 0);
  } catch (const Error&) {
    return false;
  }
  float scale = 1.f;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) scale = std::max(scale, std::abs(p.matrix[c][r]));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::abs(m[c][r] - p.matrix[c][r]) <= 1e-5f * scale)) return false;
  return true;
}

glm::mat4 parseTransformElement(const tinyxml2::XMLElement& element, const std::string& file,
                                Property* lookat) {
  glm::mat4 m(1.f);
  glm::mat4 afterLookAt(1.f);  // the operations after the last <lookat>
  Vec3 origin(0.f), target(0.f), up(0.f, 1.f, 0.f);
  bool hasLookAt = false;
  for (const XMLElement* c = element.FirstChildElement(); c; c = c->NextSiblingElement()) {
    std::string_view op = c->Name();
    glm::mat4 t(1.f);
    if (op == "translate") {
      t = glm::translate(glm::mat4(1.f), componentsOrValue(*c, file, 0.f, false));
    } else if (op == "scale") {
      t = glm::scale(glm::mat4(1.f), componentsOrValue(*c, file, 1.f, true));
    } else if (op == "rotate") {
      Vec3 axis = vecAttr(*c, "axis", file);
      float angle = floatAttr(*c, "angle", file);
      float al = glm::length(axis);
      if (!(al > 0.f)) throw Error(file, lineOf(*c), "<rotate>: expected a non-zero axis");
      t = glm::rotate(glm::mat4(1.f), glm::radians(angle), axis / al);
    } else if (op == "matrix") {
      const char* text = requireAttr(*c, "value", file);
      Property p;
      if (!parsePropertyValue(PropertyType::Transform, text, p))
        throw Error(file, lineOf(*c),
                    "<matrix>: expected 16 numbers (row-major), got \"" + std::string(text) + "\"");
      t = p.matrix;
    } else if (op == "lookat") {
      origin = vecAttr(*c, "origin", file);
      target = vecAttr(*c, "target", file);
      up = vecAttr(*c, "up", file);
      t = lookAtMatrix(origin, target, up, file, lineOf(*c));
      hasLookAt = true;
      afterLookAt = glm::mat4(1.f);
      m = t * m;
      continue;
    } else {
      throw Error(file, lineOf(*c),
                  "unknown transform operation <" + std::string(op) +
                      ">: expected translate, scale, rotate, matrix or lookat");
    }
    m = t * m;
    afterLookAt = t * afterLookAt;
  }
  if (lookat && hasLookAt) {
    lookat->hasLookAt = true;
    lookat->lookAtOrigin = Vec3(afterLookAt * glm::vec4(origin, 1.f));
    lookat->lookAtTarget = Vec3(afterLookAt * glm::vec4(target, 1.f));
    lookat->lookAtUp = Vec3(afterLookAt * glm::vec4(up, 0.f));
  }
  return m;
}

namespace {

// tinyxml2 passes any bytes through: scene files must be UTF-8 text, so that every name and value
// read from them is text for the messages and for Python (a NUL is refused before this).
void checkSceneText(const std::string& xml, const std::string& file) {
  const size_t at = invalidUtf8Offset(xml);
  if (at == std::string::npos) return;
  const int line = 1 + int(std::count(xml.begin(), xml.begin() + std::ptrdiff_t(at), '\n'));
  const size_t lineStart = at == 0 ? std::string::npos : xml.rfind('\n', at - 1);
  const size_t column = lineStart == std::string::npos ? at + 1 : at - lineStart;
  char what[160];
  std::snprintf(what, sizeof what,
                "byte 0x%02X at column %zu is not UTF-8: a scene file is UTF-8 text (convert it, e.g. "
                "with iconv -f latin1 -t utf-8)",
                unsigned(uint8_t(xml[at])), column);
  throw Error(file, line, what);
}

}  // namespace

SceneNode parseSceneString(const std::string& xml, const std::string& nameForErrors,
                           const std::string& baseDir) {
  checkNoNulCharacter(xml, nameForErrors);
  checkSceneText(xml, nameForErrors);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw Error(nameForErrors, doc.ErrorLineNum(),
                "malformed XML: " + describeXmlError(doc.ErrorID(), doc.ErrorStr() ? doc.ErrorStr() : ""));
  const XMLElement* root = doc.RootElement();
  if (!root) throw Error(nameForErrors, 0, "expected a <scene> element, found none");
  if (std::string_view(root->Name()) != "scene")
    throw Error(nameForErrors, root->GetLineNum(),
                "root element <" + std::string(root->Name()) + ">: expected <scene>");
  Parser parser{nameForErrors, baseDir};
  return parser.parseObject(*root);
}

SceneNode parseSceneFile(const std::string& path) {
  checkNoNulInPath(path, "scene file");
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw Error(path, 0, "cannot open scene file (resolved to " + fs::absolute(path, ec).string() + ")");
  return parseSceneString(readRegularFile(path, kMaxSceneFileBytes, "scene file"), path, dirOf(path));
}

std::string writeSceneXml(const SceneNode& root) {
  tinyxml2::XMLPrinter out;
  writeNode(out, root);
  return out.CStr();
}

void applyOverride(SceneNode& root, std::string_view key, std::string_view value) {
  std::string setText = "--set " + escapeInvalidUtf8(key) + "=" + escapeInvalidUtf8(value);
  if (invalidUtf8Offset(key) != std::string_view::npos || invalidUtf8Offset(value) != std::string_view::npos)
    throw Error(setText + ": not UTF-8 text");
  if (key.find('\0') != std::string_view::npos || value.find('\0') != std::string_view::npos)
    throw Error(setText + ": contains a NUL character");
  size_t dot = key.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == key.size())
    throw Error(setText + ": expected a key of the form object.property, e.g. sampler.sampleCount");
  std::string tag = normaliseTag(key.substr(0, dot));
  std::string_view prop = key.substr(dot + 1);
  SceneNode* node = tag == "scene" ? &root : root.tag == tag ? &root : findFirst(root, tag);
  if (!node && (tag == "integrator" || tag == "sampler" || tag == "camera")) {
    // Scene-wide objects may be absent from the file: --set creates them with their default type.
    SceneNode created;
    created.tag = tag;
    const RenderSettings defaults;
    created.type = tag == "integrator" ? std::string(nameOf(defaults.integrator.type))
                   : tag == "sampler"  ? std::string(samplerKindName(defaults.samplerKind))
                                       : "perspective";
    created.file = root.file;
    created.baseDir = root.baseDir;
    created.props.setContext(root.file, created.tag, created.type);
    root.children.push_back(std::move(created));
    node = &root.children.back();
  }
  if (node && prop == "type") {
    // "integrator.type=ao" switches the object's type (its properties stay; unused ones warn).
    node->type = std::string(value);
    node->typeSetBy = setText;
    node->props.setContext(node->file, node->tag, node->type);
    return;
  }
  if (!node) {
    std::string known =
        isObjectTag(tag) ? ""
                         : " (objects are scene, shape, bsdf, emitter, camera, sampler, integrator, rfilter)";
    throw Error(root.file, 0, setText + ": the scene has no <" + tag + ">" + known);
  }
  node->props.set(prop, value, setText);
}

std::string resolveScenePath(const SceneNode& node, const std::string& relative) {
  fs::path p(relative);
  if (p.is_absolute() || node.baseDir.empty()) return p.string();
  return (fs::path(node.baseDir) / p).lexically_normal().string();
}

}  // namespace penumbra
