#pragma once
// Integrity of a zip archive held in memory (LibTorch's checkpoints are zip files of stored
// tensors and a few deflated code entries): the central directory is walked and every entry's
// data is checked against the CRC-32 the archive recorded for it when it was written. A flipped bit anywhere in
// the weights, a cut or a spliced file fails here, before anything reads a value.
#include <cstddef>
#include <string>
#include <string_view>

namespace mimic {

struct ZipSummary {
  std::size_t entries = 0;
  std::size_t data_bytes = 0;  // the entries' data, all checked
};

// Throws Error (without the file's name: the caller adds it) on the first problem: no end
// record, a directory or header outside the file, an entry compressed by a method other than
// stored or deflated, one that does not inflate, or an entry whose data does not match its
// CRC-32 (naming the entry).
ZipSummary verify_zip(std::string_view bytes);

}  // namespace mimic
