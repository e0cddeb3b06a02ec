// Typed scene properties as in Nori's XML (<integer name="sampleCount" value="4"/> ...), with strict
// value parsing, alias-aware typed getters, unused-property warnings and string overrides (--set).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/math/error.h"
#include "core/math/vec.h"

namespace penumbra {

enum class PropertyType : uint8_t { Boolean, Integer, Float, String, Point, Vector, Color, Transform };

// XML tag name of a property type ("boolean", "integer", ...).
const char* propertyTypeName(PropertyType type);
// Inverse of propertyTypeName; false for an unknown tag.
bool parsePropertyType(std::string_view tag, PropertyType& out);

// Strict value parsers shared by the XML reader and PropertyList::set. They return false on any
// malformed input; callers turn that into an Error with file and line.
// Integers: plain base-10, optional sign, must fit int64 ("3.5", "1e3", "4abc" fail).
bool parseIntegerValue(std::string_view text, int64_t& out);
// Floats: decimal or scientific, optional sign; nan, inf and overflow (1e999) fail; -0 becomes +0.
bool parseFloatValue(std::string_view text, double& out);
// Booleans: exactly "true" or "false".
bool parseBooleanValue(std::string_view text, bool& out);
// Three floats separated by commas and/or whitespace ("1, 2, 3", "1 2 3", "1,2,3").
// With allowScalar (colors), a single value v is accepted as (v, v, v).
bool parseVec3Value(std::string_view text, Vec3& out, bool allowScalar = false);
// Any number of floats separated by commas and/or whitespace.
bool parseFloatList(std::string_view text, std::vector<double>& out);
// Shortest text that parses back to the same value (used by writers and messages).
std::string formatFloat(double value);
std::string formatVec3(const Vec3& v);

struct Property {
  std::string name;
  PropertyType type = PropertyType::String;
  bool boolValue = false;
  int64_t intValue = 0;
  double floatValue = 0.0;
  std::string stringValue;
  Vec3 vecValue{0.f};     // point, vector, color
  glm::mat4 matrix{1.f};  // transform
  // A transform containing <lookat>: its target and up, carried through the operations after it (the
  // viewer orbits about the target the scene names).
  bool hasLookAt = false;
  Vec3 lookAtTarget{0.f}, lookAtUp{0.f, 1.f, 0.f};
  // With hasLookAt: the <lookat> origin, carried like the target. writeSceneXml writes the transform
  // as that <lookat> when the matrix is exactly it (nothing but the <lookat> built it).
  Vec3 lookAtOrigin{0.f};
  int line = 0;  // 0 when added by an override (--set) rather than the file
  mutable bool used = false;
  bool fromOverride = false;  // added by set() (not in the file): its type was inferred from the text
  // "--set sampler.sampleCount=0" when an override gave the value: errors about the value name it
  // instead of the line of the file.
  std::string setBy;

  // The value as it would appear in a value="..." attribute (transforms: 16 numbers, row-major).
  std::string valueText() const;
};

class PropertyList {
 public:
  PropertyList() = default;
  // Where the properties come from, for messages: file name and the owning element's tag and type.
  void setContext(std::string file, std::string tag, std::string type);
  const std::string& file() const { return file_; }

  // Adds a property; a second property with the same name is an error reported at p.line.
  void add(Property p);

  // Typed getters. `names` lists accepted spellings (aliases), first match wins; giving two
  // spellings of the same property is an error. Absent → `def`. Present with the wrong type → Error
  // with file:line. Every getter marks the property it read as used.
  bool getBoolean(std::initializer_list<std::string_view> names, bool def) const;
  int64_t getInteger(std::initializer_list<std::string_view> names, int64_t def) const;
  // An integer property is accepted where a float is wanted. Values outside float range are errors.
  float getFloat(std::initializer_list<std::string_view> names, float def) const;
  std::string getString(std::initializer_list<std::string_view> names, const std::string& def) const;
  // The same getters for a list of spellings kept as data (the strategy and sampler tables).
  std::string getString(std::span<const std::string_view> names, const std::string& def) const;
  int64_t getInteger(std::span<const std::string_view> names, int64_t def) const;
  Vec3 getPoint(std::initializer_list<std::string_view> names, const Vec3& def) const;
  Vec3 getVector(std::initializer_list<std::string_view> names, const Vec3& def) const;
  // A color may also be written as a single grey value (value="0.5"); an integer or float property
  // is accepted as grey too.
  Vec3 getColor(std::initializer_list<std::string_view> names, const Vec3& def) const;
  glm::mat4 getTransform(std::initializer_list<std::string_view> names, const glm::mat4& def) const;

  bool has(std::initializer_list<std::string_view> names) const;
  // Source line of the property (0 when absent or when it came from an override).
  int lineOf(std::initializer_list<std::string_view> names) const;
  int lineOf(std::span<const std::string_view> names) const;
  // The property under any of the names, or nullptr. Does not mark it used.
  const Property* find(std::initializer_list<std::string_view> names) const;
  const Property* find(std::span<const std::string_view> names) const;
  // Marks a property as used without reading it through a typed getter.
  void markUsed(std::initializer_list<std::string_view> names) const;

  // "file:line: warning: property "x" of <tag type="y"> is not used", one per unread property.
  std::vector<std::string> unusedWarnings() const;

  // Override from a string (--set key=value). An existing property keeps its type and the value
  // must parse as that type (else Error naming `setBy`, or the property's line without it). A new
  // property's type is inferred: true/false → boolean, integer literal → integer, float literal →
  // float, else string. A new string property is also accepted by the point/vector/color/transform
  // getters when its text parses as that type. `setBy` ("--set sampler.sampleCount=0") is kept
  // with the property, so later errors about its value name the override.
  void set(std::string_view name, std::string_view value, std::string setBy = {});

  // An Error about a property's value, located where the value came from: the --set override that
  // gave it, else its line in the file.
  Error errorAt(const Property& p, const std::string& message) const;

  const std::vector<Property>& properties() const { return props_; }
  size_t size() const { return props_.size(); }
  bool empty() const { return props_.empty(); }

 private:
  const Property* lookup(std::span<const std::string_view> names) const;
  const Property* lookup(std::initializer_list<std::string_view> names) const {
    return lookup(std::span<const std::string_view>(names.begin(), names.size()));
  }
  std::string owner() const;
  [[noreturn]] void typeError(const Property& p, const char* expected) const;

  std::vector<Property> props_;
  std::string file_;
  std::string tag_;
  std::string type_;
};

// Parses `text` as a value of `type` into p (p.type is set). Returns false if it does not parse.
// Transforms take 16 numbers, row-major.
bool parsePropertyValue(PropertyType type, std::string_view text, Property& p);

}  // namespace penumbra
