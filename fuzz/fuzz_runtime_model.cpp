// Fuzz target: the runtime's model file (networks.mimic, control/skill.cpp). Any bytes must be
// read into a skill or raise mimic::Error, never crash. An input that does not start with the
// file's magic is taken as a file's body and given a valid header (its CRC-32 computed), so that
// mutations reach the reader behind the checksum instead of stopping at it.
#include <cstdint>
#include <cstring>

#include <zlib.h>

#include "control/skill_impl.hpp"
#include "core/array_file.hpp"
#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"

namespace {

std::string with_header(std::string_view body) {
  // encode_arrays writes a header for an empty list: keep its magic and version, replace the rest.
  std::string file = mimic::encode_arrays({}).substr(0, 12);
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()));
  const auto crc32_value = static_cast<std::uint32_t>(crc);
  const auto size = static_cast<std::uint64_t>(body.size());
  file.append(reinterpret_cast<const char*>(&crc32_value), 4);
  file.append(reinterpret_cast<const char*>(&size), 8);
  return file + std::string(body);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input = mimic::fuzz::as_text(data, size);
  const std::string bytes = input.rfind("MIMICARR", 0) == 0 ? std::string(input) : with_header(input);
  try {
    const std::unique_ptr<mimic::Skill::Impl> skill = mimic::read_skill_networks(bytes, "fuzz.mimic");
    // What was accepted acts: one input of zeros through both networks.
    const Eigen::MatrixXd zeros = Eigen::MatrixXd::Zero(1, skill->frame_size * skill->history);
    (void)skill->policy.forward(skill->normalised(zeros));
    (void)skill->value.forward(skill->normalised(zeros));
  } catch (const mimic::Error&) {
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  std::vector<std::string> seeds;
  try {
    const std::string walker = mimic::read_text_file(std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "walker_ppo" / "networks.mimic");
    seeds.push_back(walker);
    seeds.push_back(walker.substr(24));  // its body alone: the target gives it a valid header
  } catch (const mimic::Error&) {
  }
  return seeds;
}
