// Suggestions for mistyped names: " (did you mean 'density'?)" after an
// unknown key of a scene file, a display profile or a profile name. One
// function, so every file format suggests the same way.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace simsols {

// Levenshtein distance: insertions, deletions and substitutions.
std::size_t edit_distance(std::string_view a, std::string_view b);

// " (did you mean 'x'?)" for the allowed name closest to `name` when it is
// close enough (at most max(2, |name| / 3) edits); "" otherwise.
std::string did_you_mean(std::string_view name, const std::vector<std::string>& allowed);

}  // namespace simsols
