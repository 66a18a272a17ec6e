#pragma once
// "Did you mean ...?" for unknown keys, names and choices.

#include <string>
#include <vector>

namespace geotandem {

// Edit distance (insertions, deletions, substitutions, adjacent swaps).
std::size_t edit_distance(const std::string& a, const std::string& b);

// The candidate closest to `word` when it is close enough to be a plausible typo (distance at most
// max(2, |word| / 3)); empty otherwise.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

// Among `words` (keys a user wrote that nothing knows), the one that was most likely meant as the
// missing `name`: a plausible typo of it (as nearest()), or, ignoring case, one that begins with it
// or that it begins with, the shorter of the two at least 3 letters long ('isovalue' for 'iso',
// 'min_vol' for 'min_volume'). Empty when none is.
std::string stand_in_for(const std::string& name, const std::vector<std::string>& words);

// "did you mean 'x'?" or, when nothing is close, "expected one of: a, b, c".
std::string suggestion_hint(const std::string& word, const std::vector<std::string>& candidates);

} // namespace geotandem
