#pragma once
/// \file
/// How far apart two names are, to point a typo at the name meant ("--modul": "--module").

#include <cstddef>
#include <string>

namespace sewer3d {

/// Edits (insert, delete, replace a character; case ignored) from `a` to `b`.
std::size_t EditDistance(const std::string& a, const std::string& b);

}  // namespace sewer3d
