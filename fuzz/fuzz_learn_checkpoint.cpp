// Fuzz target: checkpoints and exported models (LibTorch zip archives). Any file must load into a
// walker trainer or raise mimic::Error, never crash; a damaged one is refused before any of it is
// used (core/zip_integrity), which the byte flips here exercise most.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string_view>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "learn/trainer/trainer.hpp"

namespace {

const char* const kConfig =
    "seed: 1\niterations: 1\nenv: {name: planar_walker}\ncollect: {envs: 2, threads: 1, samples: 64}\n"
    "policy: {hidden: [8]}\nvalue: {hidden: [8]}\nppo: {epochs: 1, value_epochs: 1, minibatch: 64}\n";

mimic::Trainer& trainer() {
  static mimic::Trainer t(mimic::parse_train_config(kConfig, "fuzz.yaml"));
  return t;
}

std::filesystem::path scratch(const char* name) {
  return std::filesystem::temp_directory_path() / ("mimic_fuzz_" + std::to_string(::getpid()) + name);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = scratch(".pt");
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    trainer().load_checkpoint(file);
  } catch (const mimic::Error&) {
  }
  std::filesystem::remove(file);
  return 0;
}

// LeakSanitizer (the asan preset): LibTorch's zip reader keeps what it allocated for an archive
// it then refuses (a known leak of its error path, not ours to fix).
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libtorch\nleak:libc10\nleak:mz_zip\n"; }

std::vector<std::string> MimicFuzzSeeds() {
  // A checkpoint after one iteration, and the model exported from it.
  mimic::Trainer t(mimic::parse_train_config(kConfig, "fuzz.yaml"));
  t.iterate();
  const std::filesystem::path checkpoint = scratch("_seed.pt"), model = scratch("_model.pt");
  t.save_checkpoint(checkpoint);
  t.export_model(model);
  std::vector<std::string> seeds{mimic::read_text_file(checkpoint), mimic::read_text_file(model)};
  std::filesystem::remove(checkpoint);
  std::filesystem::remove(model);
  return seeds;
}
