#pragma once
// Writes RGB frames to an MP4 (H.264) or GIF by piping them into ffmpeg. The file appears only
// when close() succeeds (written beside it, then renamed), so a failed render never leaves a
// broken video where a good one was.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace mimic {

class VideoWriter {
 public:
  // Throws Error if ffmpeg cannot be started or the extension is not .mp4 or .gif.
  VideoWriter(const std::filesystem::path& out, int width, int height, double fps);
  ~VideoWriter();  // abandons an unclosed video (removes the partial file)
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  void write(const std::vector<std::uint8_t>& rgb);  // width*height*3, top row first
  void close();                                       // finishes the file; throws on failure
  int frames() const { return frames_; }

 private:
  std::filesystem::path out_, partial_;
  int width_, height_, frames_ = 0;
  std::FILE* pipe_ = nullptr;
};

}  // namespace mimic
