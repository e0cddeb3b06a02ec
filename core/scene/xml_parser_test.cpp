#include "core/scene/xml_parser.h"

#include <gtest/gtest.h>

#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "core/math/error.h"

namespace penumbra {
namespace {

int errorLine(const std::string& xml, std::string* message = nullptr) {
  try {
    parseSceneString(xml, "t.xml", "/base");
  } catch (const Error& e) {
    if (message) *message = e.what();
    EXPECT_EQ(e.file(), "t.xml");
    return e.line();
  }
  ADD_FAILURE() << "no error for:\n" << xml;
  return -1;
}

void expectNear(const glm::mat4& a, const glm::mat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-5f) << "col " << c << " row " << r;
}

glm::mat4 transformOf(const std::string& ops) {
  SceneNode root = parseSceneString("<scene>\n<shape type=\"obj\">\n<transform name=\"toWorld\">\n" + ops +
                                        "\n</transform>\n</shape>\n</scene>",
                                    "t.xml", ".");
  return root.children.at(0).props.getTransform({"toWorld"}, glm::mat4(0.f));
}

TEST(XmlParser, ParsesObjectsPropertiesAndLines) {
  const std::string xml = R"(<scene>
  <sampler type="independent">
    <integer name="sampleCount" value="32"/>
  </sampler>
  <integrator type="ao">
    <integer name="nSamples" value="1"/>
    <string name="sampling" value="cosine"/>
  </integrator>
  <mesh type="obj">
    <string name="filename" value="plane.obj"/>
    <bsdf type="diffuse"><color name="albedo" value="0.5"/></bsdf>
  </mesh>
  <shape type="sphere">
    <emitter type="area"><color name="radiance" value="300,300,300"/></emitter>
  </shape>
  <camera type="perspective"><rfilter type="gaussian"/></camera>
</scene>)";
  SceneNode root = parseSceneString(xml, "t.xml", "/scenes/x");
  EXPECT_EQ(root.tag, "scene");
  ASSERT_EQ(root.children.size(), 5u);
  EXPECT_EQ(root.children[0].tag, "sampler");
  EXPECT_EQ(root.children[0].line, 2);
  EXPECT_EQ(root.children[0].props.getInteger({"sampleCount"}, 0), 32);
  EXPECT_EQ(root.children[0].props.lineOf({"sampleCount"}), 3);
  const SceneNode& mesh = root.children[2];
  EXPECT_EQ(mesh.tag, "shape");  // mesh normalised
  EXPECT_EQ(mesh.type, "obj");
  EXPECT_EQ(mesh.baseDir, "/scenes/x");
  EXPECT_EQ(resolveScenePath(mesh, "plane.obj"), "/scenes/x/plane.obj");
  EXPECT_EQ(resolveScenePath(mesh, "../ref/ajax.obj"), "/scenes/ref/ajax.obj");
  EXPECT_EQ(resolveScenePath(mesh, "/abs/a.obj"), "/abs/a.obj");
  ASSERT_EQ(mesh.children.size(), 1u);
  EXPECT_EQ(mesh.children[0].props.getColor({"albedo"}, Vec3(0)), Vec3(0.5f));
  EXPECT_EQ(root.children[3].children[0].tag, "emitter");
  EXPECT_EQ(root.children[3].children[0].line, 14);
  EXPECT_EQ(root.child("camera")->children.at(0).tag, "rfilter");
}

