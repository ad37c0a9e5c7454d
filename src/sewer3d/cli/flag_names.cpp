#include "sewer3d/cli/flag_names.hpp"

#include <string>

namespace sewer3d::cli {

InvalidValue WithFlagNames(const InvalidValue& refusal, std::initializer_list<FlagName> flags) {
  std::string field = refusal.field(), problem = refusal.problem();
  for (const auto& [name, flag] : flags) {
    if (field == name) field = flag;
    // In the problem's prose only names with an underscore: "window" there is a plain word.
    if (name.find('_') == std::string_view::npos) continue;
    for (std::string* text : {&field, &problem}) {
      for (size_t at = text->find(name); at != std::string::npos;
           at = text->find(name, at + flag.size())) {
        text->replace(at, name.size(), flag);
      }
    }
  }
  return {field, problem};
}

}  // namespace sewer3d::cli
