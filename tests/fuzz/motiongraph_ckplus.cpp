// libFuzzer target: the CK+ directory reader must reject bad input with an emoface error, never
// crash or hang (its per-file parsers alone: fuzz_motiongraph_ck_files, much faster). The input,
// split at 0xFF bytes, is a small CK+ tree: each chunk's first byte picks subject (bits 0–1),
// sequence (bits 2–3), file kind (bit 4: landmarks / emotion) and frame (bits 5–7); the rest is the
// file's content. The tree lives in a private temporary directory, rebuilt for every input and read
// with on_error stop and skip. Keep inputs short (-max_len=2048): every chunk is a file. Seeds:
// tests/fuzz/corpus/motiongraph_ckplus (see the command in tests/fuzz/CMakeLists.txt).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/io.hpp"

namespace fs = std::filesystem;
namespace mg = emoface::motiongraph;

namespace {
const fs::path& root() {
  static const fs::path dir = [] {
    std::error_code ec;  // a RAM disk when there is one: the tree is rewritten for every input
    const fs::path base =
        fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string tmpl = (base / "emoface_fuzz_ckplus_XXXXXX").string();
    if (!mkdtemp(tmpl.data())) std::abort();
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(root(), ec);
    });
    return fs::path(tmpl);
  }();
  return dir;
}

template <class F>
void guarded(F&& f) {
  try {
    f();
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);

  const fs::path& dir = root();
  std::error_code ec;
  fs::remove_all(dir / "Landmarks", ec);
  fs::remove_all(dir / "Emotion", ec);
  fs::create_directories(dir / "Landmarks", ec);
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\xff', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view chunk = text.substr(pos, end - pos);
    pos = end + 1;
    if (chunk.empty()) continue;
    const unsigned sel = static_cast<unsigned char>(chunk[0]);
    char subject[8], seq[8];
    std::snprintf(subject, sizeof subject, "S%03u", sel & 3u);
    std::snprintf(seq, sizeof seq, "%03u", (sel >> 2) & 3u);
    const bool emotion = (sel >> 4) & 1u;
    const fs::path d = dir / (emotion ? "Emotion" : "Landmarks") / subject / seq;
    fs::create_directories(d, ec);
    char name[64];
    std::snprintf(name, sizeof name, "%s_%s_%08u_%s.txt", subject, seq, (sel >> 5) + 1u,
                  emotion ? "emotion" : "landmarks");
    std::ofstream(d / name, std::ios::binary)
        .write(chunk.data() + 1, static_cast<std::streamsize>(chunk.size() - 1));
  }
  for (int k = 0; k < 2; ++k) {  // stop, labelled only; skip, unlabelled kept
    mg::CkPlusOptions o;
    o.keep_unlabelled = k == 1;
    o.on_error = k == 1 ? mg::OnError::Skip : mg::OnError::Stop;
    mg::ReadReport report;
    guarded([&] { (void)mg::read_ck_plus(dir.string(), o, &report); });
  }
  return 0;
}
