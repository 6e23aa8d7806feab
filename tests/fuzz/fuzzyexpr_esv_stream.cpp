// libFuzzer target: the CSV and NDJSON ESV readers and the batch conversion must handle any bytes with
// records or FormatErrors — never a crash, hang or other exception. The first byte picks the format.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/fuzzyexpr/esv_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fx = emoface::fuzzyexpr;
  if (size == 0) return 0;
  static const fx::Engine engine;
  fx::EsvReaderOptions ro;
  ro.format = (data[0] & 1) ? fx::StreamFormat::Ndjson : fx::StreamFormat::Csv;
  ro.clamp = (data[0] & 2) != 0;
  ro.max_line_bytes = 4096;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  try {
    fx::EsvReader reader(in, "fuzz", ro);
    fx::FmcvWriterOptions wo;
    wo.format = static_cast<fx::StreamFormat>((data[0] >> 2) % 3);
    wo.sides = (data[0] & 32) != 0;
    fx::FmcvWriter writer(wo, reader.extra_columns());
    fx::BatchOptions bo;
    bo.on_error = fx::OnError::Skip;
    std::size_t bytes = 0;
    fx::convert_stream(reader, writer, engine, bo, [&](std::string_view s) { bytes += s.size(); });
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
