#pragma once
// TensorBoard scalar logging without TensorFlow or protobuf: an event file is a sequence of
// TFRecord-framed tensorflow.Event messages, and only the few fields scalars need are encoded.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace mimic {

// CRC-32C (Castagnoli), as TFRecord framing uses it (before masking).
uint32_t crc32c(std::string_view data);

// The serialized Event {wall_time, step, summary {value {tag, simple_value}}}; `value` is stored
// as a float, as TensorBoard's simple_value is.
std::string encode_scalar_event(const std::string& tag, double value, int64_t step,
                                double wall_time);

// Appends scalars to a new event file `dir/events.out.tfevents.<unix seconds>.<host>.<pid>[.n]`.
// Every writer creates its own file (a resumed run never appends to an old one). Records are
// buffered until flush() or destruction. Not thread-safe.
class TensorBoardWriter {
 public:
  // Creates `dir` if missing; throws Error naming the path if the file cannot be created.
  explicit TensorBoardWriter(const std::filesystem::path& dir);
  TensorBoardWriter(TensorBoardWriter&&) = default;
  TensorBoardWriter& operator=(TensorBoardWriter&&) = default;
  ~TensorBoardWriter();

  // Throws Error naming the file if the write fails.
  void scalar(const std::string& tag, double value, int64_t step);
  void flush();
  const std::filesystem::path& path() const { return path_; }

 private:
  void write_record(std::string_view payload);

  std::filesystem::path path_;
  std::ofstream out_;
};

struct TensorBoardScalar {
  std::string tag;
  double value;  // the stored float, widened
  int64_t step;
};

// A resumed run's event files, cut back to its checkpoint: every record of the event files in `dir`
// whose step is above `last_step` is removed (each file rewritten atomically), and so is everything
// from a file's first damaged record on (a record cut by a kill). The resumed writer then adds
// each later step once. Returns how many records were removed.
int truncate_tensorboard_events(const std::filesystem::path& dir, int64_t last_step);

// Every simple_value scalar in an event file, in file order. Checks both CRCs of every record;
// throws Error naming the file and the record index on a bad length, CRC, truncation or message.
std::vector<TensorBoardScalar> read_tensorboard_scalars(const std::filesystem::path& file);

}  // namespace mimic