TEST(XmlParser, ErrorsCarryLines) {
  std::string msg;
  EXPECT_EQ(errorLine("<scene>\n<shape type=\"obj\"/>\n<shape type=\"obj>\n</scene>", &msg), 3);
  EXPECT_NE(msg.find("malformed XML"), std::string::npos) << msg;
  EXPECT_EQ(errorLine("<scene>\n\n<light type=\"point\"/>\n</scene>", &msg), 3);
  EXPECT_NE(msg.find("unknown tag <light>"), std::string::npos) << msg;
  EXPECT_EQ(
      errorLine("<scene>\n<integrator type=\"ao\">\n<int name=\"a\" value=\"1\"/>\n</integrator>\n</scene>"),
      3);
  EXPECT_EQ(errorLine("<scene>\n<sampler type=\"independent\">\n<integer value=\"1\"/>\n</sampler>\n</scene>",
                      &msg),
            3);
  EXPECT_NE(msg.find("name=\"...\""), std::string::npos) << msg;
  EXPECT_EQ(errorLine("<scene>\n<sampler type=\"independent\">\n<integer name=\"x\"/>\n</sampler>\n</scene>"),
            3);
  EXPECT_EQ(errorLine("<scene>\n<sampler type=\"independent\">\n<integer name=\"sampleCount\" "
                      "value=\"3.5\"/>\n</sampler>\n</scene>",
                      &msg),
            3);
  EXPECT_NE(msg.find("t.xml:3: <integer name=\"sampleCount\">: expected an integer, got \"3.5\""),
            std::string::npos)
      << msg;
  EXPECT_EQ(
      errorLine(
          "<scene>\n<shape type=\"sphere\">\n<float name=\"radius\" value=\"nan\"/>\n</shape>\n</scene>"),
      3);
  EXPECT_EQ(
      errorLine(
          "<scene>\n<shape type=\"sphere\">\n<float name=\"radius\" value=\"1e999\"/>\n</shape>\n</scene>"),
      3);
  EXPECT_EQ(
      errorLine("<scene>\n<shape type=\"sphere\">\n<camera type=\"perspective\"/>\n</shape>\n</scene>", &msg),
      3);
  EXPECT_NE(msg.find("<camera> inside <shape>"), std::string::npos) << msg;
  EXPECT_EQ(errorLine("<scene>\n<bsdf type=\"diffuse\"/>\n</scene>"), 2);
  EXPECT_EQ(errorLine("<scene>\n<shape/>\n</scene>"), 2);  // missing type
  EXPECT_EQ(errorLine("<scene>\n<camera type=\"a\"/>\n<camera type=\"b\"/>\n</scene>", &msg), 3);
  EXPECT_NE(msg.find("first at line 2"), std::string::npos) << msg;
  EXPECT_EQ(errorLine("<shape type=\"obj\"/>"), 1);
  EXPECT_EQ(errorLine("<scene>\n<scene/>\n</scene>"), 2);
  EXPECT_EQ(
      errorLine(
          "<scene>\n<shape type=\"s\">\n<float name=\"r\" value=\"1\"/>\n<float name=\"r\" value=\"2\"/>\n"
          "</shape>\n</scene>"),
      4);
  EXPECT_EQ(errorLine("<scene>\n<shape type=\"s\">\n<transform name=\"toWorld\">\n<shear value=\"1\"/>\n"
                      "</transform>\n</shape>\n</scene>"),
            4);
  EXPECT_EQ(
      errorLine("<scene>\n<camera type=\"p\">\n<transform name=\"toWorld\">\n\n<lookat origin=\"0,0,0\" "
                "target=\"0,0,0\" up=\"0,1,0\"/>\n</transform>\n</camera>\n</scene>",
                &msg),
      5);
  EXPECT_NE(msg.find("target different from origin"), std::string::npos) << msg;
  EXPECT_EQ(errorLine("<scene>\n<camera type=\"p\">\n<transform name=\"toWorld\">\n<lookat origin=\"0,0,0\" "
                      "target=\"0,1,0\" up=\"0,2,0\"/>\n</transform>\n</camera>\n</scene>",
                      &msg),
            4);
  EXPECT_NE(msg.find("parallel"), std::string::npos) << msg;
  EXPECT_EQ(
      errorLine("<scene>\n<shape type=\"s\">\n<transform name=\"t\">\n<rotate axis=\"0,0,0\" angle=\"3\"/>\n"
                "</transform>\n</shape>\n</scene>"),
      4);
}

