#include "core/scene/property.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/math/error.h"
#include "core/math/float_util.h"

namespace penumbra {

namespace {

std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\n";
  size_t b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

const char* kTypeNames[] = {"boolean", "integer", "float", "string", "point", "vector", "color", "transform"};

std::string quoted(std::string_view s) {
  return "\"" + std::string(s) + "\"";
}

}  // namespace

const char* propertyTypeName(PropertyType type) {
  return kTypeNames[static_cast<int>(type)];
}

bool parsePropertyType(std::string_view tag, PropertyType& out) {
  for (int i = 0; i < 8; ++i) {
    if (tag == kTypeNames[i]) {
      out = static_cast<PropertyType>(i);
      return true;
    }
  }
  return false;
}

bool parseIntegerValue(std::string_view text, int64_t& out) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return false;
  int64_t v = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v, 10);
  if (ec != std::errc() || ptr != text.data() + text.size()) return false;
  out = v;
  return true;
}

bool parseFloatValue(std::string_view text, double& out) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return false;
  // Only plain decimal/scientific notation: this also rules out "nan", "inf", "infinity" and hex.
  for (char c : text) {
    if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E')) return false;
  }
  double v = 0.0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v, std::chars_format::general);
  if (ptr != text.data() + text.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    // Overflow is an error; underflow (1e-400) rounds to zero or a denormal as strtod does.
    std::string copy(text);
    v = std::strtod(copy.c_str(), nullptr);
    if (!std::isfinite(v) || std::fabs(v) > 1.0) return false;
  } else if (ec != std::errc()) {
    return false;
  }
  if (!std::isfinite(v)) return false;
  if (v == 0.0) v = 0.0;  // normalise -0 to +0
  out = v;
  return true;
}

bool parseBooleanValue(std::string_view text, bool& out) {
  text = trim(text);
  if (text == "true") {
    out = true;
    return true;
  }
  if (text == "false") {
    out = false;
    return true;
  }
  return false;
}

bool parseFloatList(std::string_view text, std::vector<double>& out) {
  out.clear();
  text = trim(text);
  if (text.empty()) return false;
  size_t i = 0;
  bool expectValue = true;  // a comma must be followed by a value
  while (i < text.size()) {
    char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      ++i;
      continue;
    }
    if (c == ',') {
      if (expectValue) return false;  // ",," or leading comma
      expectValue = true;
      ++i;
      continue;
    }
    size_t j = i;
    while (j < text.size() && text[j] != ',' && text[j] != ' ' && text[j] != '\t' && text[j] != '\r' &&
           text[j] != '\n')
      ++j;
    double v;
    if (!parseFloatValue(text.substr(i, j - i), v)) return false;
    out.push_back(v);
    expectValue = false;
    i = j;
  }
  return !expectValue;  // no trailing comma
}

bool parseVec3Value(std::string_view text, Vec3& out, bool allowScalar) {
  std::vector<double> values;
  if (!parseFloatList(text, values)) return false;
  if (values.size() == 1 && allowScalar) values.assign(3, values[0]);
  if (values.size() != 3) return false;
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    float f = toFloatSaturating(values[k]);
    if (!std::isfinite(f)) return false;  // fits double but not float
    v[k] = f == 0.f ? 0.f : f;
  }
  out = v;
  return true;
}

std::string formatFloat(double value) {
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value);
  (void)ec;
  return std::string(buf, ptr);
}

std::string formatVec3(const Vec3& v) {
  auto f = [](float x) {
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, x);
    (void)ec;
    return std::string(buf, ptr);
  };
  return f(v.x) + ", " + f(v.y) + ", " + f(v.z);
}

bool parsePropertyValue(PropertyType type, std::string_view text, Property& p) {
  switch (type) {
    case PropertyType::Boolean:
      if (!parseBooleanValue(text, p.boolValue)) return false;
      break;
    case PropertyType::Integer:
      if (!parseIntegerValue(text, p.intValue)) return false;
      break;
    case PropertyType::Float:
      if (!parseFloatValue(text, p.floatValue)) return false;
      break;
    case PropertyType::String:
      p.stringValue = std::string(text);
      break;
    case PropertyType::Point:
    case PropertyType::Vector:
      if (!parseVec3Value(text, p.vecValue, false)) return false;
      break;
    case PropertyType::Color:
      if (!parseVec3Value(text, p.vecValue, true)) return false;
      break;
    case PropertyType::Transform: {
      std::vector<double> v;
      if (!parseFloatList(text, v) || v.size() != 16) return false;
      glm::mat4 m(1.f);
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = toFloatSaturating(v[r * 4 + c]);
      p.matrix = m;
      break;
    }
  }
  p.type = type;
  return true;
}

