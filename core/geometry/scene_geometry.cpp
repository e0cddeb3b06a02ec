#include "core/geometry/scene_geometry.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "core/geometry/embree_rays.h"
#include "core/geometry/triangle.h"
#include "core/math/error.h"

namespace penumbra {
namespace {

void checkEmbree(RTCDevice device, const char* what) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE)
    throw Error(std::string("Embree: ") + what + " failed (error " + std::to_string(static_cast<int>(err)) +
                ")");
}

inline Ray rayOf(RTCRayN* rays, unsigned n, unsigned i) {
  return Ray{Vec3(RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i)),
             Vec3(RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i)),
             RTCRayN_tnear(rays, n, i), RTCRayN_tfar(rays, n, i)};
}

// The sphere's box grown by a few ulps of its coordinates: re-projected hit points, rounded to float,
// may lie half an ulp outside the box rounded from centre ± radius.
void sphereBounds(const RTCBoundsFunctionArguments* args) {
  const Sphere& s = static_cast<const Sphere*>(args->geometryUserPtr)[args->primID];
  const Bounds b = s.bounds();
  const float pad = 0x1p-20f * (maxAbsComponent(s.center) + s.radius);
  *args->bounds_o = RTCBounds{b.min.x - pad, b.min.y - pad, b.min.z - pad, 0.f,
                              b.max.x + pad, b.max.y + pad, b.max.z + pad, 0.f};
}

// User-geometry intersection: the same robust Sphere::intersect as the flat loop, so both paths
// report the same float t for the same ray.
void sphereIntersect(const RTCIntersectFunctionNArguments* args) {
  const Sphere& s = static_cast<const Sphere*>(args->geometryUserPtr)[args->primID];
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    float t;
    if (!s.intersect(rayOf(rays, args->N, i), t)) continue;
    RTCRayN_tfar(rays, args->N, i) = t;
    RTCHitN_Ng_x(hits, args->N, i) = 0.f;
    RTCHitN_Ng_y(hits, args->N, i) = 0.f;
    RTCHitN_Ng_z(hits, args->N, i) = 0.f;
    RTCHitN_u(hits, args->N, i) = 0.f;
    RTCHitN_v(hits, args->N, i) = 0.f;
    RTCHitN_primID(hits, args->N, i) = args->primID;
    RTCHitN_geomID(hits, args->N, i) = args->geomID;
    RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
  }
}

void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const OcclusionContext*>(args->context);
  if (static_cast<int32_t>(args->primID) == context->skipSphere) return;
  const Sphere& s = static_cast<const Sphere*>(args->geometryUserPtr)[args->primID];
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (s.occludes(rayOf(args->ray, args->N, i))) RTCRayN_tfar(args->ray, args->N, i) = -INFINITY;
  }
}

}  // namespace

// Embree picks the widest kernels the CPU runs: 16-wide rays (AVX-512), 8-wide (AVX, AVX2), 4-wide
// (SSE); AVX and AVX2, and SSE2 and SSE4.2, are told apart by the CPU's own flags as Embree tells them.
std::string embreeKernelIsa() {
  static const std::string isa = [] {
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) return std::string("none");
    const bool ray16 = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
    const bool ray8 = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
    rtcReleaseDevice(device);
    if (ray16) return std::string("avx512");
    if (ray8)
      return std::string(__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? "avx2" : "avx");
    return std::string(__builtin_cpu_supports("sse4.2") ? "sse4.2" : "sse2");
  }();
  return isa;
}

AccelMode sphereAccelFromEnvironment() {
  const char* value = std::getenv("PENUMBRA_SPHERE_ACCEL");
  if (!value || !*value || std::strcmp(value, "auto") == 0) return AccelMode::Auto;
  if (std::strcmp(value, "bvh") == 0) return AccelMode::Embree;
  if (std::strcmp(value, "brute-force") == 0) return AccelMode::BruteForce;
  throw Error(std::string("PENUMBRA_SPHERE_ACCEL must be auto, bvh or brute-force, got \"") + value + "\"");
}

void SceneGeometry::ReleaseEmbreeDevice::operator()(void* device) const {
  rtcReleaseDevice(static_cast<RTCDevice>(device));
}

void SceneGeometry::ReleaseEmbreeScene::operator()(void* scene) const {
  rtcReleaseScene(static_cast<RTCScene>(scene));
}

uint32_t SceneGeometry::addSphere(const Sphere& sphere, uint32_t objectId) {
  spheres_.push_back(sphere);
  sphereIds_.push_back(objectId);
  bounds_.expand(sphere.bounds());
  return static_cast<uint32_t>(spheres_.size() - 1);
}

