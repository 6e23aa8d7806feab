#pragma once
// Video files from RGB frames through the ffmpeg binary (Debian package `ffmpeg`): frames are piped raw
// into one ffmpeg process (no temporary images), the result is written to a temporary file beside the
// target and renamed on `finish()`, so a failed or abandoned video leaves nothing behind.
// The container follows the extension: .mp4 .mov .mkv (H.264, yuv420p) or .gif (palette per video).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace emoface::core {

struct Image;  // image.hpp

struct VideoOptions {
  int width = 0;              ///< frame width, pixels, 1 … 16384
  int height = 0;             ///< frame height, pixels, 1 … 16384
  double fps = 25.0;          ///< frames per second, (0, 1000]
  std::string audio_path;     ///< optional audio file (e.g. WAV) muxed in (AAC); not for .gif
  bool shortest = true;       ///< with audio: stop at the shorter of video and audio
  int crf = 20;               ///< H.264 constant rate factor, 0 (lossless) … 51
  std::string ffmpeg = "ffmpeg";  ///< binary name (searched in PATH) or path
  std::string comment;        ///< stored as the container's comment metadata (e.g. the generator stamp)
  void validate() const;      ///< throws InvalidInput
};

/// True when `binary -version` runs and exits 0.
bool ffmpeg_available(const std::string& binary = "ffmpeg");

/// Streams frames into a video file. Not copyable; one writer per file.
/// Frames are `width * height * 3` bytes, RGB, row-major, top row first.
class VideoWriter {
 public:
  /// Starts ffmpeg. Throws InvalidInput for bad options or an unsupported extension, IoError when ffmpeg
  /// cannot be started (e.g. not installed).
  VideoWriter(std::string path, VideoOptions options);
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  /// Without `finish()`: stops ffmpeg and removes the temporary file; the target is left untouched.
  ~VideoWriter();

  void add_frame(const std::uint8_t* rgb);           ///< throws IoError if ffmpeg died (message has its stderr)
  void add_frame(const std::vector<std::uint8_t>& rgb);  ///< also checks the size (InvalidInput)
  void add_frame(const Image& frame);  ///< also checks that frame is width × height (InvalidInput)
  /// Closes the stream, waits for ffmpeg, and renames the temporary file to the target. Needs ≥ 1
  /// frame.
  void finish();

  std::size_t frames() const noexcept { return frames_; }
  const std::string& path() const noexcept { return path_; }

 private:
  void abort_process() noexcept;
  std::string ffmpeg_errors() const;

  std::string path_;
  std::string temp_path_;
  std::string log_path_;
  VideoOptions options_;
  int pipe_fd_ = -1;
  int pid_ = -1;
  std::size_t frames_ = 0;
  bool finished_ = false;
};

}  // namespace emoface::core
