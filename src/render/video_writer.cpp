#include "render/video_writer.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include "core/error.hpp"

namespace mimic {

VideoWriter::VideoWriter(const std::filesystem::path& out, int width, int height, double fps)
    : out_(out), width_(width), height_(height) {
  const std::string ext = out.extension().string();
  if (ext != ".mp4" && ext != ".gif") throw Error(out.string() + ": video must be .mp4 or .gif");
  if (width % 2 || height % 2) throw Error("video width and height must be even");
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  partial_ = out;
  partial_ += ".partial" + std::to_string(::getpid()) + ext;
  const std::string codec = ext == ".mp4" ? "-c:v libx264 -preset veryfast -crf 23 -pix_fmt yuv420p -movflags +faststart"
                                          : "-vf \"split[a][b];[a]palettegen[p];[b][p]paletteuse\"";
  const std::string cmd = fmt::format("ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -s {}x{} -r {} -i - {} -f {} '{}'",
                                      width, height, fps, codec, ext.substr(1), partial_.string());
  pipe_ = ::popen(cmd.c_str(), "w");
  if (!pipe_) throw Error("cannot start ffmpeg (install it with scripts/setup.sh)");
}

VideoWriter::~VideoWriter() {
  if (pipe_) {
    ::pclose(pipe_);
    std::error_code ec;
    std::filesystem::remove(partial_, ec);
  }
}

void VideoWriter::write(const std::vector<std::uint8_t>& rgb) {
  if (!pipe_) throw Error(out_.string() + ": video already closed");
  if (rgb.size() != static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3) throw Error("video frame has the wrong size");
  if (std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size()) throw Error(out_.string() + ": ffmpeg stopped accepting frames");
  ++frames_;
}

void VideoWriter::close() {
  if (!pipe_) return;
  const int status = ::pclose(pipe_);
  pipe_ = nullptr;
  std::error_code ec;
  if (status != 0 || frames_ == 0) {
    std::filesystem::remove(partial_, ec);
    throw Error(out_.string() + ": ffmpeg failed (exit status " + std::to_string(status) + ")");
  }
  std::filesystem::rename(partial_, out_, ec);
  if (ec) throw Error(out_.string() + ": cannot move the finished video into place: " + ec.message());
}

}  // namespace mimic
