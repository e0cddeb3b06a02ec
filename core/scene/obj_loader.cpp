#include "core/scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "core/math/error.h"

namespace penumbra {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> splitWs(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string t;
  while (in >> t) out.push_back(t);
  return out;
}

bool finiteNumber(const std::string& t) {
  const char* b = t.c_str();
  char* e = nullptr;
  double v = std::strtod(b, &e);
  return e != b && *e == '\0' && std::isfinite(v) && std::isfinite(static_cast<float>(v));
}

// Checks what tinyobjloader does not report with a line number: non-finite coordinates and face
// indices outside the vertex/normal arrays. Returns the number of face lines.
size_t prescan(const std::string& path, std::istream& in) {
  struct FaceRef {
    int line;
    long v, vn;
  };
  std::vector<FaceRef> forward;  // positive indices checked once all vertices are known
  long nv = 0, nvn = 0, nvt = 0;
  size_t faces = 0;
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    std::vector<std::string> tok = splitWs(line);
    if (tok.empty() || tok[0][0] == '#') continue;
    const std::string& k = tok[0];
    if (k == "v" || k == "vn") {
      if (tok.size() < 4)
        throw Error(path, lineNo,
                    "'" + k + "': expected 3 coordinates, got " + std::to_string(tok.size() - 1));
      for (int i = 1; i <= 3; ++i)
        if (!finiteNumber(tok[i]))
          throw Error(path, lineNo, "'" + k + "': expected finite numbers, got \"" + tok[i] + "\"");
      (k == "v" ? nv : nvn)++;
    } else if (k == "vt") {
      ++nvt;  // texture coordinates are not used; the assignment's plane.obj has a malformed "vt 1.0 " line
    } else if (k == "f") {
      if (tok.size() < 4)
        throw Error(path, lineNo,
                    "face with " + std::to_string(tok.size() - 1) + " vertices: expected at least 3");
      ++faces;
      for (size_t i = 1; i < tok.size(); ++i) {
        const std::string& t = tok[i];
        long idx[3] = {0, 0, 0};
        long counts[3] = {nv, nvt, nvn};
        const char* what[3] = {"vertex", "texture coordinate", "normal"};
        size_t pos = 0;
        for (int part = 0; part < 3 && pos <= t.size(); ++part) {
          size_t slash = t.find('/', pos);
          std::string s = t.substr(pos, slash == std::string::npos ? std::string::npos : slash - pos);
          if (!s.empty()) {
            char* e = nullptr;
            long v = std::strtol(s.c_str(), &e, 10);
            if (*e != '\0') throw Error(path, lineNo, "face corner \"" + t + "\": expected integer indices");
            if (v == 0)
              throw Error(path, lineNo, "face corner \"" + t + "\": index 0 (OBJ indices start at 1)");
            if (v < 0) {
              if (-v > counts[part])
                throw Error(path, lineNo,
                            "face corner \"" + t + "\": relative " + what[part] + " index " +
                                std::to_string(v) + " but only " + std::to_string(counts[part]) +
                                " defined so far");
              v = counts[part] + v + 1;
            }
            idx[part] = v;
          } else if (part == 0) {
            throw Error(path, lineNo, "face corner \"" + t + "\": expected a vertex index");
          }
          if (slash == std::string::npos) break;
          pos = slash + 1;
        }
        forward.push_back({lineNo, idx[0], idx[2]});
      }
    }
  }
  for (const FaceRef& f : forward) {
    if (f.v > nv)
      throw Error(path, f.line,
                  "vertex index " + std::to_string(f.v) + " out of range: the file has " +
                      std::to_string(nv) + " vertices");
    if (f.vn > nvn)
      throw Error(path, f.line,
                  "normal index " + std::to_string(f.vn) + " out of range: the file has " +
                      std::to_string(nvn) + " normals");
  }
  return faces;
}

struct PairHash {
  size_t operator()(const std::pair<int, int>& p) const {
    return std::hash<int64_t>()((static_cast<int64_t>(p.first) << 32) ^ static_cast<uint32_t>(p.second));
  }
};

}  // namespace

