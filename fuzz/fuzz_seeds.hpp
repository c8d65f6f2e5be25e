#pragma once
// Seeds for a fuzz target: files under ../shared/data (when present) and built-in samples.
// A target defines MimicFuzzSeeds() returning them; the standalone driver mutates them.
#include <string>
#include <vector>

std::vector<std::string> MimicFuzzSeeds();
