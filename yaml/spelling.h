// "did you mean ...?" for a mistyped key or name (yaml/; and the command line's unknown command).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace metrosync::rigfile {

// The closest candidate if it is close enough to be a typo (edit distance, case-blind, with
// adjacent transpositions; or a prefix of at least 3 letters); nullopt otherwise.
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& cands);

}  // namespace metrosync::rigfile
