#pragma once
/// \file
/// Refusals of option structs name their fields ("spot_diameter_px"); on the command line the
/// user typed flags ("--spot-px"), so a command renames them before the error is printed.

#include <initializer_list>
#include <string_view>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d::cli {

/// A field name and the flag that sets it.
using FlagName = std::pair<std::string_view, std::string_view>;

/// The refusal with every field of `flags` written as its flag: the field itself, and in the
/// problem's text the names holding an underscore (a plain word like "window" stays a word).
InvalidValue WithFlagNames(const InvalidValue& refusal, std::initializer_list<FlagName> flags);

}  // namespace sewer3d::cli
