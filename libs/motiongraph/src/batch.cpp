#include "emoface/motiongraph/batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/core/text.hpp"
#include "emoface/core/video.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/render.hpp"
#include "emoface/motiongraph/weights.hpp"

namespace emoface::motiongraph {

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (true) {
    const std::size_t e = s.find(sep, pos);
    parts.push_back(s.substr(pos, e == std::string::npos ? std::string::npos : e - pos));
    if (e == std::string::npos) return parts;
    pos = e + 1;
  }
}

const std::vector<std::string> kRequestHeader{"id", "labels"};

// The record on one data line of a requests file.
RequestRecord request_record(const std::string& file, std::size_t line,
                             const std::vector<std::string>& fields, std::size_t bad_column,
                             const std::string& csv_error) {
  RequestRecord rec;
  rec.file = file;
  rec.line = line;
  auto error = [&](std::size_t column, const std::string& message) {
    rec.error = FormatError({file, "", line, column}, message);
    return rec;
  };
  if (bad_column != 0) return error(bad_column, csv_error);
  if (fields.size() != 2)
    return error(1, "expected 2 fields (id,labels), got " + std::to_string(fields.size()));
  if (fields[0].empty()) return error(1, "empty request id");
  rec.request.id = fields[0];
  rec.request.labels = split(fields[1], ';');
  for (const std::string& name : rec.request.labels) {
    try {
      label_from_string(name);
    } catch (const InvalidInput& e) {
      return error(2, e.what());
    }
  }
  return rec;
}

}  // namespace

std::vector<RequestRecord> parse_requests_csv(std::string_view text, const std::string& file) {
  std::size_t bad = 0;
  if (!core::is_valid_utf8(text, &bad)) {
    std::size_t line = 1;
    for (std::size_t i = 0; i < bad; ++i) line += text[i] == '\n';
    throw FormatError({file, "", line, 0}, "not valid UTF-8");
  }
  std::vector<RequestRecord> records;
  std::vector<std::string> fields;
  bool header = false;
  for (const core::Line& line : core::Lines(text)) {
    if (core::trim(line.text).empty() || core::is_csv_comment(line.text)) continue;
    std::string err;
    std::string_view body = line.text;
    if (!header && body.substr(0, 3) == "\xEF\xBB\xBF") body.remove_prefix(3);
    const std::size_t col = core::split_csv_line(body, fields, &err);
    if (!header) {
      if (col != 0 || fields != kRequestHeader)
        throw FormatError({file, "", line.number, 1}, "header must be \"id,labels\"");
      header = true;
      continue;
    }
    if (col == 0 && fields == kRequestHeader) continue;  // the header of a concatenated file
    records.push_back(request_record(file, line.number, fields, col, err));
  }
  if (!header) throw FormatError({file, "", 1, 1}, "empty requests file (no header)");
  return records;
}

std::vector<RequestRecord> read_requests_csv(const std::string& path) {
  return parse_requests_csv(core::read_file(path), path);
}

std::string requests_to_csv(const std::vector<SynthesisRequest>& requests) {
  std::string out = core::csv_stamp() + "id,labels\n";
  for (const SynthesisRequest& r : requests) {
    if (r.id.empty()) throw InvalidInput("requests_to_csv: empty request id");
    if (r.labels.empty())
      throw InvalidInput("requests_to_csv: request \"" + r.id + "\" has no labels");
    std::string labels;
    for (const std::string& l : r.labels) {
      if (l.find(';') != std::string::npos)
        throw InvalidInput("requests_to_csv: label \"" + l + "\" contains ';'");
      labels += (labels.empty() ? "" : ";") + l;
    }
    core::append_csv_field(out, r.id);
    out += ',';
    core::append_csv_field(out, labels);
    out += '\n';
  }
  return out;
}

ChainOptions chain_options_for(const MotionGraph& graph) {
  const bool weights = is_weight_space(graph.dimensions);
  ChainOptions o;
  o.synthesis = weights ? weight_synthesis_options() : SynthesisOptions{};
  o.idle = weights ? weight_idle_options() : IdleOptions{};
  return o;
}

