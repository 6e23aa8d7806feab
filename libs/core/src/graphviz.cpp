#include "emoface/core/graphviz.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

extern char** environ;

namespace emoface::core {

namespace {

// Runs args with stdin/stdout from/to /dev/null and stderr into `log`; returns the exit code (-1:
// not run).
int run(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.empty() ? "/dev/null" : log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

}  // namespace

std::string dot_quote(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

bool graphviz_available(const std::string& binary) { return run({binary, "-V"}, "") == 0; }

void render_dot(std::string_view dot, const std::string& path, const std::string& binary) {
  const std::filesystem::path p(path);
  const std::string ext = p.extension().string();
  if (ext != ".svg" && ext != ".png" && ext != ".pdf")
    throw InvalidInput("render_dot: \"" + path + "\": the extension must be .svg, .png or .pdf");
  const std::string stem =
      (p.parent_path() / ("." + p.filename().string() + "." + std::to_string(::getpid()))).string();
  const std::string in = stem + ".dot", out = stem + ext, log = stem + ".log";
  write_file_atomic(in, dot);
  const int rc = run({binary, "-T" + ext.substr(1), "-o", out, in}, log);
  std::string first;
  {
    std::ifstream l(log);
    std::getline(l, first);
  }
  std::filesystem::remove(in);
  std::filesystem::remove(log);
  if (rc != 0) {
    std::filesystem::remove(out);
    throw IoError(
        rc < 0
            ? "render_dot: cannot run \"" + binary + "\" (install Graphviz: scripts/setup.sh)"
            : "render_dot: \"" + binary + "\" failed (exit " + std::to_string(rc) + "): " + first);
  }
  std::error_code ec;
  std::filesystem::rename(out, path, ec);
  if (ec) {
    std::filesystem::remove(out);
    throw IoError("render_dot: cannot write \"" + path + "\": " + ec.message());
  }
}

void write_dot(std::string_view dot, const std::string& path, const std::string& binary) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".svg" || ext == ".png" || ext == ".pdf") return render_dot(dot, path, binary);
  if (path == "-") {
    std::fwrite(dot.data(), 1, dot.size(), stdout);
    std::fflush(stdout);
    return;
  }
  write_file_atomic(path, dot);
}

}  // namespace emoface::core
