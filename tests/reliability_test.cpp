// What survives bad input and interruptions at the lowest layer: bounded reads, durable atomic
// writes that keep the previous version, the zip integrity check that guards checkpoints,
// duplicate YAML keys, and TensorBoard event files cut back for a resumed run.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/tensorboard.hpp"
#include "core/yaml_reader.hpp"
#include "core/zip_integrity.hpp"
#include "error_message.hpp"
#include "motion/builtin.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "test_data.hpp"

using namespace mimic;
using mimic::test::error_of;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

void put(std::string& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

// A zip of one stored entry "w" holding "hello", built by hand: CRC-32("hello") = 0x3610a686.
std::string hello_zip() {
  const std::string name = "w", data = "hello";
  std::string z;
  put(z, 0x04034b50, 4), put(z, 20, 2), put(z, 0, 2), put(z, 0, 2), put(z, 0, 4);  // local header: method 0
  put(z, 0x3610a686, 4), put(z, data.size(), 4), put(z, data.size(), 4), put(z, name.size(), 2), put(z, 0, 2);
  z += name + data;
  const std::size_t directory = z.size();
  put(z, 0x02014b50, 4), put(z, 20, 2), put(z, 20, 2), put(z, 0, 2), put(z, 0, 2), put(z, 0, 4);
  put(z, 0x3610a686, 4), put(z, data.size(), 4), put(z, data.size(), 4), put(z, name.size(), 2), put(z, 0, 2), put(z, 0, 2);
  put(z, 0, 2), put(z, 0, 2), put(z, 0, 4), put(z, 0, 4);  // disk, attributes, local header at 0
  z += name;
  const std::size_t directory_size = z.size() - directory;
  put(z, 0x06054b50, 4), put(z, 0, 2), put(z, 0, 2), put(z, 1, 2), put(z, 1, 2), put(z, directory_size, 4), put(z, directory, 4), put(z, 0, 2);
  return z;
}

}  // namespace

TEST(ZipIntegrity, AHandBuiltArchivePassesAndEveryFlippedDataByteFails) {
  const std::string good = hello_zip();
  const ZipSummary s = verify_zip(good);
  EXPECT_EQ(s.entries, 1u);
  EXPECT_EQ(s.data_bytes, 5u);
  const std::size_t data_at = 30 + 1;
  for (std::size_t i = 0; i < 5; ++i) {
    std::string bad = good;
    bad[data_at + i] = static_cast<char>(bad[data_at + i] ^ 0x01);
    const std::string what = error_of([&] { verify_zip(bad); });
    EXPECT_TRUE(contains(what, "zip archive entry 'w' is damaged: its data fails the CRC-32 recorded when it was written (recorded 3610a686")) << what;
  }
  EXPECT_TRUE(contains(error_of([&] { verify_zip(good.substr(0, good.size() - 3)); }), "its end record is missing"));
  std::string moved = good;
  moved[moved.size() - 6] = 0x7f;  // the directory's offset points past the file
  EXPECT_TRUE(contains(error_of([&] { verify_zip(moved); }), "its directory lies outside the file"));
  EXPECT_TRUE(contains(error_of([&] { verify_zip("PK"); }), "not a zip archive"));
}

TEST(FileLimits, ADeviceThatNeverEndsIsReadToTheLimitAndRefused) {
  const auto dir = test::temp_dir("file_limits");
  std::filesystem::create_symlink("/dev/zero", dir / "zero.bvh");
  const std::string what = error_of([&] { load_bvh(dir / "zero.bvh"); });
  EXPECT_TRUE(contains(what, (dir / "zero.bvh").string() + ": more than 256 MiB, the most this reader takes")) << what;
  EXPECT_TRUE(contains(what, "set MIMIC_MAX_INPUT_MB to raise it")) << what;
}

TEST(FileLimits, MimicMaxInputMbReplacesEveryLimit) {
  const auto dir = test::temp_dir("file_limits_env");
  std::ofstream(dir / "two.txt") << std::string(2 * 1024 * 1024, 'x');
  EXPECT_EQ(read_text_file(dir / "two.txt").size(), 2u * 1024 * 1024);
  ::setenv("MIMIC_MAX_INPUT_MB", "1", 1);
  const std::string what = error_of([&] { read_text_file(dir / "two.txt"); });
  ::setenv("MIMIC_MAX_INPUT_MB", "many", 1);
  const std::string bad = error_of([&] { read_text_file(dir / "two.txt"); });
  ::unsetenv("MIMIC_MAX_INPUT_MB");
  EXPECT_TRUE(contains(what, "two.txt: more than 1 MiB")) << what;
  EXPECT_TRUE(contains(bad, "MIMIC_MAX_INPUT_MB='many': expected a positive number of MiB")) << bad;
}

