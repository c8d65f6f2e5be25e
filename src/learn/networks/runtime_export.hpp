#pragma once
// What `mimic export` writes for the torch-free runtime (control/): networks.mimic, an array file
// (core/array_file.hpp) holding the policy and value networks, the observation normaliser and
// the sizes and names the runtime checks a world against. The names are docs/runtime.md's.
#include <filesystem>

#include "core/array_file.hpp"
#include "learn/networks/runtime_format.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic {

std::vector<NamedArray> runtime_arrays(const Trainer::Impl& t);
// The arrays' file at `path`, written atomically.
void write_runtime_file(const Trainer::Impl& t, const std::filesystem::path& path);

}  // namespace mimic
