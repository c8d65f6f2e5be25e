#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <unistd.h>

#include "core/error.hpp"
#include "core/tensorboard.hpp"

using namespace mimic;
namespace fs = std::filesystem;

namespace {

// A fresh directory under the system temp dir, removed with everything in it at the end.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto ticks = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = fs::temp_directory_path() /
            ("mimic_tb_test_" + std::to_string(::getpid()) + "_" + std::to_string(ticks) + "_" +
             std::to_string(counter++));
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Expects reading `file` to fail with an Error naming the file and `what` (e.g. the record).
void expect_read_error(const fs::path& file, const std::string& what) {
  try {
    read_tensorboard_scalars(file);
    ADD_FAILURE() << "no error reading " << file;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

// A file with a version record and three scalars (records 0..3).
fs::path write_sample(const fs::path& dir) {
  TensorBoardWriter w(dir);
  w.scalar("loss", 0.5, 1);
  w.scalar("loss", 0.25, 2);
  w.scalar("reward/mean", 12.0, 3);
  return w.path();
}

}  // namespace

TEST(TensorBoard, Crc32cKnownValues) {
  EXPECT_EQ(crc32c("123456789"), 0xE3069283u);
  EXPECT_EQ(crc32c(""), 0u);
}

TEST(TensorBoard, EncodesScalarEventBytes) {
  // Event {wall_time: 0.0 (1, fixed64), step: 3 (2, varint),
  //        summary (5) {value (1) {tag (1): "a", simple_value (2, fixed32): 1.0f}}}
  const std::string expected(
      "\x09\x00\x00\x00\x00\x00\x00\x00\x00"  // wall_time
      "\x10\x03"                              // step
      "\x2a\x0a"                              // summary, 10 bytes
      "\x0a\x08"                              // value, 8 bytes
      "\x0a\x01"
      "a"                                     // tag
      "\x15\x00\x00\x80\x3f",                 // simple_value, little-endian 1.0f
      23);
  EXPECT_EQ(encode_scalar_event("a", 1.0, 3, 0.0), expected);

  // wall_time 1.5 = 0x3FF8000000000000; step 300 = varint ac 02; value -2.0f = 0xC0000000.
  const std::string expected2(
      "\x09\x00\x00\x00\x00\x00\x00\xf8\x3f"
      "\x10\xac\x02"
      "\x2a\x0b\x0a\x09\x0a\x02xy\x15\x00\x00\x00\xc0",
      25);
  EXPECT_EQ(encode_scalar_event("xy", -2.0, 300, 1.5), expected2);
}

TEST(TensorBoard, WritesAndReadsBackScalars) {
  TempDir dir;
  const fs::path file = [&] {
    TensorBoardWriter w(dir.path() / "run");  // created if missing
    w.scalar("loss", 0.1, 0);
    w.scalar("loss", 0.05, 10);
    w.scalar("reward/mean", 123.456, 20);
    w.scalar("negative_step", -1.0, -1);
    w.flush();
    EXPECT_EQ(read_tensorboard_scalars(w.path()).size(), 4u);  // flushed while still open
    return w.path();
  }();
  EXPECT_EQ(file.parent_path(), dir.path() / "run");
  EXPECT_EQ(file.filename().string().rfind("events.out.tfevents.", 0), 0u) << file;

  const std::vector<TensorBoardScalar> s = read_tensorboard_scalars(file);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].tag, "loss");
  EXPECT_EQ(s[0].step, 0);
  EXPECT_EQ(s[0].value, static_cast<double>(0.1f));
  EXPECT_EQ(s[1].tag, "loss");
  EXPECT_EQ(s[1].step, 10);
  EXPECT_EQ(s[1].value, static_cast<double>(0.05f));
  EXPECT_EQ(s[2].tag, "reward/mean");
  EXPECT_EQ(s[2].step, 20);
  EXPECT_EQ(s[2].value, static_cast<double>(123.456f));
  EXPECT_EQ(s[3].tag, "negative_step");
  EXPECT_EQ(s[3].step, -1);
  EXPECT_EQ(s[3].value, -1.0);
}

TEST(TensorBoard, CorruptionIsReportedWithFileAndRecord) {
  TempDir dir;
  const fs::path file = write_sample(dir.path());
  const std::string good = read_bytes(file);
  ASSERT_EQ(read_tensorboard_scalars(file).size(), 3u);

  std::string bad = good;
  bad[bad.size() - 6] = static_cast<char>(bad[bad.size() - 6] ^ 0x01);  // last record's data
  write_bytes(file, bad);
  expect_read_error(file, "record 3");
  expect_read_error(file, "CRC");

  bad = good;
  bad[0] = static_cast<char>(bad[0] ^ 0x40);  // first record's length
  write_bytes(file, bad);
  expect_read_error(file, "record 0");

  write_bytes(file, good.substr(0, good.size() - 1));  // last record cut short
  expect_read_error(file, "record 3");
}

TEST(TensorBoard, EachWriterCreatesItsOwnFile) {
  TempDir dir;
  {
    TensorBoardWriter a(dir.path());
    TensorBoardWriter b(dir.path());  // same second, same process
    EXPECT_NE(a.path(), b.path());
    a.scalar("a", 1.0, 1);
    b.scalar("b", 2.0, 2);
    a.flush();
    b.flush();
    ASSERT_EQ(read_tensorboard_scalars(a.path()).size(), 1u);
    EXPECT_EQ(read_tensorboard_scalars(a.path())[0].tag, "a");
    ASSERT_EQ(read_tensorboard_scalars(b.path()).size(), 1u);
    EXPECT_EQ(read_tensorboard_scalars(b.path())[0].tag, "b");
  }
  // A resumed run never appends to an existing file.
  TensorBoardWriter c(dir.path());
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 3);
}

TEST(TensorBoard, UnopenableDirectoryIsAnError) {
  TempDir dir;
  fs::create_directories(dir.path());
  const fs::path blocker = dir.path() / "not_a_dir";
  write_bytes(blocker, "x");
  try {
    TensorBoardWriter w(blocker / "run");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(blocker.string()), std::string::npos) << e.what();
  }
}