std::vector<Sequence> synthesize_chain(const MotionGraph& graph,
                                       const std::vector<std::string>& labels, std::uint64_t seed,
                                       const std::string& prefix, const ChainOptions& options) {
  SynthesisOptions o = options.synthesis;
  o.seed = seed;
  std::vector<Label> parsed;
  for (const std::string& name : labels) parsed.push_back(label_from_string(name));
  if (parsed.empty()) throw InvalidInput("no labels");
  SynthesisState state = initial_state(graph);
  std::vector<Sequence> out;
  for (std::size_t k = 0; k < parsed.size(); ++k) {
    const std::string& name = labels[k];
    out.push_back({prefix + "synth_" + std::to_string(out.size()) + "_" + name, "", parsed[k],
                   synthesize(graph, state, parsed[k], o)});
    if (options.idle_after > 0.0) {
      IdleOptions io = options.idle;
      io.duration = options.idle_after;
      io.seed = seed;
      out.push_back({prefix + "idle_" + std::to_string(out.size()) + "_" + name, "", parsed[k],
                     idle(graph, state, parsed[k], io)});
    }
  }
  return out;
}

std::vector<Sequence> synthesize_requests(const MotionGraph& graph,
                                          const std::vector<RequestRecord>& records,
                                          std::pair<std::size_t, std::size_t> block,
                                          std::uint64_t seed, const ChainOptions& options,
                                          OnError on_error, ReadReport* report) {
  if (block.first > block.second || block.second > records.size())
    throw InvalidInput("synthesize_requests: block out of range");
  std::vector<Sequence> seqs;
  for (std::size_t r = block.first; r < block.second; ++r) {
    const RequestRecord& rec = records[r];
    try {
      if (rec.error) throw *rec.error;
      std::vector<Sequence> mine;
      try {
        mine = synthesize_chain(graph, rec.request.labels, core::derive_seed(seed, r),
                                rec.request.id + "/", options);
      } catch (const InvalidInput& e) {
        throw FormatError({rec.file, "", rec.line, 2}, e.what());
      }
      seqs.insert(seqs.end(), mine.begin(), mine.end());
    } catch (const FormatError& e) {
      if (on_error == OnError::Stop) throw;
      if (report) report->skipped.push_back(e.what());
    }
  }
  return seqs;
}

// --- evaluation table ---------------------------------------------------------------------------

namespace {

const char* const kEvalColumns[] = {
    "threshold",       "compression_percent", "nodes",         "length_diff_mean",
    "length_diff_std", "pose_diff_mean",      "pose_diff_std", "samples",
    "distances",       "length_sum",          "length_sum2",   "pose_sum",
    "pose_sum2"};
const char* const kRawColumns[] = {"raw_pose_diff_mean", "raw_pose_diff_std", "raw_pose_sum",
                                   "raw_pose_sum2"};

}  // namespace

std::string evaluation_csv(const std::vector<EvaluationRow>& rows) {
  const bool raw = !rows.empty() && rows.front().has_raw;
  std::string out = core::csv_stamp();
  for (const char* c : kEvalColumns) out += std::string(c == kEvalColumns[0] ? "" : ",") + c;
  if (raw)
    for (const char* c : kRawColumns) out += std::string(",") + c;
  out += "\n";
  char line[640];
  for (const EvaluationRow& r : rows) {
    if (r.has_raw != raw)
      throw InvalidInput("evaluation_csv: rows with and without raw comparisons");
    std::snprintf(
        line, sizeof line, "%.6g,%.4f,%zu,%.6g,%.6g,%.6g,%.6g,%zu,%zu,%.17g,%.17g,%.17g,%.17g",
        r.threshold, 100 * r.compression, r.nodes, r.length_mean, r.length_std, r.pose_mean,
        r.pose_std, r.samples, r.distances, r.length_sum, r.length_sum2, r.pose_sum, r.pose_sum2);
    out += line;
    if (raw) {
      std::snprintf(line, sizeof line, ",%.6g,%.6g,%.17g,%.17g", r.raw_pose_mean, r.raw_pose_std,
                    r.raw_pose_sum, r.raw_pose_sum2);
      out += line;
    }
    out += "\n";
  }
  return out;
}

