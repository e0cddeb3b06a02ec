#include "core/scene/xml_error_text.h"

#include <tinyxml2.h>

namespace penumbra {

namespace {

// The element tinyxml2 names in its detail ("... Line number=2: XMLElement name=integrator").
std::string elementNamed(const std::string& text) {
  const std::string key = "XMLElement name=";
  const size_t at = text.find(key);
  if (at == std::string::npos) return {};
  std::string name = text.substr(at + key.size());
  const size_t end = name.find_first_of(" \t\r\n");
  return end == std::string::npos ? name : name.substr(0, end);
}

}  // namespace

std::string describeXmlError(int errorId, const std::string& tinyxmlText) {
  const std::string name = elementNamed(tinyxmlText);
  const std::string element = name.empty() ? std::string("an element") : "<" + name + ">";
  switch (static_cast<tinyxml2::XMLError>(errorId)) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: {
      const std::string tag = name.empty() ? std::string("...") : name;
      return element + " starting on this line is not closed by </" + tag +
             ">: its closing tag is missing, misspelt or out of place (an empty element is written <" + tag +
             " .../>)";
    }
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "a malformed attribute in " + element + ": expected name=\"value\", the value in quotes";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "a malformed tag: expected <name attribute=\"value\" ...> or <name .../> (a '<', '>' or '/' "
             "out of place)";
    case tinyxml2::XML_ERROR_PARSING:
      return "the element starting on this line is not closed before the file ends (a missing closing "
             "tag such as </scene>, or a truncated file)";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "the file is empty: expected a <scene> element";
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return "a comment \"<!--\" is not closed with \"-->\"";
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return "a \"<![CDATA[\" section is not closed with \"]]>\"";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return "a malformed declaration: expected <?xml version=\"1.0\"?>, closed with \"?>\"";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return "a malformed \"<!...>\" directive: expected it closed with \">\"";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "malformed text between the tags";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
      return "elements are nested too deeply";
    default:
      return "cannot parse the file (" + tinyxmlText + ")";
  }
}

}  // namespace penumbra