void SceneGeometry::addMesh(const TriangleMesh& mesh, uint32_t objectId) {
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    throw Error("mesh has " + std::to_string(mesh.normals.size()) + " normals for " +
                std::to_string(mesh.positions.size()) + " vertices");
  for (const glm::uvec3& t : mesh.triangles)
    if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size())
      throw Error("mesh triangle refers to a vertex out of range");
  meshes_.push_back(mesh);
  meshIds_.push_back(objectId);
  triangleCount_ += mesh.triangles.size();
  for (const glm::uvec3& t : mesh.triangles) {
    bounds_.expand(mesh.positions[t.x]);
    bounds_.expand(mesh.positions[t.y]);
    bounds_.expand(mesh.positions[t.z]);
  }
}

void SceneGeometry::pairFlatTriangles() {
  for (uint32_t m = 0; m < meshes_.size(); ++m) {
    const TriangleMesh& mesh = meshes_[m];
    std::vector<uint32_t> leftover;
    pairParallelograms(mesh, m, quads_, leftover);
    for (uint32_t i : leftover) {
      const glm::uvec3 t = mesh.triangles[i];
      const Vec3 &p0 = mesh.positions[t.x], &p1 = mesh.positions[t.y], &p2 = mesh.positions[t.z];
      flat_.push_back({p0, p1, p2, m, i, trianglePlane(p0, p1, p2)});
    }
  }
}

void SceneGeometry::build(AccelMode mode, AccelMode sphereMode) {
  scene_.reset();
  device_.reset();
  trianglesInEmbree_ = false;
  spheresInEmbree_ = false;
  flatSphereCount_ = 0;
  quads_.clear();
  flat_.clear();
  // The flat loop's primitives: each mesh's triangles paired into parallelograms where they form
  // one, the rest one by one. Pairing is quadratic, so it is only tried where the flat loop can win.
  const bool paired = triangleCount_ > 0 && mode != AccelMode::Embree &&
                      (mode == AccelMode::BruteForce || triangleCount_ <= 2 * kBruteForceMaxPrimitives);
  if (paired) pairFlatTriangles();
  const bool useEmbree =
      triangleCount_ > 0 &&
      (mode == AccelMode::Embree ||
       (mode == AccelMode::Auto && (!paired || quads_.size() + flat_.size() > kBruteForceMaxPrimitives)));
  if (useEmbree) {
    quads_.clear();
    flat_.clear();
  }
  if (sphereMode == AccelMode::Auto) sphereMode = sphereAccelFromEnvironment();
  const bool spheresInBvh =
      !spheres_.empty() && (sphereMode == AccelMode::Embree ||
                            (sphereMode == AccelMode::Auto && spheres_.size() > kBruteForceMaxSpheres));
  if (!useEmbree && !spheresInBvh) {
    flatSphereCount_ = spheres_.size();
    return;
  }

  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) throw Error("Embree: cannot create a device");
  device_.reset(device);
  RTCScene scene = rtcNewScene(device);
  checkEmbree(device, "rtcNewScene");
  scene_.reset(scene);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  // Watertight like the flat loop (no cracks between triangles sharing an edge); costs ~15-20%.
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  for (uint32_t m = 0; useEmbree && m < meshes_.size(); ++m) {
    const TriangleMesh& mesh = meshes_[m];
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangles.size()));
    checkEmbree(device, "rtcSetNewGeometryBuffer");
    std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
    std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
    rtcCommitGeometry(geom);
    // Geometry ids are assigned sequentially from 0, so the id is the index into meshes_.
    rtcAttachGeometryByID(scene, geom, m);
    rtcReleaseGeometry(geom);
    checkEmbree(device, "attaching a mesh");
  }
  if (spheresInBvh) {
    // User geometry rather than RTC_GEOMETRY_TYPE_SPHERE_POINT: Embree's own sphere test is a float
    // quadratic, which loses small far spheres and re-hits a sphere from its own surface.
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(spheres_.size()));
    rtcSetGeometryUserData(geom, spheres_.data());  // stable: no sphere is added after build
    rtcSetGeometryBoundsFunction(geom, sphereBounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, sphereIntersect);
    rtcSetGeometryOccludedFunction(geom, sphereOccluded);
    rtcCommitGeometry(geom);
    sphereGeometryId_ = static_cast<uint32_t>(meshes_.size());
    rtcAttachGeometryByID(scene, geom, sphereGeometryId_);
    rtcReleaseGeometry(geom);
    checkEmbree(device, "attaching the spheres");
  }
  rtcCommitScene(scene);
  checkEmbree(device, "rtcCommitScene");
  trianglesInEmbree_ = useEmbree;
  spheresInEmbree_ = spheresInBvh;
  flatSphereCount_ = spheresInBvh ? 0 : spheres_.size();
}

bool SceneGeometry::nearestEmbreeTriangle(const Ray& r, TriangleCandidate& c, int* sphere) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  setupRayHit(r, r.tMax, rh);
  rtcIntersect1(static_cast<RTCScene>(scene_.get()), &context, &rh);
  return readEmbreeHit(rh, c, sphere);
}

