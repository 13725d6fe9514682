// UTF-8 checks for rig text: every string a rig can put into a file (names, the rig's own
// text, --set values) is checked when the rig is loaded, so that no run can fail while writing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace metrosync {

// The offset of the first byte that does not start a well-formed UTF-8 sequence (overlong forms,
// surrogates U+D800..U+DFFF and code points above U+10FFFF are not well formed), or nullopt.
std::optional<std::size_t> firstBadUtf8(const std::string& s);

// `s` with every byte of an ill-formed sequence and every control character written as \xNN,
// so that a message can quote it safely.
std::string printable(const std::string& s);

}  // namespace metrosync
