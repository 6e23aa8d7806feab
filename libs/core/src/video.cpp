#include "emoface/core/video.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "emoface/core/errors.hpp"
#include "emoface/core/image.hpp"
#include "emoface/core/version.hpp"

extern char** environ;

namespace emoface::core {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string format_for(const std::string& ext) {
  if (ext == ".mp4") return "mp4";
  if (ext == ".mov") return "mov";
  if (ext == ".mkv") return "matroska";
  if (ext == ".gif") return "gif";
  return {};
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// Unique per process and writer; the extension is kept so nothing guesses differently.
std::string temp_name(const std::string& path, const char* kind) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path p(path);
  const std::string name = "." + p.filename().string() + "." + kind + std::to_string(::getpid()) + "_" +
                           std::to_string(counter++) + p.extension().string();
  return (p.parent_path() / name).string();
}

// Spawns argv with stdin from `in_fd` (or /dev/null when -1), stdout to /dev/null, stderr to `log_path`.
int spawn(const std::vector<std::string>& args, int in_fd, int close_fd, const std::string& log_path) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (in_fd >= 0) {
    posix_spawn_file_actions_adddup2(&actions, in_fd, STDIN_FILENO);
  } else {
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  }
  if (close_fd >= 0) posix_spawn_file_actions_addclose(&actions, close_fd);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_path.empty() ? "/dev/null" : log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    errno = rc;
    return -1;
  }
  return pid;
}

int wait_exit(int pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// Writes all of `data` to a pipe without letting SIGPIPE kill the process: the signal is blocked in this
// thread for the write and a pending one is consumed (the usual technique for libraries, which must not
// change the process-wide disposition). Returns false when the reader has gone.
bool write_all_no_sigpipe(int fd, const std::uint8_t* data, std::size_t n) {
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &block, &old);
  bool ok = true;
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      ok = false;
      break;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  if (!ok && errno == EPIPE) {
    const timespec zero{0, 0};
    sigtimedwait(&block, nullptr, &zero);  // consume the SIGPIPE this write raised
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}

}  // namespace

void VideoOptions::validate() const {
  if (width < 1 || width > 16384 || height < 1 || height > 16384)
    throw InvalidInput("video size must be 1 … 16384 pixels per side, got " + std::to_string(width) + "x" +
                       std::to_string(height));
  if (!std::isfinite(fps) || fps <= 0.0 || fps > 1000.0)
    throw InvalidInput("video fps must be in (0, 1000], got " + number(fps));
  if (crf < 0 || crf > 51) throw InvalidInput("video crf must be 0 … 51, got " + std::to_string(crf));
  if (ffmpeg.empty()) throw InvalidInput("video: empty ffmpeg binary name");
}

bool ffmpeg_available(const std::string& binary) {
  const int pid = spawn({binary, "-hide_banner", "-version"}, -1, -1, "");
  return pid > 0 && wait_exit(pid) == 0;
}

VideoWriter::VideoWriter(std::string path, VideoOptions options) : path_(std::move(path)), options_(std::move(options)) {
  options_.validate();
  const std::string ext = lower_extension(path_);
  const std::string format = format_for(ext);
  if (format.empty())
    throw InvalidInput(path_ + ": unsupported video extension '" + ext + "' (use .mp4, .mov, .mkv or .gif)");
  const bool gif = format == "gif";
  if (gif && !options_.audio_path.empty()) throw InvalidInput(path_ + ": a GIF cannot carry audio");
  if (!options_.audio_path.empty() && !std::filesystem::is_regular_file(options_.audio_path))
    throw IoError(options_.audio_path + ": audio file not found");
  std::error_code ec;
  const auto dir = std::filesystem::path(path_).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    throw IoError(path_ + ": directory " + dir.string() + " does not exist");
  if (std::filesystem::is_directory(path_, ec)) throw IoError(path_ + ": is a directory");

  temp_path_ = temp_name(path_, "part");
  log_path_ = temp_name(path_ + ".log", "ffmpeg") + ".txt";
  const std::string size = std::to_string(options_.width) + "x" + std::to_string(options_.height);
  std::vector<std::string> args = {options_.ffmpeg, "-hide_banner", "-loglevel", "error", "-y",
                                   "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", size,
                                   "-framerate", number(options_.fps), "-i", "pipe:0"};
  if (!options_.audio_path.empty()) {
    args.insert(args.end(), {"-i", options_.audio_path, "-map", "0:v", "-map", "1:a", "-c:a", "aac", "-b:a", "128k"});
    if (options_.shortest) args.push_back("-shortest");
  }
  if (gif) {
    // One palette for the whole clip (two passes inside one filter graph), no dithering noise.
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=none"});
  } else {
    args.insert(args.end(), {"-c:v", "libx264", "-preset", "medium", "-crf", std::to_string(options_.crf),
                             "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"});
    if (format == "mp4" || format == "mov") args.insert(args.end(), {"-movflags", "+faststart"});
  }
  // Reproducible files: no encoder/muxer version strings or creation times beyond our own comment.
  args.insert(args.end(), {"-map_metadata", "-1", "-fflags", "+bitexact", "-flags:v", "+bitexact"});
  if (!options_.audio_path.empty()) args.insert(args.end(), {"-flags:a", "+bitexact"});
  args.insert(args.end(), {"-metadata", "comment=" + (options_.comment.empty() ? std::string(kGenerator) : options_.comment)});
  args.insert(args.end(), {"-f", format, temp_path_});

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw IoError(path_ + ": cannot create a pipe for ffmpeg: " + std::strerror(errno));
  pid_ = spawn(args, fds[0], fds[1], log_path_);
  const int spawn_errno = errno;
  ::close(fds[0]);
  if (pid_ < 0) {
    ::close(fds[1]);
    ::unlink(log_path_.c_str());
    throw IoError(path_ + ": cannot run '" + options_.ffmpeg + "' (" + std::strerror(spawn_errno) +
                  "); install the Debian package ffmpeg");
  }
  pipe_fd_ = fds[1];
}