std::vector<EvaluationRow> parse_evaluation_csv(std::string_view text, const std::string& file) {
  const core::CsvTable table = core::CsvTable::parse(text, file);
  std::vector<std::size_t> col;
  for (const char* c : kEvalColumns) col.push_back(table.require_column(c));
  const bool raw = table.column(kRawColumns[0]).has_value();
  if (raw)
    for (const char* c : kRawColumns) col.push_back(table.require_column(c));
  if (table.header().size() != col.size())
    throw FormatError({file, "", table.header_line(), 0},
                      "unexpected columns (expected the 13 evaluation columns" +
                          std::string(raw ? " and the 4 raw ones)" : ")"));
  std::vector<EvaluationRow> rows;
  for (std::size_t i = 0; i < table.size(); ++i) {
    auto number = [&](std::size_t k, double lo) {
      const double v = table.number(i, col[k]);
      if (v < lo)
        table.fail(i, col[k],
                   "column \"" + table.header()[col[k]] + "\": " + core::format_number(v) +
                       " is below " + core::format_number(lo));
      return v;
    };
    auto count = [&](std::size_t k) {
      const auto v = core::parse_integer(table.field(i, col[k]));
      if (!v || *v < 0)
        table.fail(i, col[k],
                   "column \"" + table.header()[col[k]] +
                       "\": expected a non-negative integer, got \"" + table.field(i, col[k]) +
                       "\"");
      return static_cast<std::size_t>(*v);
    };
    EvaluationRow r;
    r.threshold = number(0, 0.0);
    const double percent = number(1, 0.0);
    if (percent > 100.0) table.fail(i, col[1], "column \"compression_percent\": above 100");
    r.compression = percent / 100.0;
    r.nodes = count(2);
    r.length_mean = number(3, 0.0);
    r.length_std = number(4, 0.0);
    r.pose_mean = number(5, 0.0);
    r.pose_std = number(6, 0.0);
    r.samples = count(7);
    r.distances = count(8);
    r.length_sum = number(9, 0.0);
    r.length_sum2 = number(10, 0.0);
    r.pose_sum = number(11, 0.0);
    r.pose_sum2 = number(12, 0.0);
    if (raw) {
      r.has_raw = true;
      r.raw_pose_mean = number(13, 0.0);
      r.raw_pose_std = number(14, 0.0);
      r.raw_pose_sum = number(15, 0.0);
      r.raw_pose_sum2 = number(16, 0.0);
    }
    rows.push_back(r);
  }
  return rows;
}

std::vector<EvaluationRow> read_evaluation_csv(const std::string& path) {
  return parse_evaluation_csv(core::read_file(path), path);
}

// --- pictures
// -------------------------------------------------------------------------------------

void stage_animation_pictures(core::OutputBundle& bundle, const MotionGraph& g,
                              const std::vector<Pose>& all, const AnimationPictures& a) {
  if (!a.any()) return;
  if (is_weight_space(g.dimensions))
    throw InvalidInput("pictures draw landmarks: not for a weight graph");
  if (all.empty()) throw InvalidInput("pictures of an animation without frames");
  if (a.every < 1) throw InvalidInput("pictures: every must be >= 1");
  const std::vector<int> groups = g.landmark_regions();
  const auto contours = contours_for(g.landmark_ids());
  if (!a.sheet.empty()) {
    std::vector<Pose> shown;
    const auto every = static_cast<std::size_t>(a.every);
    for (std::size_t f = 0; f < all.size(); f += every) shown.push_back(all[f]);
    if ((all.size() - 1) % every != 0) shown.push_back(all.back());
    bundle.add(a.sheet, core::encode_png(contact_sheet(shown, groups, a.columns, a.cell_width,
                                                       a.cell_width * 7 / 8, contours)));
  }
  if (!a.plot.empty()) bundle.add(a.plot, core::encode_png(plot_trajectories(all, groups)));
  if (!a.frames_dir.empty()) {
    const View view = fit_view(all, 640, 490);
    for (std::size_t f = 0; f < all.size(); ++f) {
      core::Image img(640, 490);
      draw_pose(img, all[f], groups, view);
      char name[32];
      std::snprintf(name, sizeof name, "/frame_%05zu.png", f);
      bundle.add(a.frames_dir + name, core::encode_png(img));
    }
  }
  if (!a.video.empty()) {
    core::VideoOptions vo;
    vo.width = a.video_width;
    vo.height = a.video_height;
    vo.fps = a.fps > 0.0 ? a.fps : g.frame_rate;
    core::VideoWriter video(bundle.stage_path(a.video), vo);  // renamed into place on commit
    const View view = fit_view(all, vo.width, vo.height);
    for (const Pose& pose : all) {
      core::Image img(vo.width, vo.height);
      draw_contours(img, pose, contours, view);
      draw_pose(img, pose, groups, view, std::max(1.5, vo.width / 256.0));
      video.add_frame(img);
    }
    video.finish();
  }
}

