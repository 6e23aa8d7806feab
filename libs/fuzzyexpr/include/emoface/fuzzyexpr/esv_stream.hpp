#pragma once
// Line-oriented ESV input and FMCV output for batch conversion (the emo2muscle CLI and any pipeline):
// CSV with a header row or NDJSON in, CSV / NDJSON / JSON out. Records are independent, so a stream can
// be split across processes and concatenated back.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/text.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"

namespace emoface::fuzzyexpr {

enum class StreamFormat : std::uint8_t { Csv, Ndjson, Json };
std::string_view to_string(StreamFormat f) noexcept;
std::optional<StreamFormat> stream_format_from_string(std::string_view s) noexcept;
/// By file extension: .csv → Csv, .ndjson/.jsonl → Ndjson, .json → Json; otherwise nullopt.
std::optional<StreamFormat> stream_format_from_path(std::string_view path) noexcept;

struct EsvReaderOptions {
  StreamFormat format = StreamFormat::Csv;  ///< Csv or Ndjson
  /// Clamp finite out-of-range intensities into [0, 1] instead of rejecting them (NaN/inf always fail).
  bool clamp = false;
  /// Longest accepted line in bytes (without the newline); longer lines are an error. ≥ 64.
  std::size_t max_line_bytes = std::size_t{1} << 20;
  void validate() const;
};

/// One input record.
struct EsvRecord {
  std::size_t line = 0;   ///< 1-based line number in the input
  std::size_t index = 0;  ///< 0-based record ordinal (header excluded, bad records included)
  Esv esv{};
  std::vector<std::string> extra;  ///< CSV: the non-emotion fields, in header order
  std::string extra_json;          ///< NDJSON: the non-emotion members as JSON text, e.g. "\"id\":7"
};

/// Reads ESV records. CSV: the header names the six emotions (any order, case-insensitive; each exactly
/// once) and any other columns, which are passed through. NDJSON: one object per line with the six
/// emotion fields (case-insensitive, each once) and any other members. A UTF-8 byte-order mark is
/// skipped; other encodings are rejected.
class EsvReader {
 public:
  /// Reads the CSV header at once (FormatError if it is bad). `name` names the stream in errors.
  EsvReader(std::istream& in, std::string name, EsvReaderOptions options = {});
  ~EsvReader();
  EsvReader(const EsvReader&) = delete;
  EsvReader& operator=(const EsvReader&) = delete;

  /// The next record; false at the end of the input. A bad record throws FormatError naming the
  /// stream, line and column (CSV: the field number; NDJSON: the byte column when known); the reader
  /// stays usable and the next call continues with the following line.
  bool next(EsvRecord& record);

  /// CSV: names of the passed-through columns, in header order (empty for NDJSON).
  const std::vector<std::string>& extra_columns() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct FmcvWriterOptions {
  StreamFormat format = StreamFormat::Csv;
  /// Write the 35 left/right face parameters (side_parameter_names()) instead of the 19 muscles.
  bool sides = false;
  /// Digits after the decimal point for levels. Range 1–17.
  int precision = 6;
  /// Optional: write `mapped_columns` instead of the muscles / sides, computed from the 35 side
  /// parameters by `map` (which writes mapped_columns.size() values; e.g. faceweights' FACS or ARKit
  /// weights for emo2muscle --weights). Both set or both empty.
  std::vector<std::string> mapped_columns;
  std::function<void(const SideParameters& sides, double* out)> map;
  void validate() const;
};

/// Formats converted records. CSV: header of the passed-through columns then the parameter names.
/// NDJSON: one object per record, passed-through members first. JSON: one "emoface.fmcv" 1.0 document
/// {"format", "version", "generator", "parameters": [names], "rows": [objects as in NDJSON]}.
class FmcvWriter {
 public:
  FmcvWriter(FmcvWriterOptions options, std::vector<std::string> extra_columns);
  std::string begin() const;
  void append(std::string& out, const EsvRecord& record, const Fmcv& fmcv);
  std::string end() const;
  const std::vector<std::string>& parameter_names() const noexcept { return names_; }

 private:
  FmcvWriterOptions options_;
  std::vector<std::string> extra_;
  std::vector<std::string> names_;
  std::string zero_;  // 0 formatted at the chosen precision
  std::vector<double> mapped_;  // scratch for options_.map
  std::size_t rows_ = 0;
};

/// Stop: the first bad record ends the batch (its FormatError propagates); Skip: bad records are
/// counted and skipped, the good ones converted. The one OnError of core (emoface/core/text.hpp).
using core::on_error_from_string;
using core::OnError;
using core::to_string;

struct BatchOptions {
  OnError on_error = OnError::Stop;
  /// This process converts the contiguous block of records core::Shard{shard_index, shard_count}
  /// .block(total_records) gives, so N processes with shards 0/N … N−1/N together convert the
  /// stream once and their outputs, merged in shard order (core::merge_shard_outputs), are the
  /// output of one run. Row r always uses tie-break stream r. With shard_count > 1, total_records
  /// must be the number of records of the stream, bad ones included (count_records()).
  std::size_t shard_index = 0;
  std::size_t shard_count = 1;
  std::size_t total_records = kUnknownTotal;
  static constexpr std::size_t kUnknownTotal = static_cast<std::size_t>(-1);
  /// With OnError::Skip: how many error messages the report keeps (the count is always exact).
  std::size_t max_kept_errors = 10;
  void validate() const;
};

struct BatchReport {
  std::size_t records_read = 0;     ///< records seen (all shards, bad ones included)
  std::size_t records_written = 0;  ///< records of this shard converted and written
  std::size_t records_skipped = 0;  ///< bad records of this shard skipped
  std::vector<std::string> errors;  ///< the first max_kept_errors messages
};

/// The number of records `reader` yields from here to the end, bad ones included (each FormatError
/// of next() counts as one record, as in convert_stream). Consumes the reader.
std::size_t count_records(EsvReader& reader);

/// Reads every record, converts the ones of this shard with `engine` (row number = record index) and
/// hands the formatted text to `sink` in chunks (begin() first, end() last). `observer`, if set, sees each
/// converted record. Bad records: see BatchOptions::on_error. I/O errors always propagate.
BatchReport convert_stream(EsvReader& reader, FmcvWriter& writer, const Engine& engine,
                           const BatchOptions& options,
                           const std::function<void(std::string_view)>& sink,
                           const std::function<void(const EsvRecord&, const Selection&, const Fmcv&)>&
                               observer = {});

/// A readable one-line account of a conversion, e.g.
/// "blend surprise 0.70 + happiness 0.40 | frontalis_medialis 0.70, zygomatic_major 0.35, …".
std::string describe(const Esv& esv, const Selection& selection, const Fmcv& fmcv,
                     std::size_t top_muscles = 4);

}  // namespace emoface::fuzzyexpr
