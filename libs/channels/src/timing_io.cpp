#include "emoface/channels/timing_io.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"

namespace emoface::channels {

namespace {

constexpr core::FormatVersion kTimingVersion{1, 0};
constexpr double kMaxSeconds = 24 * 3600.0;

[[noreturn]] void fail_line(const std::string& file, std::size_t line, const std::string& msg) {
  throw FormatError({file, "", line, 0}, msg);
}
[[noreturn]] void fail_json(const std::string& file, const std::string& pointer,
                            const std::string& msg) {
  throw FormatError({file, pointer.empty() ? "/" : pointer, 0, 0}, msg);
}

std::string number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool parse_seconds(std::string_view s, double& out) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.remove_suffix(1);
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(out) && out >= 0 &&
         out <= kMaxSeconds;
}

// Lines without '\r', with their 1-based numbers; comment lines ('#') and blank lines skipped.
std::vector<std::pair<std::size_t, std::string_view>> content_lines(std::string_view text) {
  std::vector<std::pair<std::size_t, std::string_view>> out;
  std::size_t pos = 0, line = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view l = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line;
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (l.find_first_not_of(" \t") == std::string_view::npos || core::is_csv_comment(l)) continue;
    out.emplace_back(line, l);
  }
  return out;
}

std::vector<std::string_view> split_tabs(std::string_view l) {
  std::vector<std::string_view> f;
  std::size_t pos = 0;
  while (true) {
    const std::size_t t = l.find('\t', pos);
    f.push_back(l.substr(pos, t == std::string_view::npos ? std::string_view::npos : t - pos));
    if (t == std::string_view::npos) break;
    pos = t + 1;
  }
  return f;
}

void check_name(const std::string& name) {
  if (name.empty() || name.size() > 64)
    throw InvalidInput("segment name must have 1 to 64 characters");
  for (char c : name)
    if (c == '\t' || c == '\n' || c == '\r' || c == '"' || c == '\\' ||
        static_cast<unsigned char>(c) < 0x20)
      throw InvalidInput("segment name '" + name +
                         "' has a control character, tab, quote or backslash");
  if (!core::is_valid_utf8(name)) throw InvalidInput("segment name is not valid UTF-8");
}

void check_segments(const std::vector<PhonemeTiming>& s, bool contiguous) {
  if (s.size() > kMaxTimingSegments) throw InvalidInput("too many segments");
  for (std::size_t i = 0; i < s.size(); ++i) {
    check_name(s[i].phoneme);
    if (!(std::isfinite(s[i].start) && std::isfinite(s[i].end) && s[i].start >= 0 &&
          s[i].end <= kMaxSeconds))
      throw InvalidInput("segment " + std::to_string(i + 1) +
                         ": times must be finite, in [0, 86400] s");
    if (!(s[i].end > s[i].start))
      throw InvalidInput("segment " + std::to_string(i + 1) + ": end must be after start");
    if (i > 0 && s[i].start < s[i - 1].end)
      throw InvalidInput("segment " + std::to_string(i + 1) +
                         " starts before the previous one ends");
    if (contiguous && i > 0 && s[i].start != s[i - 1].end)
      throw InvalidInput("cue " + std::to_string(i + 1) +
                         " does not start where the previous one ends");
  }
}

const std::set<std::string>& rhubarb_shapes() {
  static const std::set<std::string> s{"A", "B", "C", "D", "E", "F", "G", "H", "X"};
  return s;
}

template <class Json>
double json_seconds(const Json& v, const std::string& file, const std::string& pointer) {
  if (!v.is_number()) fail_json(file, pointer, "expected a number of seconds");
  const double d = v.template get<double>();
  if (!(std::isfinite(d) && d >= 0 && d <= kMaxSeconds))
    fail_json(file, pointer, "seconds must be in [0, 86400]");
  return d;
}

}  // namespace

std::string_view to_string(TimingKind kind) noexcept {
  return kind == TimingKind::Viseme ? "viseme" : "phoneme";
}

TimingKind timing_kind_from_string(std::string_view name) {
  if (name == "phoneme") return TimingKind::Phoneme;
  if (name == "viseme") return TimingKind::Viseme;
  throw InvalidInput("unknown timing kind '" + std::string(name) + "' (phoneme or viseme)");
}

void SpeechTiming::validate() const { check_segments(segments, false); }