// tinyxml2 keeps text as C strings: a NUL would silently end the file or a value (here the second
// shape, or the mesh path "plane.obj\0.bak" read as "plane.obj"). Refused where it is.
TEST(XmlParser, NulCharactersAreRefusedWithTheirLine) {
  const std::string head = "<scene>\n<shape type=\"sphere\"/>\n";
  std::string msg;
  const std::string nul(1, '\0');
  EXPECT_EQ(errorLine(head + "  " + nul + "<shape type=\"sphere\"/>\n</scene>", &msg), 3);
  EXPECT_NE(msg.find("t.xml:3: column 3: a NUL character (byte 0) is not allowed"), std::string::npos) << msg;
  EXPECT_EQ(errorLine(head + "</scene>" + nul + "trailing", &msg), 3);
  for (const char* ref : {"&#0;", "&#x0;", "&#000;", "&#x00;"}) {
    EXPECT_EQ(errorLine(head + "<shape type=\"obj\">\n<string name=\"filename\" value=\"plane.obj" + ref +
                            ".bak\"/>\n</shape>\n</scene>",
                        &msg),
              4)
        << ref;
    EXPECT_NE(msg.find(std::string("the character reference ") + ref + " (NUL)"), std::string::npos) << msg;
  }
  // Other character references are text as usual.
  EXPECT_NO_THROW(parseSceneString(head + "<!-- &#10; &#x41; &#100; &#x10; -->\n</scene>", "t.xml", "/base"));
}

TEST(XmlParser, ScenePathWithANulByteIsRefused) {
  try {
    parseSceneFile(std::string("scene.xml") + '\0' + ".evil");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scene file path \"scene.xml\\0.evil\" has a NUL byte at offset 9"),
              std::string::npos)
        << e.what();
  }
}

// tinyxml2 passes any bytes through (and stops at a NUL): the parser names the line of the first
// byte that is not UTF-8 text, before anything else is read.
TEST(XmlParser, TextThatIsNotUtf8IsRefusedWithItsLine) {
  std::string msg;
  EXPECT_EQ(errorLine("<scene>\n<shape type=\"sphere\">\n  <string name=\"caf\xE9\" value=\"x\"/>\n"
                      "</shape>\n</scene>",
                      &msg),
            3);
  EXPECT_NE(msg.find("t.xml:3: byte 0xE9 at column 20 is not UTF-8"), std::string::npos) << msg;
  EXPECT_EQ(errorLine("<scene>\n<!-- \xC0\xAF -->\n</scene>", &msg), 2);  // overlong, even in a comment
  EXPECT_EQ(
      errorLine(std::string("<scene>\n\n<sampler type=\"independent\"/>\0<bogus/>\n</scene>", 56), &msg), 3);
  EXPECT_NE(msg.find("column 30: a NUL character"), std::string::npos) << msg;
  EXPECT_EQ(errorLine("\xFF<scene/>", &msg), 1);
  EXPECT_NE(msg.find("column 1"), std::string::npos) << msg;
  // Valid UTF-8 (a byte-order mark, accents) is fine.
  SceneNode root =
      parseSceneString("\xEF\xBB\xBF<scene>\n<shape type=\"caf\xC3\xA9\"/>\n</scene>", "t.xml", ".");
  EXPECT_EQ(root.children.at(0).type, "caf\xC3\xA9");
}

TEST(Override, ValuesThatAreNotUtf8TextAreRefused) {
  SceneNode root = parseSceneString("<scene>\n<sampler type=\"independent\"/>\n</scene>", "t.xml", ".");
  try {
    applyOverride(root, "sampler.name", "caf\xE9");
    FAIL() << "a Latin-1 value was accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--set sampler.name=caf\\xE9: not UTF-8 text");
  }
  EXPECT_THROW(applyOverride(root, "sampler.name", std::string("a\0b", 3)), Error);
  EXPECT_THROW(applyOverride(root, std::string("sampler.sample\0Count", 20), "4"), Error);
}

TEST(XmlParser, MissingFile) {
  try {
    parseSceneFile("/nonexistent/dir/scene.xml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open scene file"), std::string::npos);
  }
}