TriangleMesh loadObjMesh(const std::string& path, const glm::mat4& toWorld, const std::string& sceneFile,
                         int sceneLine, ObjLoadStats* statsOut) {
  ObjLoadStats localStats;
  ObjLoadStats& stats = statsOut ? *statsOut : localStats;
  stats = ObjLoadStats{};

  std::ifstream file(path, std::ios::binary);
  if (!file || fs::is_directory(path)) {
    std::error_code ec;
    fs::path abs = fs::absolute(path, ec);
    throw Error(sceneFile, sceneLine,
                "cannot open mesh file '" + fs::path(path).filename().string() + "' (resolved to " +
                    (ec ? path : abs.lexically_normal().string()) + ")");
  }
  size_t faceLines = prescan(path, file);
  if (faceLines == 0) throw Error(path, 0, "expected at least one face ('f' line), found none");

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::string dir = fs::path(path).parent_path().string();
  if (!dir.empty()) dir += '/';
  bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, path.c_str(), dir.c_str(), true);
  if (!ok || !err.empty()) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw Error(path, 0, "malformed OBJ: " + (err.empty() ? std::string("unknown error") : err));
  }
  std::istringstream warnLines(warn);
  for (std::string w; std::getline(warnLines, w);)
    if (!w.empty()) stats.warnings.push_back(path + ": warning: " + w);

  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(toWorld)));
  const size_t nv = attrib.vertices.size() / 3;
  const size_t nn = attrib.normals.size() / 3;

  // Collect triangles as index triples (tinyobj triangulated every face).
  std::vector<tinyobj::index_t> corners;
  for (const tinyobj::shape_t& s : shapes) {
    size_t offset = 0;
    for (unsigned char fv : s.mesh.num_face_vertices) {
      if (fv != 3) throw Error(path, 0, "face with " + std::to_string(fv) + " vertices after triangulation");
      for (int k = 0; k < 3; ++k) corners.push_back(s.mesh.indices[offset + k]);
      offset += fv;
    }
  }
  stats.inputTriangles = corners.size() / 3;
  bool allNormals = nn > 0;
  for (const tinyobj::index_t& c : corners) {
    if (c.vertex_index < 0 || static_cast<size_t>(c.vertex_index) >= nv)
      throw Error(path, 0, "vertex index out of range after parsing");
    if (c.normal_index < 0 || static_cast<size_t>(c.normal_index) >= nn) allNormals = false;
  }
  if (nn > 0 && !allNormals) {
    stats.normalsDropped = true;
    stats.warnings.push_back(path + ": warning: only some face corners have normals; ignoring all normals");
  }

  TriangleMesh mesh;
  std::unordered_map<std::pair<int, int>, uint32_t, PairHash> remap;
  auto worldPos = [&](const tinyobj::index_t& c) -> Vec3 {
    const float* p = &attrib.vertices[3 * static_cast<size_t>(c.vertex_index)];
    glm::vec4 w = toWorld * glm::vec4(p[0], p[1], p[2], 1.f);
    Vec3 pos = w.w != 1.f && w.w != 0.f ? Vec3(w) / w.w : Vec3(w);
    if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z))
      throw Error(sceneFile, sceneLine, "mesh '" + path + "': transformed vertex is not finite");
    return pos;
  };
  auto vertexOf = [&](const tinyobj::index_t& c) -> uint32_t {
    std::pair<int, int> key(c.vertex_index, allNormals ? c.normal_index : -1);
    auto it = remap.find(key);
    if (it != remap.end()) return it->second;
    Vec3 pos = worldPos(c);
    uint32_t index = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(pos);
    if (allNormals) {
      const float* n = &attrib.normals[3 * static_cast<size_t>(c.normal_index)];
      Vec3 wn = normalMatrix * Vec3(n[0], n[1], n[2]);
      float len = glm::length(wn);
      mesh.normals.push_back(len > 0.f && std::isfinite(len) ? wn / len : Vec3(0.f));
    }
    remap.emplace(key, index);
    return index;
  };

  for (size_t t = 0; t < corners.size(); t += 3) {
    const tinyobj::index_t &a = corners[t], &b = corners[t + 1], &c = corners[t + 2];
    if (a.vertex_index == b.vertex_index || b.vertex_index == c.vertex_index ||
        a.vertex_index == c.vertex_index) {
      ++stats.droppedDegenerate;
      continue;
    }
    // Zero area in world space (checked before adding vertices, so none are left unreferenced).
    Vec3 pa = worldPos(a), e1 = worldPos(b) - pa, e2 = worldPos(c) - pa;
    if (!(glm::length(glm::cross(e1, e2)) > 0.f)) {
      ++stats.droppedDegenerate;
      continue;
    }
    mesh.triangles.push_back(glm::uvec3(vertexOf(a), vertexOf(b), vertexOf(c)));
  }
  if (stats.droppedDegenerate > 0)
    stats.warnings.push_back(path + ": warning: dropped " + std::to_string(stats.droppedDegenerate) +
                             " degenerate (zero-area) triangle(s)");
  if (mesh.triangles.empty())
    throw Error(path, 0,
                "expected at least one non-degenerate triangle, all " + std::to_string(stats.inputTriangles) +
                    " are degenerate");
  return mesh;
}

}  // namespace penumbra