VideoWriter::~VideoWriter() {
  if (!finished_) abort_process();
}

void VideoWriter::abort_process() noexcept {
  if (pipe_fd_ >= 0) {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
  }
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    wait_exit(pid_);
    pid_ = -1;
  }
  ::unlink(temp_path_.c_str());
  ::unlink(log_path_.c_str());
}

std::string VideoWriter::ffmpeg_errors() const {
  std::ifstream in(log_path_);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  if (text.size() > 600) text = "…" + text.substr(text.size() - 600);
  for (auto& c : text)
    if (c == '\n') c = ' ';
  return text.empty() ? std::string("no message") : text;
}

void VideoWriter::add_frame(const std::uint8_t* rgb) {
  if (finished_ || pipe_fd_ < 0) throw InvalidInput(path_ + ": video already finished");
  const std::size_t n = static_cast<std::size_t>(options_.width) * static_cast<std::size_t>(options_.height) * 3;
  if (!write_all_no_sigpipe(pipe_fd_, rgb, n)) {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
    if (pid_ > 0) wait_exit(pid_);
    pid_ = -1;
    const std::string message = path_ + ": ffmpeg stopped at frame " + std::to_string(frames_) + ": " + ffmpeg_errors();
    abort_process();
    finished_ = true;
    throw IoError(message);
  }
  ++frames_;
}

void VideoWriter::add_frame(const std::vector<std::uint8_t>& rgb) {
  const std::size_t n = static_cast<std::size_t>(options_.width) * static_cast<std::size_t>(options_.height) * 3;
  if (rgb.size() != n)
    throw InvalidInput(path_ + ": frame has " + std::to_string(rgb.size()) + " bytes, expected " + std::to_string(n) +
                       " (" + std::to_string(options_.width) + "x" + std::to_string(options_.height) + " RGB)");
  add_frame(rgb.data());
}

void VideoWriter::add_frame(const Image& frame) {
  if (frame.width != options_.width || frame.height != options_.height)
    throw InvalidInput(path_ + ": frame is " + std::to_string(frame.width) + "x" +
                       std::to_string(frame.height) + ", the video " +
                       std::to_string(options_.width) + "x" + std::to_string(options_.height));
  add_frame(frame.rgb);
}

void VideoWriter::finish() {
  if (finished_) throw InvalidInput(path_ + ": video already finished");
  if (frames_ == 0) throw InvalidInput(path_ + ": a video needs at least one frame");
  ::close(pipe_fd_);
  pipe_fd_ = -1;
  const int code = wait_exit(pid_);
  pid_ = -1;
  if (code != 0) {
    const std::string message = path_ + ": ffmpeg failed (exit " + std::to_string(code) + "): " + ffmpeg_errors();
    abort_process();
    finished_ = true;
    throw IoError(message);
  }
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const std::string message = path_ + ": cannot rename the finished video: " + std::strerror(errno);
    abort_process();
    finished_ = true;
    throw IoError(message);
  }
  ::unlink(log_path_.c_str());
  finished_ = true;
}

}  // namespace emoface::core
