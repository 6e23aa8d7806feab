#pragma once
// Glue shared by every emoface command-line app (CONVENTIONS.md, "Errors"):
// fixed exit codes, one-line error messages on stderr, --shard i/N, and outputs written atomically.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/shard.hpp"

namespace emoface::cli {

/// Fixed exit codes of every app.
enum ExitCode : int {
  kExitOk = 0,         ///< success
  kExitUsage = 1,      ///< bad command line
  kExitInput = 2,      ///< bad input file or content (InvalidInput, FormatError, IoError)
  kExitNumerical = 3,  ///< NumericalError
  kExitInternal = 4,   ///< anything else
};

/// A bad option value found after parsing (unknown enum name, malformed --shard): exit code 1.
class UsageError : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

/// Parses the command line; on --help/--version prints and returns kExitOk, on a usage error prints
/// one line and returns kExitUsage; returns std::nullopt when the app should go on.
std::optional<int> parse(CLI::App& app, int argc, char** argv);

/// Runs `body`, mapping exceptions to one line "<tool>: error: <message>" on stderr and the exit
/// codes above. Returns body's result when it does not throw.
int run(std::string_view tool, const std::function<int()>& body);

/// Looks up an enum value by name with `parse` (returning std::optional); UsageError naming `flag`
/// and the accepted values otherwise.
template <class Enum, class Parse>
Enum parse_enum(const std::string& text, Parse parse, const char* flag, const char* accepted) {
  if (auto v = parse(text)) return *v;
  throw UsageError(std::string(flag) + ": unknown value \"" + text + "\" (expected " + accepted + ")");
}

/// --shard i/N | auto: core::Shard (contiguous blocks: owns(item, total); the Slurm array variables
/// for "auto"; docs/scale-out.md).
using core::Shard;

/// core::parse_shard, with its errors as UsageError (exit code 1).
Shard parse_shard(std::string_view text);

/// The one progress display of the apps (issue 18): on a terminal (stderr is a TTY) a bar redrawn
/// in place, "stage      [#####.....]  50% 5/10"; otherwise — a log file, a pipe — one plain line
/// per 10 % and per stage, "<tool>: stage 50% (5/10)"; nothing when quiet.
class ProgressBar {
 public:
  ProgressBar(std::string tool, bool quiet);
  /// Reports `done` of `total` items of `stage` (total 0: ignored).
  void update(std::string_view stage, std::size_t done, std::size_t total);
  bool on_terminal() const noexcept { return tty_; }

 private:
  std::string tool_;
  bool quiet_, tty_;
  int last_pct_ = -1;
  std::string stage_;
};

/// An input stream that is either stdin ("-") or a file. With `rewindable`, stdin is read into
/// memory once so the input can be read twice (a first pass counting records for --shard).
class Input {
 public:
  Input(const std::string& path, bool rewindable);
  std::istream& stream() noexcept { return *in_; }
  /// The file name, or "<stdin>".
  const std::string& name() const noexcept { return name_; }
  /// Back to the start (only when rewindable or a file).
  void rewind();

 private:
  std::string name_;
  std::unique_ptr<std::istream> owned_;
  std::istream* in_ = nullptr;
};

/// An output stream that is either stdout ("-") or a file written atomically: nothing appears at
/// `path` unless commit() is called.
class Output {
 public:
  explicit Output(const std::string& path);
  void write(std::string_view data);
  void commit();
  bool is_stdout() const noexcept { return !file_; }

 private:
  std::unique_ptr<core::AtomicFile> file_;
  std::string buffer_;
};

}  // namespace emoface::cli
