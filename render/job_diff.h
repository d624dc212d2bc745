#pragma once
// Which field of two job signatures ("tray:job", docs/farm.md) differs: what tray-merge and
// --resume say when a file belongs to another render.
#include <string>
#include <utility>
#include <vector>

namespace tray {

/// The "name=value" fields of a job signature, in order. A value may hold spaces (a scene
/// file name): a word without '=' belongs to the field before it.
std::vector<std::pair<std::string, std::string>> jobFields(const std::string& job);

/// "" if the jobs are equal, else the first difference in words, e.g. "seed is 8 there, 7 here"
/// or "the field 'max-depth' is missing there" (`here` and `there` name the two sides).
std::string jobDifference(const std::string& here, const std::string& there);

}  // namespace tray