bool SceneGeometry::readEmbreeHit(const RTCRayHit& rh, TriangleCandidate& c, int* sphere) const {
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  if (spheresInEmbree_ && rh.hit.geomID == sphereGeometryId_) {
    *sphere = static_cast<int>(rh.hit.primID);
    c.isect.t = rh.ray.tfar;
    return false;
  }
  c.mesh = rh.hit.geomID;
  c.prim = rh.hit.primID;
  c.isect = {rh.ray.tfar, 1.f - rh.hit.u - rh.hit.v, rh.hit.u, rh.hit.v};
  c.flat = nullptr;
  return true;
}

bool SceneGeometry::nearestFlatTriangle(const Ray& r, TriangleCandidate& c) const {
  const TriangleRay tr(r);
  float tMax = r.tMax;
  const FlatTriangle* best = nullptr;
  auto loop = [&]<int KZ>() {
    for (const FlatTriangle& tri : flat_) {
      if (intersectTriangleK<KZ>(tr, tMax, tri.p0, tri.p1, tri.p2, c.isect)) {
        tMax = c.isect.t;
        best = &tri;
      }
    }
  };
  switch (tr.kz) {
    case 0:
      loop.template operator()<0>();
      break;
    case 1:
      loop.template operator()<1>();
      break;
    default:
      loop.template operator()<2>();
      break;
  }
  if (!best) return false;
  // intersectTriangleK writes `out` only on a hit, so c.isect holds the nearest one.
  c.mesh = best->mesh;
  c.prim = best->prim;
  c.flat = best;
  return true;
}

void SceneGeometry::nearestOutsideBvh(const Ray& ray, NearestHit& n) const {
  Ray r = ray;
  n.sphere = -1;
  n.quad = nullptr;
  n.triHit = false;
  for (size_t i = 0; i < flatSphereCount_; ++i) {
    float t;
    if (spheres_[i].intersect(r, t)) {
      r.tMax = t;
      n.sphere = static_cast<int>(i);
    }
  }
  for (const Parallelogram& q : quads_) {
    float t, u, v;
    if (intersectParallelogram(q, r, r.tMax, t, u, v)) {
      r.tMax = t;
      n.quad = &q;
      n.quadU = u;
      n.quadV = v;
    }
  }
  if (!flat_.empty() && nearestFlatTriangle(r, n.tri)) {
    n.triHit = true;
    r.tMax = n.tri.isect.t;
  }
  n.tMax = r.tMax;
}

void SceneGeometry::takeBvhAnswer(bool triangle, int bvhSphere, const TriangleCandidate& c, NearestHit& n) {
  if (triangle) {
    n.tri = c;
    n.triHit = true;
  } else if (bvhSphere >= 0) {
    n.sphere = bvhSphere;
    n.tMax = c.isect.t;
    n.triHit = false;
    n.quad = nullptr;
  }
}

bool SceneGeometry::fillNearestHit(const Ray& ray, const NearestHit& n, SurfaceHit& hit) const {
  if (n.triHit) {
    // Embree hits keep offsets relative to the triangle's coordinates (its t carries that error);
    // brute-force hits are projected and offset relative to |p| (see projectOntoPlane).
    fillTriangleHit(meshes_[n.tri.mesh], n.tri.prim, n.tri.isect, meshIds_[n.tri.mesh], hit);
    if (n.tri.flat) projectOntoPlane(n.tri.flat->plane, hit);
    return true;
  }
  if (n.quad) {
    fillParallelogramHit(*n.quad, ray, n.tMax, n.quadU, n.quadV, meshIds_[n.quad->mesh], hit);
    return true;
  }
  if (n.sphere >= 0) {
    spheres_[n.sphere].fillHit(ray, n.tMax, sphereIds_[n.sphere], hit);
    return true;
  }
  return false;
}

bool SceneGeometry::intersect(const Ray& ray, SurfaceHit& hit) const {
  NearestHit n;
  nearestOutsideBvh(ray, n);
  if (scene_) {
    TriangleCandidate c;
    int bvhSphere = -1;
    const bool triangle = nearestEmbreeTriangle(Ray{ray.o, ray.d, ray.tMin, n.tMax}, c, &bvhSphere);
    takeBvhAnswer(triangle, bvhSphere, c, n);
  }
  return fillNearestHit(ray, n, hit);
}

// Embree reports a ray through the edge shared by two triangles on whichever it meets first, and a
// stream meets them in another order than rtcIntersect1; a hit whose barycentric is within this of 0
// is asked again alone, so that the answer is intersect()'s.
constexpr float kStreamEdgeBarycentric = 0x1p-12f;

