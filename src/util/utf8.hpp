// Text that reaches JSON, glTF or the window must be valid UTF-8 (nlohmann::json throws on
// anything else). Names from files (joint names, file names) go through this where they are
// read, so every later consumer sees valid text.
#pragma once

#include <string>

namespace util {

// True if `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing
// above U+10FFFF).
bool is_valid_utf8(const std::string& text);

// `text` with every byte that is not part of a well-formed UTF-8 sequence replaced by U+FFFD.
std::string to_valid_utf8(const std::string& text);

}  // namespace util