std::string Property::valueText() const {
  switch (type) {
    case PropertyType::Boolean:
      return boolValue ? "true" : "false";
    case PropertyType::Integer:
      return std::to_string(intValue);
    case PropertyType::Float:
      return formatFloat(floatValue);
    case PropertyType::String:
      return stringValue;
    case PropertyType::Point:
    case PropertyType::Vector:
    case PropertyType::Color:
      return formatVec3(vecValue);
    case PropertyType::Transform: {
      std::string s;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          if (!s.empty()) s += ' ';
          s += formatFloat(matrix[c][r]);
        }
      return s;
    }
  }
  return {};
}

// ---- PropertyList --------------------------------------------------------------------------------

void PropertyList::setContext(std::string file, std::string tag, std::string type) {
  file_ = std::move(file);
  tag_ = std::move(tag);
  type_ = std::move(type);
}

std::string PropertyList::owner() const {
  if (tag_.empty()) return "the object";
  if (type_.empty()) return "<" + tag_ + ">";
  return "<" + tag_ + " type=\"" + type_ + "\">";
}

void PropertyList::add(Property p) {
  for (const Property& q : props_) {
    if (q.name == p.name) {
      std::string where = q.line > 0 ? " (first defined at line " + std::to_string(q.line) + ")" : "";
      throw Error(file_, p.line,
                  "property \"" + p.name + "\" of " + owner() + " is defined twice" + where +
                      "; expected each property name at most once");
    }
  }
  props_.push_back(std::move(p));
}

const Property* PropertyList::find(std::initializer_list<std::string_view> names) const {
  return find(std::span<const std::string_view>(names.begin(), names.size()));
}

const Property* PropertyList::find(std::span<const std::string_view> names) const {
  for (std::string_view n : names)
    for (const Property& p : props_)
      if (p.name == n) return &p;
  return nullptr;
}

const Property* PropertyList::lookup(std::span<const std::string_view> names) const {
  const Property* found = nullptr;
  for (std::string_view n : names) {
    for (const Property& p : props_) {
      if (p.name != n) continue;
      if (found && found != &p) {
        throw Error(file_, p.line,
                    "properties \"" + found->name + "\" (line " + std::to_string(found->line) + ") and \"" +
                        p.name + "\" of " + owner() +
                        " are spellings of the same setting; expected only one of them");
      }
      found = &p;
    }
  }
  if (found) found->used = true;
  return found;
}

Error PropertyList::errorAt(const Property& p, const std::string& message) const {
  if (!p.setBy.empty()) return Error(p.setBy + ": " + message);
  return Error(file_, p.line, message);
}

void PropertyList::typeError(const Property& p, const char* expected) const {
  std::string got = std::string(propertyTypeName(p.type)) + " " + quoted(p.valueText());
  if (!p.setBy.empty())
    throw errorAt(p, "property \"" + p.name + "\" of " + owner() + ": expected " + expected + ", got " + got);
  throw Error(file_, p.line,
              "<" + std::string(propertyTypeName(p.type)) + " name=\"" + p.name + "\"> of " + owner() +
                  ": expected " + expected + ", got " + got);
}

bool PropertyList::has(std::initializer_list<std::string_view> names) const {
  return find(names) != nullptr;
}

int PropertyList::lineOf(std::initializer_list<std::string_view> names) const {
  const Property* p = find(names);
  return p ? p->line : 0;
}

int PropertyList::lineOf(std::span<const std::string_view> names) const {
  const Property* p = find(names);
  return p ? p->line : 0;
}

void PropertyList::markUsed(std::initializer_list<std::string_view> names) const {
  for (std::string_view n : names)
    for (const Property& p : props_)
      if (p.name == n) p.used = true;
}

bool PropertyList::getBoolean(std::initializer_list<std::string_view> names, bool def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  if (p->type != PropertyType::Boolean) typeError(*p, "a boolean");
  return p->boolValue;
}

int64_t PropertyList::getInteger(std::initializer_list<std::string_view> names, int64_t def) const {
  return getInteger(std::span<const std::string_view>(names.begin(), names.size()), def);
}

int64_t PropertyList::getInteger(std::span<const std::string_view> names, int64_t def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  if (p->type != PropertyType::Integer) typeError(*p, "an integer");
  return p->intValue;
}

float PropertyList::getFloat(std::initializer_list<std::string_view> names, float def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  double v;
  if (p->type == PropertyType::Float)
    v = p->floatValue;
  else if (p->type == PropertyType::Integer)
    v = static_cast<double>(p->intValue);
  else
    typeError(*p, "a float");
  float f = toFloatSaturating(v);
  if (!std::isfinite(f))
    throw errorAt(*p, "property \"" + p->name + "\" of " + owner() +
                          ": expected a value in float range, got " + p->valueText());
  return f;
}