Database animation_database(const MotionGraph& g, std::vector<Sequence> sequences) {
  Database db;
  db.dimensions = g.dimensions;
  db.frame_rate = g.frame_rate;
  db.landmark_ids = g.landmark_ids();
  db.landmark_count = db.landmark_ids.size();
  db.sequences = std::move(sequences);
  return db;
}

// --- databases and tables of a run
// -------------------------------------------------------------------------------------

void stage_database(core::OutputBundle& bundle, const std::string& path, const Database& db) {
  const bool csv = path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
  bundle.add(path, csv ? database_to_csv(db) : database_to_json(db));
}

Database database_block(Database db, std::pair<std::size_t, std::size_t> block) {
  if (block.first > block.second || block.second > db.sequences.size())
    throw InvalidInput("database_block: [" + std::to_string(block.first) + ", " +
                       std::to_string(block.second) + ") is not within the " +
                       std::to_string(db.sequences.size()) + " sequences");
  const auto first = db.sequences.begin();
  db.sequences = std::vector<Sequence>(first + static_cast<std::ptrdiff_t>(block.first),
                                       first + static_cast<std::ptrdiff_t>(block.second));
  return db;
}

std::vector<Pose> label_peaks(const Database& db) {
  std::vector<Pose> shown;
  if (db.sequences.empty() || db.sequences.front().frames.empty()) return shown;
  shown.push_back(db.sequences.front().frames.front());
  std::vector<Label> seen;
  for (const Sequence& s : db.sequences)
    if (!s.frames.empty() && std::find(seen.begin(), seen.end(), s.label) == seen.end()) {
      seen.push_back(s.label);
      shown.push_back(s.frames.back());
    }
  return shown;
}

void stage_peaks_sheet(core::OutputBundle& bundle, const std::string& path, const Database& db,
                       int columns, int cell_width) {
  if (is_weight_space(db.dimensions) || db.landmark_count != 68)
    throw InvalidInput("a sheet of label peaks needs a 68-landmark iBUG database");
  const std::vector<Pose> shown = label_peaks(db);
  if (shown.empty()) throw InvalidInput("a sheet of label peaks needs a sequence");
  const LandmarkLayout layout = default_layout();
  std::vector<int> groups(68, 8);  // 8: grey in render.cpp's palette
  for (std::size_t r = 0; r < layout.regions.size(); ++r)
    for (int i : layout.regions[r].landmarks)
      groups[static_cast<std::size_t>(i)] = static_cast<int>(r);
  std::vector<int> all_ids(68);
  for (int i = 0; i < 68; ++i) all_ids[static_cast<std::size_t>(i)] = i;
  bundle.add(path, encode_png(contact_sheet(shown, groups, columns, cell_width, cell_width * 7 / 8,
                                            contours_for(all_ids))));
}

std::string evaluation_table(const std::vector<EvaluationRow>& rows, const std::string& unit) {
  const bool raw = !rows.empty() && rows.front().has_raw;
  const std::string pose = "pose diff (" + unit + ")";
  const std::string vs_raw = "   vs raw samples (" + unit + ")";
  char line[256];
  std::snprintf(line, sizeof line, "%10s %14s %7s %22s %22s%s\n", "threshold", "compression %",
                "nodes", "length diff (frames)", pose.c_str(), raw ? vs_raw.c_str() : "");
  std::string out = line;
  for (const EvaluationRow& r : rows) {
    std::snprintf(line, sizeof line, "%10.4f %14.2f %7zu %10.3f +- %-8.3f %10.4f +- %-8.4f",
                  r.threshold, 100 * r.compression, r.nodes, r.length_mean, r.length_std,
                  r.pose_mean, r.pose_std);
    out += line;
    if (raw) {
      std::snprintf(line, sizeof line, " %10.4f +- %-8.4f", r.raw_pose_mean, r.raw_pose_std);
      out += line;
    }
    out += "\n";
  }
  return out +
         "paper (CK+, 70 sequences): 90% -> 0.98 +- 1.84 frames, 2.86 +- 2.3 px; 78% -> 0.071 +- "
         "0.39, 2.12 +- 1.81; 57.53% -> 0 +- 0, 1.52 +- 1.51\n";
}

}  // namespace emoface::motiongraph
