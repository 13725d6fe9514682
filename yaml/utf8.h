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

// Is the character at `i` (a well-formed sequence) a control character: C0 (below 0x20), DEL,
// or C1 (U+0080..U+009F, bytes C2 80..C2 9F: a terminal acts on them as on ESC sequences)?
bool isControlAt(const std::string& s, std::size_t i);

// The offset of the first control character of `s` (isControlAt), or nullopt.
std::optional<std::size_t> firstControl(const std::string& s);

// `s` with every byte of an ill-formed sequence and every control character written as \xNN,
// so that a message can quote it safely.
std::string printable(const std::string& s);

// The same for a whole message to a terminal: line feeds and tabs kept, every other control
// character (ESC, BEL, C1) and every ill-formed byte written as \xNN.
std::string terminalText(const std::string& s);

}  // namespace metrosync
