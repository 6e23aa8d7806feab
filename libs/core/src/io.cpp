#include "emoface/core/io.hpp"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

#include "emoface/core/version.hpp"

namespace emoface::core {

std::string FormatVersion::to_string() const {
  return std::to_string(major) + "." + std::to_string(minor);
}

FormatVersion parse_format_version(std::string_view text) {
  auto dot = text.find('.');
  auto parse_int = [&](std::string_view part) {
    int value = -1;
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || ec != std::errc() || ptr != part.data() + part.size() || value < 0)
      throw InvalidInput("bad version \"" + std::string(text) + "\" (expected \"MAJOR.MINOR\")");
    return value;
  };
  if (dot == std::string_view::npos)
    throw InvalidInput("bad version \"" + std::string(text) + "\" (expected \"MAJOR.MINOR\")");
  return {parse_int(text.substr(0, dot)), parse_int(text.substr(dot + 1))};
}

nlohmann::ordered_json make_envelope(std::string_view kind, FormatVersion version) {
  nlohmann::ordered_json doc = nlohmann::ordered_json::object();
  doc["format"] = "emoface." + std::string(kind);
  doc["version"] = version.to_string();
  doc["generator"] = kGenerator;
  return doc;
}

std::string ndjson_header(std::string_view kind, FormatVersion version) {
  return make_envelope(kind, version).dump() + "\n";
}

namespace {
template <class J>
bool stream_header(const J& record) {
  if (!record.is_object() || record.size() > 3) return false;
  const auto format = record.find("format");
  if (format == record.end() || !format->is_string() || format->template get_ref<const std::string&>().rfind("emoface.", 0) != 0)
    return false;
  for (auto it = record.begin(); it != record.end(); ++it)
    if (it.key() != "format" && it.key() != "version" && it.key() != "generator") return false;
  return true;
}
}  // namespace

bool is_stream_header(const nlohmann::json& record) { return stream_header(record); }
bool is_stream_header(const nlohmann::ordered_json& record) { return stream_header(record); }

std::string read_file(const std::string& path, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading: " + std::strerror(errno));
  std::string content;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    auto got = static_cast<std::size_t>(in.gcount());
    if (content.size() + got > max_bytes)
      throw IoError(path + ": file is larger than the limit of " + std::to_string(max_bytes) +
                    " bytes");
    content.append(buffer, got);
  }
  if (in.bad()) throw IoError(path + ": read error");
  return content;
}

nlohmann::ordered_json parse_json(std::string_view text, const std::string& file) {
  try {
    return nlohmann::ordered_json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // Locate the byte offset nlohmann reports as a line and column.
    SourceLocation where;
    where.file = file;
    std::size_t offset = e.byte == 0 ? 0 : e.byte - 1;
    if (offset > text.size()) offset = text.size();
    where.line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < offset; ++i) {
      if (text[i] == '\n') {
        ++where.line;
        line_start = i + 1;
      }
    }
    where.column = offset - line_start + 1;
    std::string message = e.what();
    // nlohmann's text starts with "[json.exception.parse_error.101] parse error at line 1, column 2: ".
    auto colon = message.find(": ");
    if (colon != std::string::npos) message = message.substr(colon + 2);
    throw FormatError(where, "invalid JSON: " + message);
  } catch (const nlohmann::json::exception& e) {
    // e.g. out_of_range 406 "number overflow" for 1e999: nlohmann reports no position for these.
    std::string message = e.what();
    auto bracket = message.find("] ");
    if (bracket != std::string::npos) message = message.substr(bracket + 2);
    throw FormatError(SourceLocation{file, "", 0, 0}, "invalid JSON: " + message);
  }
}

nlohmann::ordered_json read_json_file(const std::string& path, std::size_t max_bytes) {
  return parse_json(read_file(path, max_bytes), path);
}

namespace {

std::string temp_name_for(const std::string& path) {
  static thread_local std::mt19937_64 gen{std::random_device{}()};
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, ".tmp%016llx", static_cast<unsigned long long>(gen()));
  return path + suffix;
}

void write_all(int fd, std::string_view data, const std::string& path) {
  while (!data.empty()) {
    ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(path + ": write failed: " + std::strerror(errno));
    }
    data.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw InvalidInput("AtomicFile: empty output path");
  std::string target = path_;
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw IoError(path_ + ": is a directory");
    // A device or FIFO (/dev/null, /dev/stdout, a pipe): renaming over it would replace the device
    // node, so write to it directly. Atomicity does not apply to such targets.
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) throw IoError(path_ + ": cannot open output: " + std::strerror(errno));
    direct_ = true;
    return;
  }
  // A symbolic link to a file: replace the file it points to, not the link.
  char resolved[PATH_MAX];
  struct stat lst {};
  if (::lstat(path_.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode) && ::realpath(path_.c_str(), resolved))
    target = resolved;
  target_path_ = target;
  temp_path_ = temp_name_for(target);
  fd_ = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError(path_ + ": cannot create output file: " + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !direct_) ::unlink(temp_path_.c_str());
}

void AtomicFile::write(std::string_view data) {
  if (committed_) throw InvalidInput("AtomicFile::write after commit: " + path_);
  write_all(fd_, data, path_);
}

void AtomicFile::commit() {
  if (committed_) return;
  if (direct_) {
    const int rc = ::close(fd_);
    fd_ = -1;
    committed_ = true;
    if (rc != 0) throw IoError(path_ + ": close failed: " + std::strerror(errno));
    return;
  }
  if (::fsync(fd_) != 0 && errno != EINVAL)
    throw IoError(path_ + ": fsync failed: " + std::strerror(errno));
  int rc = ::close(fd_);
  fd_ = -1;
  if (rc != 0) throw IoError(path_ + ": close failed: " + std::strerror(errno));
  if (std::rename(temp_path_.c_str(), target_path_.c_str()) != 0)
    throw IoError(path_ + ": cannot move the finished file into place: " + std::strerror(errno));
  committed_ = true;
}

void write_file_atomic(const std::string& path, std::string_view content) {
  AtomicFile file(path);
  file.write(content);
  file.commit();
}

std::string json_pointer_token(std::string_view token) {
  std::string out;
  for (char c : token) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

}  // namespace emoface::core
