#pragma once
// The data a run keeps beside its config and names from it (`mimic imitate` writes them: the
// clips, start clips, character and demonstrations), carried into a model made from the run, so
// that the model loads wherever it is copied.
#include <filesystem>
#include <string>
#include <vector>

namespace mimic::app {

// Copies each of the run's clips/, start_clips/, character/ and demos.csv that exists into
// `model` (replacing what the model had of them); returns the names copied.
std::vector<std::string> copy_run_data(const std::filesystem::path& run, const std::filesystem::path& model);

}  // namespace mimic::app