void SceneGeometry::intersectMany(const Ray* rays, size_t n, SurfaceHit* hits, bool* found,
                                  Coherence coherence) const {
  for (size_t first = 0; first < n; first += kIntersectManyRays) {
    const size_t count = std::min(kIntersectManyRays, n - first);
    NearestHit nearest[kIntersectManyRays];
    for (size_t i = 0; i < count; ++i) nearestOutsideBvh(rays[first + i], nearest[i]);
    if (scene_) {
      RTCRayHit stream[kIntersectManyRays];
      for (size_t i = 0; i < count; ++i) setupRayHit(rays[first + i], nearest[i].tMax, stream[i]);
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = coherence == Coherence::Coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                       : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      rtcIntersect1M(static_cast<RTCScene>(scene_.get()), &context, stream, unsigned(count),
                     sizeof(RTCRayHit));
      for (size_t i = 0; i < count; ++i) {
        TriangleCandidate c;
        int bvhSphere = -1;
        bool triangle = readEmbreeHit(stream[i], c, &bvhSphere);
        if (triangle && std::min({c.isect.b0, c.isect.b1, c.isect.b2}) < kStreamEdgeBarycentric) {
          bvhSphere = -1;
          const Ray& ray = rays[first + i];
          triangle = nearestEmbreeTriangle(Ray{ray.o, ray.d, ray.tMin, nearest[i].tMax}, c, &bvhSphere);
        }
        takeBvhAnswer(triangle, bvhSphere, c, nearest[i]);
      }
    }
    for (size_t i = 0; i < count; ++i)
      found[first + i] = fillNearestHit(rays[first + i], nearest[i], hits[first + i]);
  }
}

bool SceneGeometry::occluded(const Ray& ray, int32_t skipSphere) const {
  if (occludedByFlatShapes(ray, skipSphere)) return true;
  // An empty segment (a light closer than the origin's offset) is blocked by nothing; Embree would
  // hand back its negative tfar, which reads as a hit below.
  if (scene_ && ray.tMax > ray.tMin) {
    OcclusionContext context;
    rtcInitIntersectContext(&context.base);
    context.skipSphere = skipSphere;
    RTCRay r;
    setupRay(ray, ray.tMax, r);
    rtcOccluded1(static_cast<RTCScene>(scene_.get()), &context.base, &r);
    if (r.tfar < 0.f) return true;  // Embree sets tfar = -inf on a hit
  }
  return occludedByFlatTriangles(ray);
}

void SceneGeometry::occludedMany(const Ray* rays, const bool* active, size_t n, int32_t skipSphere,
                                 bool* blocked) const {
  RTCRay bvh[kOccludedManyRays];
  size_t query[kOccludedManyRays];
  size_t queued = 0;
  for (size_t i = 0; i < n; ++i) {
    blocked[i] = false;
    if (!active[i]) continue;
    const Ray& ray = rays[i];
    // occluded()'s tests, the BVH's deferred (the flat triangles' come first here: the answer is the same).
    if (occludedByFlatShapes(ray, skipSphere) || occludedByFlatTriangles(ray)) {
      blocked[i] = true;
      continue;
    }
    if (!scene_ || !(ray.tMax > ray.tMin)) continue;
    setupRay(ray, ray.tMax, bvh[queued]);
    query[queued++] = i;
  }
  if (queued == 0) return;
  OcclusionContext context;
  rtcInitIntersectContext(&context.base);
  context.skipSphere = skipSphere;
  rtcOccluded1M(static_cast<RTCScene>(scene_.get()), &context.base, bvh, unsigned(queued), sizeof(RTCRay));
  for (size_t q = 0; q < queued; ++q)
    if (bvh[q].tfar < 0.f) blocked[query[q]] = true;  // Embree sets tfar = -inf on a hit
}

bool SceneGeometry::occludedByFlatShapes(const Ray& ray, int32_t skipSphere) const {
  for (size_t i = 0; i < flatSphereCount_; ++i)
    if (static_cast<int32_t>(i) != skipSphere && spheres_[i].occludes(ray)) return true;
  for (const Parallelogram& q : quads_) {
    float t, u, v;
    if (intersectParallelogram(q, ray, ray.tMax, t, u, v)) return true;
  }
  return false;
}

bool SceneGeometry::occludedByFlatTriangles(const Ray& ray) const {
  if (flat_.empty()) return false;
  const TriangleRay tr(ray);
  auto loop = [&]<int KZ>() {
    for (const FlatTriangle& tri : flat_) {
      TriangleIntersection isect;
      if (intersectTriangleK<KZ>(tr, ray.tMax, tri.p0, tri.p1, tri.p2, isect)) return true;
    }
    return false;
  };
  switch (tr.kz) {
    case 0:
      return loop.template operator()<0>();
    case 1:
      return loop.template operator()<1>();
    default:
      return loop.template operator()<2>();
  }
}

}  // namespace penumbra
