#include "core/scene/obj_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/math/error.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

std::string writeTemp(const std::string& name, const std::string& text) {
  fs::path dir = fs::temp_directory_path() / ("penumbra_obj_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(ObjLoader, PlaneWithMalformedTexcoord) {
  // scenes/hw1's plane.obj has a "vt 1.0 " line with one component.
  ObjLoadStats stats;
  TriangleMesh m = loadObjMesh(kScenes + "hw1/Tests/plane.obj", glm::mat4(1.f), "s.xml", 3, &stats);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.normals.size(), 4u);
  for (const Vec3& n : m.normals) EXPECT_EQ(n, Vec3(0, 1, 0));
  EXPECT_EQ(stats.droppedDegenerate, 0u);
  // Surprise kept on purpose: this plane (blob d6999a0, also dev-scenes) is wound clockwise with
  // respect to its own normal, so the geometric normal is -y while the shading normal is +y. The
  // hw0/hw2 plane (blob bdc0206/fa54911) is wound counter-clockwise. We keep the file's winding.
  for (const glm::uvec3& t : m.triangles) {
    Vec3 g = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    EXPECT_LT(g.y, 0.f);
  }
  TriangleMesh other = loadObjMesh(kScenes + "hw0/Tests/plane.obj", glm::mat4(1.f), "s.xml", 3);
  for (const glm::uvec3& t : other.triangles) {
    Vec3 g =
        glm::cross(other.positions[t.y] - other.positions[t.x], other.positions[t.z] - other.positions[t.x]);
    EXPECT_GT(g.y, 0.f);
  }
}

TEST(ObjLoader, EveryAssignmentPlaneAndItsTransform) {
  for (const char* f :
       {"hw0/Tests/plane.obj", "hw0/Final/plane.obj", "hw1/Final/plane.obj", "hw2/Tests/plane.obj",
        "hw2/Finals/plane.obj", "hw2/Early-2017-08-30/Tests/plane.obj", "dev-scenes/sphere/plane.obj"}) {
    // the ground plane's transform: scale(10,1,10), rotate x 90, translate (0,0,-1) → plane z=-1, normal
    // -z...
    // :
    glm::mat4 s = glm::scale(glm::mat4(1.f), Vec3(10, 1, 10));
    glm::mat4 r = glm::rotate(glm::mat4(1.f), glm::radians(90.f), Vec3(1, 0, 0));
    glm::mat4 t = glm::translate(glm::mat4(1.f), Vec3(0, 0, -1));
    TriangleMesh m = loadObjMesh(kScenes + f, t * r * s, "s.xml", 1);
    ASSERT_EQ(m.triangles.size(), 2u) << f;
    for (const Vec3& p : m.positions) {
      EXPECT_NEAR(p.z, -1.f, 1e-5f) << f;
      EXPECT_NEAR(std::abs(p.x), 10.f, 1e-4f) << f;
    }
    ASSERT_EQ(m.normals.size(), m.positions.size()) << f;
    for (const Vec3& n : m.normals) {
      EXPECT_NEAR(n.z, 1.f, 1e-5f) << f;  // +y rotated about x by 90 → +z, normalised despite scaling
    }
  }
}

TEST(ObjLoader, NormalsUseInverseTranspose) {
  std::string p = writeTemp("slanted.obj", "v 0 0 0\nv 1 1 0\nv 0 0 1\nvn 1 -1 0\nf 1//1 2//1 3//1\n");
  TriangleMesh m = loadObjMesh(p, glm::scale(glm::mat4(1.f), Vec3(2, 1, 1)), "s.xml", 1);
  // Surface x = y scaled by 2 in x becomes x = 2y: normal ∝ (1, -2, 0).
  Vec3 expected = glm::normalize(Vec3(1, -2, 0));
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_NEAR(m.normals[0].x, expected.x, 1e-6f);
  EXPECT_NEAR(m.normals[0].y, expected.y, 1e-6f);
  EXPECT_EQ(m.positions[1], Vec3(2, 1, 0));
}

