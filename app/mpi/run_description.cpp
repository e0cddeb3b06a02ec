#include "app/mpi/run_description.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <unordered_map>

#include "core/math/error.h"
#include "core/render/filter.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/property.h"
#include "core/scene/xml_parser.h"

namespace penumbra::mpi {

namespace {

constexpr uint64_t kFnvOffset = 1469598103934665603ull, kFnvPrime = 1099511628211ull;

void fnv(uint64_t& h, const char* data, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    h ^= uint8_t(data[i]);
    h *= kFnvPrime;
  }
}

std::string hex16(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)h);
  return buf;
}

// "fnv1a64 <hex>, <n> bytes" of the file, or why it could not be read.
std::string fileContentsValue(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::string("unreadable (") + std::strerror(errno) + ")";
  uint64_t h = kFnvOffset, size = 0;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    const size_t n = size_t(in.gcount());
    fnv(h, buffer, n);
    size += n;
  }
  return "fnv1a64 " + hex16(h) + ", " + std::to_string(size) + " bytes";
}

std::string placeOf(const SceneNode& node, int line) {
  if (line <= 0) return "--set";
  return node.file + ":" + std::to_string(line);
}

// One entry for the object (its type), then its properties by name (the order in the file does not
// change the scene), then the contents of the file it names, then its children in document order.
// An object is named by its tag, numbered from the second of a tag on in document order (depth
// first), as --set counts: "emitter" is the first emitter, "shape#3" the third shape.
void describeNode(const SceneNode& node, std::map<std::string, int>& seen, RunDescription& out) {
  const int n = ++seen[node.tag];
  const std::string label = n == 1 ? node.tag : node.tag + "#" + std::to_string(n);
  out.push_back({label, node.type, placeOf(node, node.line), true});
  std::vector<const Property*> props;
  for (const Property& p : node.props.properties()) props.push_back(&p);
  std::sort(props.begin(), props.end(),
            [](const Property* a, const Property* b) { return a->name < b->name; });
  for (const Property* p : props) {
    const std::string where = placeOf(node, p->line);
    out.push_back({label + "." + p->name, p->valueText(), where, true});
    out.push_back({label + "." + p->name + " (type)", propertyTypeName(p->type), where, true});
    if (p->name == "filename" && p->type == PropertyType::String) {
      const std::string path = resolveScenePath(node, p->stringValue);
      out.push_back({label + ".filename (contents)", fileContentsValue(path), where + ", " + path, true});
    }
  }
  for (const SceneNode& child : node.children) describeNode(child, seen, out);
}

void putField(std::string& out, const std::string& field) {
  out += std::to_string(field.size());
  out += ':';
  out += field;
}

std::string takeField(const std::string& bytes, size_t& at) {
  const size_t colon = bytes.find(':', at);
  if (colon == std::string::npos) throw Error("run description: malformed field length");
  const size_t length = std::stoull(bytes.substr(at, colon - at));
  if (colon + 1 + length > bytes.size()) throw Error("run description: truncated field");
  std::string field = bytes.substr(colon + 1, length);
  at = colon + 1 + length;
  return field;
}

std::string phrase(const RunSetting& s, const std::string& mine, const std::string& root) {
  if (!s.inScene) return " on " + s.name + ": " + mine + " vs " + root;
  return ": the resolved scene differs at " + s.name + (s.where.empty() ? "" : " (" + s.where + ")") + ": " +
         mine + " vs " + root;
}

}  // namespace

RunDescription describeRun(const RenderSettings& s, const RunChoices& c, const SceneNode& scene) {
  RunDescription d;
  auto add = [&d](std::string name, std::string value) {
    d.push_back({std::move(name), std::move(value), "", false});
  };
  add("camera.width", std::to_string(s.camera.width));
  add("camera.height", std::to_string(s.camera.height));
  add("spp", c.targetSpp > 0 ? std::to_string(c.targetSpp) : "none (until the time limit)");
  add("time", c.seconds > 0 ? formatFloat(c.seconds) + " s" : "none");
  add("block", std::to_string(c.block));
  add("seed", std::to_string(s.seed));
  add("sampler.type", samplerKindName(s.samplerKind));
  add("sampler.sampleCount", std::to_string(s.sampleCount));
  add("integrator", std::string(nameOf(s.integrator.type)));
  for (const CanonicalProperty& p : canonicalProperties(s.integrator))
    add("integrator." + std::string(p.name), p.value);
  add("rfilter", filterTypeName(s.filter.type));
  add("reference", c.reference ? "yes" : "no");
  add("output format", c.outputFormat);
  std::map<std::string, int> seen;
  describeNode(scene, seen, d);
  return d;
}

uint64_t digestOf(const RunDescription& description) {
  uint64_t h = kFnvOffset;
  for (const RunSetting& s : description) {
    fnv(h, s.name.c_str(), s.name.size() + 1);  // with the terminating NUL: "ab","c" differs from "a","bc"
    fnv(h, s.value.c_str(), s.value.size() + 1);
  }
  return h;
}

std::string serialize(const RunDescription& description) {
  std::string out;
  for (const RunSetting& s : description) {
    putField(out, s.name);
    putField(out, s.value);
    putField(out, s.where);
    out += s.inScene ? '1' : '0';
  }
  return out;
}

RunDescription deserialize(const std::string& bytes) {
  RunDescription d;
  for (size_t at = 0; at < bytes.size();) {
    RunSetting s;
    s.name = takeField(bytes, at);
    s.value = takeField(bytes, at);
    s.where = takeField(bytes, at);
    if (at >= bytes.size()) throw Error("run description: truncated entry");
    s.inScene = bytes[at++] == '1';
    d.push_back(std::move(s));
  }
  return d;
}

std::string firstDifference(const RunDescription& mine, const RunDescription& root) {
  std::unordered_map<std::string, const RunSetting*> mineByName, rootByName;
  for (const RunSetting& s : mine) mineByName.emplace(s.name, &s);
  for (const RunSetting& s : root) rootByName.emplace(s.name, &s);
  for (const RunSetting& r : root) {
    const auto it = mineByName.find(r.name);
    if (it == mineByName.end()) return phrase(r, "(absent)", r.value);
    if (it->second->value != r.value) return phrase(r, it->second->value, r.value);
  }
  for (const RunSetting& m : mine)
    if (!rootByName.count(m.name)) return phrase(m, m.value, "(absent)");
  return "";
}

}  // namespace penumbra::mpi