SpeechTiming parse_timing_tsv(std::string_view text, const std::string& file) {
  const auto lines = content_lines(text);
  if (lines.empty())
    fail_line(file, 1, "empty timing file (expected a header start<TAB>end<TAB>phoneme)");
  SpeechTiming t;
  {
    const auto h = split_tabs(lines[0].second);
    if (h.size() != 3 || h[0] != "start" || h[1] != "end" ||
        (h[2] != "phoneme" && h[2] != "viseme"))
      fail_line(file, lines[0].first, "expected the header start<TAB>end<TAB>phoneme (or viseme)");
    t.kind = timing_kind_from_string(h[2]);
  }
  if (lines.size() - 1 > kMaxTimingSegments) fail_line(file, lines[0].first, "too many segments");
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto [line, l] = lines[i];
    const auto f = split_tabs(l);
    if (f.size() != 3)
      fail_line(file, line, "expected 3 tab-separated fields, got " + std::to_string(f.size()));
    PhonemeTiming p;
    if (!parse_seconds(f[0], p.start))
      fail_line(file, line, "start: not a number of seconds in [0, 86400]");
    if (!parse_seconds(f[1], p.end))
      fail_line(file, line, "end: not a number of seconds in [0, 86400]");
    p.phoneme = std::string(f[2]);
    try {
      check_name(p.phoneme);
      check_segments({p}, false);
    } catch (const InvalidInput& e) {
      fail_line(file, line, e.what());
    }
    if (!t.segments.empty() && p.start < t.segments.back().end)
      fail_line(file, line, "segment starts before the previous one ends");
    t.segments.push_back(std::move(p));
  }
  return t;
}

std::string format_timing_tsv(const SpeechTiming& t) {
  t.validate();
  std::string out = core::csv_stamp();
  out += "start\tend\t";
  out += to_string(t.kind);
  out += '\n';
  for (const auto& s : t.segments)
    out += number(s.start) + '\t' + number(s.end) + '\t' + s.phoneme + '\n';
  return out;
}

// Through core::JsonReader: a newer minor version (1.1+) may add fields, which are ignored; in 1.0
// files unknown fields are errors (docs/formats.md).
SpeechTiming parse_timing_json(std::string_view text, const std::string& file) {
  const core::JsonReader reader(text, file, "speech_timing", kTimingVersion);
  const core::JsonValue doc = reader.root();
  doc.only_keys({"kind", "segments"});
  SpeechTiming t;
  const core::JsonValue kind = doc.at("kind");
  if (!kind.is_string()) kind.fail("expected \"phoneme\" or \"viseme\"");
  try {
    t.kind = timing_kind_from_string(kind.string());
  } catch (const InvalidInput& e) {
    kind.fail(e.what());
  }
  const core::JsonValue seg = doc.at("segments").expect_array();
  if (seg.size() > kMaxTimingSegments) seg.fail("too many segments");
  for (const core::JsonValue& s : seg.items()) {
    s.only_keys({"start", "end", "name"});
    PhonemeTiming p;
    const core::JsonValue start = s.at("start"), end = s.at("end");
    p.start = json_seconds(start.json(), file, start.pointer());
    p.end = json_seconds(end.json(), file, end.pointer());
    p.phoneme = s.at("name").string();
    try {
      check_segments({p}, false);
    } catch (const InvalidInput& e) {
      s.fail(e.what());
    }
    if (!t.segments.empty() && p.start < t.segments.back().end)
      start.fail("segment starts before the previous one ends");
    t.segments.push_back(std::move(p));
  }
  return t;
}

std::string format_timing_json(const SpeechTiming& t) {
  t.validate();
  auto doc = core::make_envelope("speech_timing", kTimingVersion);
  doc["kind"] = std::string(to_string(t.kind));
  auto& seg = doc["segments"] = nlohmann::ordered_json::array();
  for (const auto& s : t.segments)
    seg.push_back({{"start", s.start}, {"end", s.end}, {"name", s.phoneme}});
  return doc.dump(1) + "\n";
}

void RhubarbCues::validate() const {
  check_segments(cues, true);
  for (const auto& c : cues)
    if (!rhubarb_shapes().count(c.phoneme))
      throw InvalidInput("unknown Rhubarb mouth shape '" + c.phoneme + "'");
}

RhubarbCues parse_rhubarb_tsv(std::string_view text, const std::string& file) {
  const auto lines = content_lines(text);
  if (lines.empty()) fail_line(file, 1, "empty Rhubarb TSV (expected <start><TAB><shape> lines)");
  if (lines.size() > kMaxTimingSegments) fail_line(file, 1, "too many cues");
  RhubarbCues r;
  double prev = -1.0;
  std::string prev_shape;
  for (const auto& [line, l] : lines) {
    const auto f = split_tabs(l);
    if (f.size() != 2) fail_line(file, line, "expected <start><TAB><shape>");
    double t = 0;
    if (!parse_seconds(f[0], t))
      fail_line(file, line, "start: not a number of seconds in [0, 86400]");
    const std::string shape(f[1]);
    if (!rhubarb_shapes().count(shape))
      fail_line(file, line, "unknown mouth shape '" + shape + "' (A-H, X)");
    if (prev >= 0) {
      if (!(t > prev)) fail_line(file, line, "cue times must increase");
      r.cues.push_back({prev_shape, prev, t});
    }
    prev = t;
    prev_shape = shape;
  }
  return r;
}

std::string format_rhubarb_tsv(const RhubarbCues& r) {
  r.validate();
  std::string out;
  for (const auto& c : r.cues) out += number(c.start) + '\t' + c.phoneme + '\n';
  if (!r.cues.empty()) out += number(r.cues.back().end) + "\tX\n";  // the end marker
  return out;
}