TEST(Transform, SingleOperations) {
  expectNear(transformOf("<translate value=\"1, 2, 3\"/>"), glm::translate(glm::mat4(1.f), Vec3(1, 2, 3)));
  expectNear(transformOf("<translate x=\"1\" z=\"3\"/>"), glm::translate(glm::mat4(1.f), Vec3(1, 0, 3)));
  expectNear(transformOf("<scale value=\"2\"/>"), glm::scale(glm::mat4(1.f), Vec3(2)));
  expectNear(transformOf("<scale y=\"5\"/>"), glm::scale(glm::mat4(1.f), Vec3(1, 5, 1)));
  // rotate 90 degrees about x: y → z, z → -y.
  glm::mat4 r = transformOf("<rotate axis=\"1,0,0\" angle=\"90\"/>");
  glm::mat4 expected(1.f);
  expected[1] = glm::vec4(0, 0, 1, 0);
  expected[2] = glm::vec4(0, -1, 0, 0);
  expectNear(r, expected);
  // matrix is row-major in the file.
  glm::mat4 m = transformOf("<matrix value=\"1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1\"/>");
  expectNear(m, glm::translate(glm::mat4(1.f), Vec3(5, 6, 7)));
}

TEST(Transform, DocumentOrderLeftMultiplies) {
  // The assignment's ground plane: scale(10,1,10), rotate x 90, translate (0,0,-1).
  glm::mat4 m = transformOf(
      "<scale value=\"10,1,10\"/><rotate axis=\"1,0,0\" angle=\"90\"/><translate value=\"0,0,-1\"/>");
  // Hand-computed: the point (1,0,1) → scale (10,0,10) → rotate x90 (10,-10,0) → translate (10,-10,-1).
  glm::vec4 p = m * glm::vec4(1, 0, 1, 1);
  EXPECT_NEAR(p.x, 10.f, 1e-5f);
  EXPECT_NEAR(p.y, -10.f, 1e-5f);
  EXPECT_NEAR(p.z, -1.f, 1e-5f);
  glm::mat4 expected(0.f);
  expected[0] = glm::vec4(10, 0, 0, 0);
  expected[1] = glm::vec4(0, 0, 1, 0);
  expected[2] = glm::vec4(0, -10, 0, 0);
  expected[3] = glm::vec4(0, 0, -1, 1);
  expectNear(m, expected);
  // translate then scale: the translation is scaled too.
  expectNear(transformOf("<translate value=\"1,0,0\"/><scale value=\"2\"/>"),
             glm::translate(glm::mat4(1.f), Vec3(2, 0, 0)) * glm::scale(glm::mat4(1.f), Vec3(2)));
}

TEST(Transform, LookAtMatchesNori) {
  // The camera of scenes/hw0/Tests: origin (4,4,0), target 0, up z.
  glm::mat4 m = transformOf("<lookat target=\"0,0,0\" origin=\"4,4,0\" up=\"0,0,1\"/>");
  float s = 1.f / std::sqrt(2.f);
  Vec3 dir(-s, -s, 0);
  Vec3 left = glm::normalize(glm::cross(Vec3(0, 0, 1), dir));  // (s, -s, 0)
  EXPECT_NEAR(left.x, s, 1e-6f);
  EXPECT_NEAR(left.y, -s, 1e-6f);
  glm::mat4 expected(1.f);
  expected[0] = glm::vec4(left, 0);
  expected[1] = glm::vec4(0, 0, 1, 0);
  expected[2] = glm::vec4(dir, 0);
  expected[3] = glm::vec4(4, 4, 0, 1);
  expectNear(m, expected);
  // Camera-space +z maps to the viewing direction, the origin to the eye.
  glm::vec4 o = m * glm::vec4(0, 0, 0, 1);
  EXPECT_NEAR(o.x, 4.f, 1e-6f);
  // A translate after lookat moves the camera.
  glm::mat4 m2 =
      transformOf("<lookat target=\"0,0,0\" origin=\"4,4,0\" up=\"0,0,1\"/><translate value=\"0,0,1\"/>");
  expectNear(m2, glm::translate(glm::mat4(1.f), Vec3(0, 0, 1)) * expected);
}

