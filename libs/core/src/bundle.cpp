#include "emoface/core/bundle.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "emoface/core/errors.hpp"

namespace emoface::core {

namespace fs = std::filesystem;

namespace {

// ".bundle<random>.<name>" beside the target: hidden, and the extension (.mp4, .glb) is kept for
// writers that choose the format by it.
std::string temp_name(const std::string& path) {
  static thread_local std::mt19937_64 gen{std::random_device{}()};
  char prefix[40];
  std::snprintf(prefix, sizeof prefix, ".bundle%016llx.", static_cast<unsigned long long>(gen()));
  const fs::path p(path);
  return (p.parent_path() / (prefix + p.filename().string())).string();
}

void write_whole(const std::string& temp, const std::string& target, std::string_view data) {
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw IoError(target + ": cannot write: " + std::strerror(errno));
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(temp.c_str());
      throw IoError(target + ": write failed: " + why);
    }
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(temp.c_str());
    throw IoError(target + ": write failed: " + why);
  }
}

}  // namespace

OutputBundle::~OutputBundle() {
  if (committed_) return;
  for (const Staged& f : files_)
    if (!f.temp.empty()) ::unlink(f.temp.c_str());
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
    std::error_code ec;
    fs::remove(*it, ec);  // only if empty: never a file someone else put there
  }
}

std::string OutputBundle::stage_path(const std::string& path) {
  if (path == "-") throw InvalidInput("OutputBundle: standard output cannot be staged as a path");
  add(path, {});  // checks, directories, an empty temporary file
  return files_.back().temp.empty() ? files_.back().target : files_.back().temp;
}

void OutputBundle::add(const std::string& path, std::string_view content) {
  if (committed_) throw InvalidInput("OutputBundle: already committed");
  if (path == "-") {
    if (stdout_) throw InvalidInput("OutputBundle: standard output staged twice");
    stdout_ = true;
    stdout_text_ = std::string(content);
    return;
  }
  if (path.empty()) throw InvalidInput("OutputBundle: empty path");
  const std::string target = fs::absolute(path).lexically_normal().string();
  for (const Staged& f : files_)
    if (f.target == target) throw InvalidInput("OutputBundle: \"" + path + "\" staged twice");
  // Parent directories, outermost first; remember the ones created here.
  const fs::path parent = fs::path(target).parent_path();
  std::vector<fs::path> missing;
  for (fs::path p = parent; !p.empty() && !fs::exists(p); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    std::error_code ec;
    if (!fs::create_directory(*it, ec) && ec)
      throw IoError(path + ": cannot create directory " + it->string() + ": " + ec.message());
    created_dirs_.push_back(it->string());
  }
  if (fs::is_directory(target)) throw IoError(path + ": is a directory");
  const fs::file_status st = fs::status(target);
  if (fs::exists(st) && !fs::is_regular_file(st)) {  // a device or FIFO: written, never replaced
    files_.push_back({target, "", std::string(content)});
    return;
  }
  const std::string temp = temp_name(target);
  write_whole(temp, path, content);
  files_.push_back({target, temp, {}});
}

void OutputBundle::commit() {
  if (committed_) throw InvalidInput("OutputBundle: already committed");
  for (std::size_t i = 0; i < files_.size(); ++i) {
    if (files_[i].temp.empty()) {  // device or FIFO
      std::FILE* f = std::fopen(files_[i].target.c_str(), "wb");
      const std::string& d = files_[i].direct;
      const bool ok = f && std::fwrite(d.data(), 1, d.size(), f) == d.size();
      if (f) std::fclose(f);
      if (!ok) throw IoError(files_[i].target + ": write failed");
      continue;
    }
    if (std::rename(files_[i].temp.c_str(), files_[i].target.c_str()) != 0) {
      const std::string message =
          files_[i].target + ": cannot rename into place: " + std::strerror(errno);
      for (std::size_t j = i; j < files_.size(); ++j)
        if (!files_[j].temp.empty()) ::unlink(files_[j].temp.c_str());
      files_.clear();
      created_dirs_.clear();  // files renamed before this one may live in them
      committed_ = true;
      throw IoError(message);
    }
  }
  committed_ = true;
  if (stdout_) {
    std::fwrite(stdout_text_.data(), 1, stdout_text_.size(), stdout);
    std::fflush(stdout);
  }
}

}  // namespace emoface::core
