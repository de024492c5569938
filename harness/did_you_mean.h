#pragma once
// "did you mean" for a mistyped name (scheme, parameter, config field, subcommand): the closest
// known name by edit distance, when it is close enough to be a typo rather than another word.
#include <string>
#include <vector>

namespace lb {

// Levenshtein distance (insertions, deletions, substitutions), ASCII case-insensitive.
size_t editDistance(const std::string& a, const std::string& b);
// "; did you mean 'x'?" for the nearest known name within max(1, |given| / 3) edits (ties: the
// first in `known`), or "" when none is that close.
std::string didYouMean(const std::string& given, const std::vector<std::string>& known);

}  // namespace lb