TEST(XmlWriter, RoundTrip) {
  const std::string xml = R"(<scene>
  <integrator type="direct"><integer name="nSamples" value="4294967296"/><string name="measure" value="a &lt;b&gt; &amp; &quot;c&quot;"/><boolean name="b" value="true"/></integrator>
  <shape type="obj">
    <string name="filename" value="plane.obj"/>
    <transform name="toWorld"><scale value="0.1,8,0.1"/><rotate axis="1,0,0" angle="90"/><translate value="0.2,0.2,0"/></transform>
    <bsdf type="diffuse"><color name="albedo" value="0.1, 0.2, 0.3"/></bsdf>
  </shape>
  <shape type="sphere"><point name="center" value="1,-1.5,1.75"/><float name="radius" value="0.1"/>
    <emitter type="area"><color name="radiance" value="300,300,300"/></emitter></shape>
  <emitter type="directional"><vector name="direction" value="0,1,10"/></emitter>
  <camera type="perspective"><float name="fov" value="16.000001"/></camera>
</scene>)";
  SceneNode a = parseSceneString(xml, "a.xml", "/d");
  std::string text = writeSceneXml(a);
  SceneNode b = parseSceneString(text, "b.xml", "/d");
  std::function<void(const SceneNode&, const SceneNode&)> same = [&](const SceneNode& x, const SceneNode& y) {
    EXPECT_EQ(x.tag, y.tag);
    EXPECT_EQ(x.type, y.type);
    ASSERT_EQ(x.props.size(), y.props.size());
    for (size_t i = 0; i < x.props.size(); ++i) {
      const Property& p = x.props.properties()[i];
      const Property& q = y.props.properties()[i];
      EXPECT_EQ(p.name, q.name);
      EXPECT_EQ(p.type, q.type);
      EXPECT_EQ(p.valueText(), q.valueText()) << p.name;
      EXPECT_EQ(p.intValue, q.intValue);
      EXPECT_EQ(p.floatValue, q.floatValue);
      EXPECT_EQ(p.stringValue, q.stringValue);
      EXPECT_EQ(p.vecValue, q.vecValue);
      EXPECT_EQ(p.matrix, q.matrix);
    }
    ASSERT_EQ(x.children.size(), y.children.size());
    for (size_t i = 0; i < x.children.size(); ++i) same(x.children[i], y.children[i]);
  };
  same(a, b);
  EXPECT_EQ(writeSceneXml(b), text);
}

TEST(Override, AppliesToFirstObjectWithTag) {
  SceneNode root = parseSceneString(R"(<scene>
<sampler type="independent"><integer name="sampleCount" value="16"/></sampler>
<integrator type="direct"><string name="measure" value="solid-angle"/></integrator>
<shape type="sphere"><emitter type="area"><color name="radiance" value="1,1,1"/></emitter></shape>
<camera type="perspective"><float name="fov" value="16"/></camera>
</scene>)",
                                    "s.xml", ".");
  applyOverride(root, "integrator.measure", "area");
  applyOverride(root, "sampler.sampleCount", "64");
  applyOverride(root, "camera.fov", "40");
  applyOverride(root, "emitter.radiance", "2");     // nested emitter, color accepts a grey value
  applyOverride(root, "integrator.nSamples", "4");  // new property, inferred integer
  EXPECT_EQ(root.child("integrator")->props.getString({"measure"}, ""), "area");
  EXPECT_EQ(root.child("sampler")->props.getInteger({"sampleCount"}, 0), 64);
  EXPECT_FLOAT_EQ(root.child("camera")->props.getFloat({"fov"}, 0), 40.f);
  EXPECT_EQ(root.child("shape")->children[0].props.getColor({"radiance"}, Vec3(0)), Vec3(2));
  EXPECT_EQ(root.child("integrator")->props.getInteger({"nSamples"}, 1), 4);
  EXPECT_THROW(applyOverride(root, "sampler.sampleCount", "3.5"), Error);
  EXPECT_THROW(applyOverride(root, "rfilter.radius", "2"), Error);
  EXPECT_THROW(applyOverride(root, "sampleCount", "2"), Error);
  EXPECT_THROW(applyOverride(root, "sampler.", "2"), Error);
  // Blamed on the --set, which names the file's line that gives the property its type.
  try {
    applyOverride(root, "sampler.sampleCount", "abc");
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("--set sampler.sampleCount=abc: cannot set property \"sampleCount\"", 0), 0u) << m;
    EXPECT_NE(m.find(":2)"), std::string::npos) << m;
    EXPECT_EQ(e.line(), 0);
  }
}

}  // namespace
}  // namespace penumbra
