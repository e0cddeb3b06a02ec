// tinyxml2's parse errors in words: "malformed XML: <integrator> starting on this line is not closed
// ..." instead of "Error=XML_ERROR_MISMATCHED_ELEMENT ErrorID=14 (0xe) Line number=2: ...".
#pragma once

#include <string>

namespace penumbra {

// What is wrong, for the error `errorId` (tinyxml2::XMLError) reported at a line, given tinyxml2's
// ErrorStr() (its "XMLElement name=..." detail names the element where it has one).
std::string describeXmlError(int errorId, const std::string& tinyxmlText);

}  // namespace penumbra
