#include "emoface/cli/cli.hpp"

#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>

#include "emoface/core/errors.hpp"

namespace emoface::cli {

std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << app.get_name() << ": usage error: " << e.what() << " (see --help)\n";
    return kExitUsage;
  }
  return std::nullopt;
}

int run(std::string_view tool, const std::function<int()>& body) {
  auto report = [&](const char* kind, const char* what) {
    std::cerr << tool << ": " << kind << ": " << what << '\n';
  };
  try {
    return body();
  } catch (const UsageError& e) {
    std::cerr << tool << ": usage error: " << e.what() << " (see --help)\n";
    return kExitUsage;
  } catch (const FormatError& e) {
    report("error", e.what());
    return kExitInput;
  } catch (const IoError& e) {
    report("error", e.what());
    return kExitInput;
  } catch (const InvalidInput& e) {
    report("error", e.what());
    return kExitInput;
  } catch (const NumericalError& e) {
    report("numerical error", e.what());
    return kExitNumerical;
  } catch (const std::exception& e) {
    report("internal error", e.what());
    return kExitInternal;
  } catch (...) {
    report("internal error", "unknown exception");
    return kExitInternal;
  }
}

Shard parse_shard(std::string_view text) {
  try {
    return core::parse_shard(text);
  } catch (const InvalidInput& e) {
    throw UsageError(e.what());
  }
}

Output::Output(const std::string& path) {
  if (path != "-") file_ = std::make_unique<core::AtomicFile>(path);
}

void Output::write(std::string_view data) {
  if (file_) {
    buffer_.append(data);
    if (buffer_.size() >= (1u << 20)) {
      file_->write(buffer_);
      buffer_.clear();
    }
  } else {
    std::fwrite(data.data(), 1, data.size(), stdout);
  }
}

void Output::commit() {
  if (file_) {
    file_->write(buffer_);
    buffer_.clear();
    file_->commit();
  } else if (std::fflush(stdout) != 0) {
    throw IoError("<stdout>: write failed");
  }
}

Input::Input(const std::string& path, bool rewindable) : name_(path == "-" ? "<stdin>" : path) {
  if (path != "-") {
    auto file = std::make_unique<std::ifstream>(path, std::ios::binary);
    if (!*file) throw IoError(path + ": cannot open for reading");
    owned_ = std::move(file);
  } else if (rewindable) {
    std::ostringstream all;
    all << std::cin.rdbuf();
    owned_ = std::make_unique<std::istringstream>(all.str());
  }
  in_ = owned_ ? owned_.get() : &std::cin;
}

void Input::rewind() {
  if (!owned_) throw InvalidInput(name_ + ": cannot rewind standard input");
  in_->clear();
  in_->seekg(0);
}

ProgressBar::ProgressBar(std::string tool, bool quiet)
    : tool_(std::move(tool)), quiet_(quiet), tty_(::isatty(2) == 1) {}

void ProgressBar::update(std::string_view stage, std::size_t done, std::size_t total) {
  if (quiet_ || total == 0) return;
  const int pct = static_cast<int>(100 * done / total);
  const bool same_stage = stage == stage_;
  if (tty_) {
    if (pct == last_pct_ && same_stage) return;
    const int width = 30, filled = width * pct / 100;
    std::fprintf(stderr, "\r%-10.10s [%s%s] %3d%% %zu/%zu", std::string(stage).c_str(),
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), '.').c_str(), pct, done,
                 total);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  } else if (pct / 10 != last_pct_ / 10 || !same_stage || done == total) {
    if (!(done == total && pct == last_pct_ && same_stage))
      std::fprintf(stderr, "%s: %s %d%% (%zu/%zu)\n", tool_.c_str(), std::string(stage).c_str(),
                   pct, done, total);
  }
  last_pct_ = pct;
  stage_ = std::string(stage);
}

}  // namespace emoface::cli
