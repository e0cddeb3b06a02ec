// Malformed XML is reported in words, at the file and line tinyxml2 found, never as tinyxml2's
// "Error=XML_ERROR_PARSING ErrorID=15 (0xf) Line number=..." text.
#include "core/scene/xml_error_text.h"

#include <gtest/gtest.h>

#include <string>

#include "core/math/error.h"
#include "core/scene/xml_parser.h"

namespace penumbra {
namespace {

std::string parseError(const std::string& xml) {
  try {
    parseSceneString(xml, "scene.xml", ".");
  } catch (const Error& e) {
    return e.what();
  }
  return "(parsed)";
}

void expectPlain(const std::string& message) {
  for (const char* raw : {"XML_ERROR", "ErrorID", "Error=", "0x"})
    EXPECT_EQ(message.find(raw), std::string::npos) << "tinyxml2's raw text in: " << message;
}

TEST(XmlErrorText, UnclosedElementNamesItsTagAndLine) {
  const std::string m = parseError("<scene>\n<integrator type=\"direct\">\n</scene>\n");
  EXPECT_EQ(m.rfind("scene.xml:2: malformed XML: <integrator> starting on this line is not closed by "
                    "</integrator>",
                    0),
            0u)
      << m;
  expectPlain(m);
}

TEST(XmlErrorText, FileThatEndsInsideAnElementSaysSo) {
  const std::string m = parseError("<scene>\n<integer name=\"a\" value=\"1\"/>\n");
  EXPECT_EQ(m.rfind("scene.xml:1: malformed XML: the element starting on this line is not closed before the "
                    "file ends",
                    0),
            0u)
      << m;
  expectPlain(m);
}

TEST(XmlErrorText, EveryParseErrorIsDescribedInWords) {
  struct Case {
    const char* xml;
    const char* words;
  } cases[] = {
      {"<scene>\n<integer name=\"a\" value=1/>\n</scene>",
       "scene.xml:2: malformed XML: a malformed attribute in <integer>"},
      {"<scene>\n<integer name=\"a\" value=\"1\"/\n</scene>", "scene.xml:2: malformed XML: a malformed tag"},
      {"", "scene.xml: malformed XML: the file is empty"},
      {"<scene>\n<!-- open\n</scene>", "scene.xml:2: malformed XML: a comment \"<!--\" is not closed"},
      {"<scene>\n<![CDATA[ x\n</scene>", "scene.xml:2: malformed XML: a \"<![CDATA[\" section is not closed"},
      {"<?xml version=\"1.0\"\n<scene/>", "scene.xml:1: malformed XML: a malformed declaration"},
      {"<scene>\n</scen>", "scene.xml:1: malformed XML: <scene> starting on this line is not closed"},
  };
  for (const Case& c : cases) {
    const std::string m = parseError(c.xml);
    EXPECT_EQ(m.rfind(c.words, 0), 0u) << m;
    expectPlain(m);
  }
}

TEST(XmlErrorText, UnknownCodesStillSayWhatTinyxmlSaid) {
  EXPECT_EQ(describeXmlError(-1, "something odd"), "cannot parse the file (something odd)");
}

}  // namespace
}  // namespace penumbra