// A valid 43 MB DeepMimic motion took 25 s and 2.4 GB in yaml-cpp; YAML and JSON are refused
// above 16 MiB before any parsing.
TEST(FileLimits, JsonAndYamlAboveSixteenMiBAreRefusedBeforeParsing) {
  std::string motion = "{\"Loop\": \"wrap\", \"Frames\": [";
  const std::string row = "[0.0333, 0, 0.8, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0],\n";
  while (motion.size() <= 16 * kMiB) motion += row;
  motion += row.substr(0, row.size() - 2) + "]}";
  const std::string what = error_of([&] { parse_deepmimic_motion(motion, "big.txt", builtin_jumping_jack().skeleton); });
  EXPECT_TRUE(contains(what, "big.txt: more than 16 MiB, the most this reader takes (YAML and JSON")) << what;
}

TEST(YamlKeys, AKeyGivenTwiceOrAKeyThatIsNotANameIsAnErrorNamingTheLine) {
  const YamlReader r("run.yaml");
  EXPECT_TRUE(contains(error_of([&] { r.parse("seed: 2\nseed: 3\n", "bad"); }), "run.yaml:2: key 'seed' is given twice (first on line 1)"));
  EXPECT_TRUE(contains(error_of([&] { r.parse("ppo:\n  clip: 0.2\n  epochs: 3\n  clip: 0.1\n", "bad"); }),
                       "run.yaml:4: key 'clip' is given twice (first on line 2)"));
  EXPECT_TRUE(contains(error_of([&] { r.parse("rewards:\n  - {source: gail, weight: 1, weight: 2}\n", "bad"); }), "key 'weight' is given twice"));
  // A key that is not a name (yaml-cpp would throw its own exception at the first lookup).
  EXPECT_TRUE(contains(error_of([&] { r.parse("env: {name: tracking, [512, 256], clip: x.txt}\n", "bad"); }),
                       "run.yaml:1: a key that is a list, where keys are names"));
  EXPECT_TRUE(contains(error_of([&] { r.parse("ppo:\n  ? {a: 1}\n  : 2\n", "bad"); }), "run.yaml:2: a key that is a mapping"));
  EXPECT_TRUE(contains(error_of([&] { r.parse("seed: 1\n: 2\n", "bad"); }), "run.yaml:2: a key that is empty"));
  // The same key in two mappings is fine.
  EXPECT_NO_THROW(r.parse("policy: {hidden: [8]}\nvalue: {hidden: [8]}\n", "bad"));
}

TEST(AtomicWrites, TheReplacedVersionIsKeptAndStaleTemporariesAreRemoved) {
  const auto dir = test::temp_dir("atomic_keep");
  write_file_atomic_keeping(dir / "c.pt", dir / "c.prev.pt", "one");
  EXPECT_FALSE(std::filesystem::exists(dir / "c.prev.pt"));
  write_file_atomic_keeping(dir / "c.pt", dir / "c.prev.pt", "two");
  write_file_atomic_keeping(dir / "c.pt", dir / "c.prev.pt", "three");
  EXPECT_EQ(read_text_file(dir / "c.pt"), "three");
  EXPECT_EQ(read_text_file(dir / "c.prev.pt"), "two");
  // What a kill in the middle of a write leaves: removed; everything else stays.
  std::ofstream(dir / "c.pt.tmp4242") << "half";
  std::ofstream(dir / "config.yaml.tmp17") << "half";
  std::ofstream(dir / "notes.tmp") << "mine";
  std::ofstream(dir / "a.tmp12x") << "mine";
  EXPECT_EQ(remove_stale_temporaries(dir), 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "c.pt.tmp4242"));
  EXPECT_TRUE(std::filesystem::exists(dir / "notes.tmp"));
  EXPECT_TRUE(std::filesystem::exists(dir / "a.tmp12x"));
  // An output under a file cannot be made: a named error, not an unexpected failure.
  const std::string what = error_of([&] { write_file_atomic(dir / "notes.tmp" / "x.yaml", "x"); });
  EXPECT_TRUE(contains(what, "notes.tmp: cannot create the directory")) << what;
}

TEST(TensorBoardResume, StepsAfterTheCheckpointAndACutRecordAreRemoved) {
  const auto dir = test::temp_dir("tensorboard_truncate");
  std::filesystem::path file;
  {
    TensorBoardWriter w(dir);
    for (int step = 1; step <= 5; ++step) w.scalar("return", step * 10.0, step);
    w.flush();
    file = w.path();
  }
  std::ofstream(file, std::ios::app | std::ios::binary) << std::string("\x20\0\0\0\0\0\0\0\x01\x02", 10);  // a record cut by a kill
  EXPECT_EQ(truncate_tensorboard_events(dir, 3), 3);  // steps 4 and 5, and the cut record
  const auto scalars = read_tensorboard_scalars(file);
  ASSERT_EQ(scalars.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(scalars[static_cast<std::size_t>(i)].step, i + 1);
  EXPECT_EQ(truncate_tensorboard_events(dir, 3), 0);  // nothing more to remove
}