TEST(ObjLoader, SeedSphereTeapotAndCube) {
  TriangleMesh sphere = loadObjMesh(kScenes + "hw0/Tests/sphere.obj", glm::mat4(1.f), "s.xml", 1);
  EXPECT_GT(sphere.triangles.size(), 500u);
  EXPECT_EQ(sphere.normals.size(), sphere.positions.size());
  for (const Vec3& p : sphere.positions) EXPECT_NEAR(glm::length(p), 1.f, 1e-3f);

  ObjLoadStats stats;
  TriangleMesh teapot = loadObjMesh(kScenes + "hw1/Final/teapot.obj", glm::mat4(1.f), "s.xml", 1, &stats);
  EXPECT_EQ(stats.inputTriangles, 6320u);
  EXPECT_EQ(teapot.triangles.size() + stats.droppedDegenerate, 6320u);
  EXPECT_TRUE(teapot.normals.empty());

  TriangleMesh cube = loadObjMesh(kScenes + "hw2/Finals/cube.obj", glm::mat4(1.f), "s.xml", 1);
  ASSERT_EQ(cube.triangles.size(), 12u);
  ASSERT_EQ(cube.normals.size(), cube.positions.size());
  for (const glm::uvec3& t : cube.triangles) {
    Vec3 a = cube.positions[t.x], b = cube.positions[t.y], c = cube.positions[t.z];
    Vec3 g = glm::normalize(glm::cross(b - a, c - a));
    Vec3 centroid = (a + b + c) / 3.f;
    EXPECT_GT(glm::dot(g, centroid), 0.f);                    // outward winding
    EXPECT_NEAR(glm::dot(g, cube.normals[t.x]), 1.f, 1e-6f);  // matches the shading normal
    for (const Vec3& p : {a, b, c}) EXPECT_NEAR(maxComponent(glm::abs(p)), 0.5f, 0.f);  // side 1
  }
}

TEST(ObjLoader, MissingNormalsQuadsAndDegenerates) {
  std::string p = writeTemp("quad.obj",
                            "# quad and degenerate faces\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                            "f 1 2 3 4\n"
                            "f 1 1 2\n"    // repeated vertex
                            "f 1 2 5\n");  // collinear: zero area
  ObjLoadStats stats;
  TriangleMesh m = loadObjMesh(p, glm::mat4(1.f), "s.xml", 1, &stats);
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);  // vertex 5 is only used by a dropped triangle
  EXPECT_EQ(stats.inputTriangles, 4u);
  EXPECT_EQ(stats.droppedDegenerate, 2u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_FALSE(stats.warnings.empty());
}

TEST(ObjLoader, NegativeIndices) {
  std::string p = writeTemp("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
  EXPECT_EQ(loadObjMesh(p, glm::mat4(1.f), "s.xml", 1).triangles.size(), 1u);
}

TEST(ObjLoader, Errors) {
  auto expectError = [](const std::string& path, const std::string& file, int line, const std::string& text) {
    try {
      loadObjMesh(path, glm::mat4(1.f), "scene.xml", 12);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.file(), file) << e.what();
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  expectError("/nonexistent/ajax.obj", "scene.xml", 12,
              "cannot open mesh file 'ajax.obj' (resolved to /nonexistent/ajax.obj)");
  std::string bad = writeTemp("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n");
  expectError(bad, bad, 5, "vertex index 4 out of range");
  std::string zero = writeTemp("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  expectError(zero, zero, 4, "index 0");
  std::string negBad = writeTemp("negbad.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
  expectError(negBad, negBad, 3, "relative vertex index -3");
  std::string badN = writeTemp("badn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n");
  expectError(badN, badN, 5, "normal index 2 out of range");
  std::string nan = writeTemp("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError(nan, nan, 2, "finite");
  std::string inf = writeTemp("inf.obj", "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n");
  expectError(inf, inf, 2, "finite");
  std::string noFaces = writeTemp("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expectError(noFaces, noFaces, 0, "no");
  std::string allDegenerate = writeTemp("degen.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  expectError(allDegenerate, allDegenerate, 0, "degenerate");
  std::string twoCorners = writeTemp("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expectError(twoCorners, twoCorners, 3, "at least 3");
}

}  // namespace
}  // namespace penumbra
