#pragma once
// The training recipes of `mimic imitate`, one per method: configs/recipes/<method>.yaml, compiled
// into the program (so an installed `mimic` has them) by CMake from those files.
#include <string>
#include <vector>

namespace mimic::app {

struct Recipe {
  std::string method;  // iccgan, gail, tracking
  std::string text;    // the YAML of configs/recipes/<method>.yaml
};

const std::vector<Recipe>& recipes();
// The recipe of `method`; Error listing the methods for another name.
const Recipe& recipe(const std::string& method);

}  // namespace mimic::app
