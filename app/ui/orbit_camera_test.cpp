// OrbitControl on its own (no engine): the orbit about the scene's <lookat> target, the horizon and
// surface limits with their notes, the lookat the scene writer gets, and a camera that is no lookat.
#include "app/ui/orbit_camera.h"

#include <gtest/gtest.h>

#include "core/scene/scene_builder.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {

// A unit sphere at the origin on the floor y = -1, seen from (0, 0, 4) looking at the origin.
LoadedScene sphereOnFloor(
    const std::string& cameraTransform = "<lookat origin=\"0,0,4\" target=\"0,0,0\" up=\"0,1,0\"/>") {
  return loadSceneFromString(
      "<scene><integrator type=\"normals\"/><shape type=\"sphere\"/>"
      "<shape type=\"plane\"><transform name=\"toWorld\"><scale value=\"10,1,10\"/>"
      "<translate value=\"0,-1,0\"/></transform></shape>"
      "<camera type=\"perspective\"><transform name=\"toWorld\">" +
          cameraTransform +
          "</transform><integer name=\"width\" value=\"64\"/><integer name=\"height\" "
          "value=\"64\"/></camera></scene>",
      "sphere.xml", ".");
}

OrbitControl about(const LoadedScene& s) {
  OrbitControl o;
  o.reset(s.settings.camera, s.settings.camera, s.desc, s.scene);
  return o;
}

Vec3 originOf(const glm::mat4& m) {
  return Vec3(m[3]);
}

}  // namespace

TEST(OrbitControl, OrbitsAboutTheScenesLookatTarget) {
  const LoadedScene s = sphereOnFloor();
  OrbitControl o = about(s);
  EXPECT_EQ(o.state().target, Vec3(0.f));
  EXPECT_FLOAT_EQ(o.state().distance, 4.f);
  EXPECT_TRUE(o.state().isLookAt);
  EXPECT_FALSE(o.state().moved);
  CameraDesc cam = s.settings.camera;
  const std::optional<glm::mat4> m = o.orbit(cam, 100.f, 0.f);
  ASSERT_TRUE(m);
  EXPECT_NEAR(glm::length(originOf(*m)), 4.f, 1e-4f);  // on the sphere about the target
  EXPECT_TRUE(o.state().moved);
  cam.toWorld = *m;
  const std::optional<CameraLookAt> look = o.lookAt(cam);
  ASSERT_TRUE(look);
  EXPECT_EQ(look->origin, originOf(*m));
  EXPECT_EQ(look->target, Vec3(0.f));
  EXPECT_EQ(look->up, Vec3(0, 1, 0));
}

TEST(OrbitControl, StopsAtTheHorizonAndInFrontOfSurfaces) {
  const LoadedScene s = sphereOnFloor();
  // Pitching either way: the camera never goes under the horizon plane through the target, and
  // the way down stops there with the note.
  bool noted = false;
  for (float dy : {20.f, -20.f}) {
    OrbitControl p = about(s);
    CameraDesc cam = s.settings.camera;
    for (int i = 0; i < 200; ++i)
      if (std::optional<glm::mat4> m = p.orbit(cam, 0.f, dy)) cam.toWorld = *m;
    EXPECT_GE(originOf(cam.toWorld).y, -1e-4f);
    noted = noted || p.limitNote() == kCameraLimitNotes[0];
  }
  EXPECT_TRUE(noted);
  // Dollying in: stops in front of the sphere, with the note.
  OrbitControl d = about(s);
  CameraDesc near = s.settings.camera;
  for (int i = 0; i < 100; ++i)
    if (std::optional<glm::mat4> m = d.dolly(near, 5.f)) near.toWorld = *m;
  EXPECT_GT(originOf(near.toWorld).z, 1.f);
  EXPECT_EQ(d.limitNote(), kCameraLimitNotes[1]);
  // A free move clears the note.
  ASSERT_TRUE(d.dolly(near, -1.f));
  EXPECT_EQ(d.limitNote(), "");
}

TEST(OrbitControl, ACameraThatIsNoLookatKeepsItsRotationWhenPanned) {
  // A camera placed by a matrix: the orbit target is in front of it, and a pan moves it sideways.
  const LoadedScene s = sphereOnFloor("<translate value=\"0,0,-4\"/>");
  OrbitControl o = about(s);
  EXPECT_FALSE(o.state().isLookAt);
  EXPECT_FALSE(o.lookAt(s.settings.camera));
  const std::optional<glm::mat4> m = o.pan(s.settings.camera, 10.f, 0.f);
  ASSERT_TRUE(m);
  for (int c = 0; c < 3; ++c) EXPECT_EQ((*m)[c], s.settings.camera.toWorld[c]);
  EXPECT_NE(originOf(*m), originOf(s.settings.camera.toWorld));
  EXPECT_FALSE(o.state().isLookAt);
  // No shift at all: the camera stays.
  EXPECT_FALSE(o.pan(s.settings.camera, 0.f, 0.f));
}