RhubarbCues parse_rhubarb_json(std::string_view text, const std::string& file) {
  const auto doc = core::parse_json(text, file);
  if (!doc.is_object()) fail_json(file, "", "expected a JSON object with \"mouthCues\"");
  RhubarbCues r;
  if (const auto m = doc.find("metadata"); m != doc.end()) {
    if (!m->is_object()) fail_json(file, "/metadata", "expected an object");
    if (const auto sf = m->find("soundFile"); sf != m->end()) {
      if (!sf->is_string()) fail_json(file, "/metadata/soundFile", "expected a string");
      r.sound_file = sf->get<std::string>();
    }
    if (const auto d = m->find("duration"); d != m->end())
      json_seconds(*d, file, "/metadata/duration");
  }
  const auto cues = doc.find("mouthCues");
  if (cues == doc.end() || !cues->is_array()) fail_json(file, "/mouthCues", "expected an array");
  if (cues->size() > kMaxTimingSegments) fail_json(file, "/mouthCues", "too many cues");
  for (std::size_t i = 0; i < cues->size(); ++i) {
    const std::string ptr = "/mouthCues/" + std::to_string(i);
    const auto& c = (*cues)[i];
    if (!c.is_object()) fail_json(file, ptr, "expected an object");
    if (!c.contains("start")) fail_json(file, ptr + "/start", "missing");
    if (!c.contains("end")) fail_json(file, ptr + "/end", "missing");
    if (!c.contains("value") || !c["value"].is_string())
      fail_json(file, ptr + "/value", "expected a shape letter");
    PhonemeTiming p{c["value"].get<std::string>(), json_seconds(c["start"], file, ptr + "/start"),
                    json_seconds(c["end"], file, ptr + "/end")};
    if (!rhubarb_shapes().count(p.phoneme))
      fail_json(file, ptr + "/value", "unknown mouth shape (A-H, X)");
    if (!(p.end > p.start)) fail_json(file, ptr + "/end", "end must be after start");
    if (!r.cues.empty() && p.start < r.cues.back().end)
      fail_json(file, ptr + "/start", "cue starts before the previous one ends");
    r.cues.push_back(std::move(p));
  }
  return r;
}

std::string format_rhubarb_json(const RhubarbCues& r) {
  r.validate();
  nlohmann::ordered_json doc;
  doc["metadata"] = {{"soundFile", r.sound_file},
                     {"duration", r.cues.empty() ? 0.0 : r.cues.back().end}};
  auto& cues = doc["mouthCues"] = nlohmann::ordered_json::array();
  for (const auto& c : r.cues)
    cues.push_back({{"start", c.start}, {"end", c.end}, {"value", c.phoneme}});
  return doc.dump(2) + "\n";
}

const std::map<std::string, std::string>& default_rhubarb_visemes() {
  static const std::map<std::string, std::string> m{{"A", "PBM"}, {"B", "SZ"},   {"C", "EH"},
                                                    {"D", "AA"},  {"E", "OH"},   {"F", "UW"},
                                                    {"G", "FV"},  {"H", "TDNL"}, {"X", "sil"}};
  return m;
}

SpeechTiming rhubarb_to_visemes(const RhubarbCues& cues,
                                const std::map<std::string, std::string>& table) {
  SpeechTiming t;
  t.kind = TimingKind::Viseme;
  for (const auto& c : cues.cues) {
    const auto it = table.find(c.phoneme);
    if (it == table.end()) throw InvalidInput("no viseme for Rhubarb shape '" + c.phoneme + "'");
    t.segments.push_back({it->second, c.start, c.end});
  }
  return t;
}

SpeechTiming read_timing_file(const std::string& path) {
  const std::string text = core::read_file(path);
  const std::size_t first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  if (first != std::string::npos && text[first] == '{') {
    if (text.find("\"mouthCues\"") != std::string::npos &&
        text.find("\"emoface.speech_timing\"") == std::string::npos)
      return rhubarb_to_visemes(parse_rhubarb_json(text, path));
    return parse_timing_json(text, path);
  }
  const auto lines = content_lines(text);
  if (!lines.empty() && lines[0].second.rfind("start\t", 0) == 0)
    return parse_timing_tsv(text, path);
  return rhubarb_to_visemes(parse_rhubarb_tsv(text, path));
}

Utterance external_utterance(const SpeechTiming& timing, const WavAudio& audio) {
  timing.validate();
  if (timing.segments.empty()) throw InvalidInput("external speech: no segments");
  Utterance u;
  u.sample_rate = audio.samples.empty() ? 22050 : audio.sample_rate;
  u.samples = audio.samples;
  double t = 0.0;
  for (const auto& s : timing.segments) {
    if (s.start > t) u.phonemes.push_back({"_", t, s.start});
    u.phonemes.push_back(s);
    t = s.end;
  }
  if (u.samples.empty())
    u.samples.assign(static_cast<std::size_t>(std::ceil(t * u.sample_rate)), 0);
  if (t > u.duration() + 1.0 / u.sample_rate)
    throw InvalidInput("external speech: the timing ends at " + number(t) +
                       " s, after the audio (" + number(u.duration()) + " s)");
  if (t < u.duration()) u.phonemes.push_back({"_", t, u.duration()});
  u.phonemes.back().end = u.duration();
  return u;
}

}  // namespace emoface::channels