std::string PropertyList::getString(std::span<const std::string_view> names, const std::string& def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  if (p->type != PropertyType::String) typeError(*p, "a string");
  return p->stringValue;
}

std::string PropertyList::getString(std::initializer_list<std::string_view> names,
                                    const std::string& def) const {
  return getString(std::span<const std::string_view>(names.begin(), names.size()), def);
}

namespace {
// A string added by an override may be read as a structured type if its text parses.
bool overrideAs(const Property& p, PropertyType want, Property& tmp) {
  return p.fromOverride && p.type == PropertyType::String && parsePropertyValue(want, p.stringValue, tmp);
}
}  // namespace

Vec3 PropertyList::getPoint(std::initializer_list<std::string_view> names, const Vec3& def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  Property tmp;
  if (overrideAs(*p, PropertyType::Point, tmp)) return tmp.vecValue;
  if (p->type != PropertyType::Point) typeError(*p, "a point");
  return p->vecValue;
}

Vec3 PropertyList::getVector(std::initializer_list<std::string_view> names, const Vec3& def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  Property tmp;
  if (overrideAs(*p, PropertyType::Vector, tmp)) return tmp.vecValue;
  if (p->type != PropertyType::Vector) typeError(*p, "a vector");
  return p->vecValue;
}

Vec3 PropertyList::getColor(std::initializer_list<std::string_view> names, const Vec3& def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  Property tmp;
  if (overrideAs(*p, PropertyType::Color, tmp)) return tmp.vecValue;
  if (p->type == PropertyType::Color) return p->vecValue;
  if (p->type == PropertyType::Float || p->type == PropertyType::Integer) {
    double v = p->type == PropertyType::Float ? p->floatValue : static_cast<double>(p->intValue);
    float f = toFloatSaturating(v);
    if (std::isfinite(f)) return Vec3(f);
  }
  typeError(*p, "a color");
}

glm::mat4 PropertyList::getTransform(std::initializer_list<std::string_view> names,
                                     const glm::mat4& def) const {
  const Property* p = lookup(names);
  if (!p) return def;
  Property tmp;
  if (overrideAs(*p, PropertyType::Transform, tmp)) return tmp.matrix;
  if (p->type != PropertyType::Transform) typeError(*p, "a transform");
  return p->matrix;
}

std::vector<std::string> PropertyList::unusedWarnings() const {
  std::vector<std::string> out;
  for (const Property& p : props_) {
    if (p.used) continue;
    std::string where = file_.empty() ? std::string() : file_ + ":";
    if (p.line > 0) where += std::to_string(p.line) + ":";
    if (!where.empty()) where += " ";
    out.push_back(where + "warning: property \"" + p.name + "\" of " + owner() + " is not used");
  }
  return out;
}

void PropertyList::set(std::string_view name, std::string_view value, std::string setBy) {
  for (Property& p : props_) {
    if (p.name != name) continue;
    // A property added by an earlier override has no type from the file: infer again below.
    if (p.fromOverride) break;
    Property parsed = p;
    if (!parsePropertyValue(p.type, value, parsed)) {
      const std::string expected = std::string(p.type == PropertyType::Integer ? "an " : "a ") +
                                   propertyTypeName(p.type) + " like the value in the file";
      if (!setBy.empty())
        throw Error(setBy + ": cannot set property \"" + p.name + "\" of " + owner() + " to " +
                    quoted(value) + ": expected " + expected + " (" + file_ + ":" + std::to_string(p.line) +
                    ")");
      throw Error(file_, p.line,
                  "cannot set property \"" + p.name + "\" of " + owner() + " to " + quoted(value) +
                      ": expected " + expected);
    }
    parsed.setBy = std::move(setBy);
    parsed.hasLookAt = false;  // a transform set from text is a matrix
    p = std::move(parsed);
    return;
  }
  Property p;
  p.name = std::string(name);
  p.line = 0;
  p.fromOverride = true;
  p.setBy = std::move(setBy);
  if (!parsePropertyValue(PropertyType::Boolean, value, p) &&
      !parsePropertyValue(PropertyType::Integer, value, p) &&
      !parsePropertyValue(PropertyType::Float, value, p)) {
    parsePropertyValue(PropertyType::String, value, p);
  }
  for (Property& q : props_) {
    if (q.name == name) {
      q = std::move(p);
      return;
    }
  }
  props_.push_back(std::move(p));
}

}  // namespace penumbra
