#include "emoface/channels/script.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <pugixml.hpp>
#include <set>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/core/text.hpp"
#include "emoface/core/vocab.hpp"

namespace emoface::channels {

const std::array<std::string, 6>& emotion_names() {
  static const std::array<std::string, 6> n = {"sadness", "happiness", "anger", "fear", "disgust", "surprise"};
  return n;
}

namespace {


class Parser {
 public:
  Parser(std::string text, std::string file, ScriptDefaults d)
      : text_(std::move(text)), file_(std::move(file)), defaults_(d) {}

  Script run() {
    std::size_t bad = 0;
    if (!core::is_valid_utf8(text_, &bad)) fail_at(static_cast<std::ptrdiff_t>(bad), "invalid UTF-8");
    if (!(defaults_.onset > 0 && defaults_.offset > 0 && std::isfinite(defaults_.onset) && std::isfinite(defaults_.offset)))
      throw InvalidInput("script defaults: onset and offset must be > 0");
    pugi::xml_document doc;
    const auto res = doc.load_buffer(text_.data(), text_.size(),
                                     pugi::parse_default | pugi::parse_fragment, pugi::encoding_utf8);
    if (!res) fail_at(res.offset, std::string("malformed markup: ") + res.description());
    Script s;
    s.file = file_;
    bool any = false;
    for (pugi::xml_node n : doc.children()) {
      if (n.type() == pugi::node_element && core::ascii_lower(n.name()) == "script") {
        check_attrs(n, {});
        for (pugi::xml_node c : n.children()) any |= element(c, s);
      } else {
        any |= element(n, s);
      }
    }
    if (!any) fail_at(0, "the script has no elements");
    return s;
  }

 private:
  [[noreturn]] void fail_at(std::ptrdiff_t offset, const std::string& msg) const {
    SourceLocation w;
    w.file = file_;
    const auto loc = locate(offset);
    w.line = loc.line;
    w.column = loc.column;
    throw FormatError(w, msg);
  }
  [[noreturn]] void fail(pugi::xml_node n, const std::string& msg) const { fail_at(offset(n), msg); }

  // pugixml reports an element at its name; point at its '<'.
  static std::ptrdiff_t offset(pugi::xml_node n) {
    const std::ptrdiff_t o = n.offset_debug();
    return n.type() == pugi::node_element && o > 0 ? o - 1 : o;
  }

  ScriptLocation locate(std::ptrdiff_t offset) const {
    ScriptLocation l{1, 1};
    const auto end = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(offset, 0, static_cast<std::ptrdiff_t>(text_.size())));
    for (std::size_t i = 0; i < end; ++i) {
      if (text_[i] == '\n') {
        ++l.line;
        l.column = 1;
      } else if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) {
        ++l.column;
      }
    }
    return l;
  }

  void check_attrs(pugi::xml_node n, const std::set<std::string>& allowed) const {
    std::set<std::string> seen;
    for (pugi::xml_attribute a : n.attributes()) {
      const std::string k = core::ascii_lower(a.name());
      if (!allowed.count(k)) fail(n, "unknown attribute \"" + std::string(a.name()) + "\" on <" + n.name() + ">");
      if (!seen.insert(k).second) fail(n, "attribute \"" + std::string(a.name()) + "\" repeated");
    }
  }

  pugi::xml_attribute attr(pugi::xml_node n, const std::string& key) const {
    for (pugi::xml_attribute a : n.attributes())
      if (core::ascii_lower(a.name()) == key) return a;
    return {};
  }

  double number(pugi::xml_node n, pugi::xml_attribute a) const {
    const std::string v = a.value();
    const char* b = v.c_str();
    char* e = nullptr;
    const double d = std::strtod(b, &e);
    while (e && std::isspace(static_cast<unsigned char>(*e))) ++e;
    if (v.empty() || *e != '\0' || !std::isfinite(d))
      fail(n, "attribute \"" + std::string(a.name()) + "\": not a finite number: \"" + v + "\"");
    return d;
  }

  double required(pugi::xml_node n, const std::string& key) const {
    const auto a = attr(n, key);
    if (!a) fail(n, "<" + std::string(n.name()) + "> needs the attribute \"" + key + "\"");
    return number(n, a);
  }

  double optional(pugi::xml_node n, const std::string& key, double def) const {
    const auto a = attr(n, key);
    return a ? number(n, a) : def;
  }

  // time/duration/onset/offset → Timing; missing onset/offset default, shrunk to fit the duration.
  Timing timing(pugi::xml_node n, double def_duration = -1, double def_on = -1, double def_off = -1) const {
    const double t = required(n, "time");
    if (t < 0) fail(n, "negative time");
    if (t > 1e6) fail(n, "time too large");
    const double d = def_duration > 0 ? optional(n, "duration", def_duration) : required(n, "duration");
    if (!(d > 0)) fail(n, "duration must be > 0");
    if (d > 1e6) fail(n, "duration too large");
    const bool has_on = static_cast<bool>(attr(n, "onset")), has_off = static_cast<bool>(attr(n, "offset"));
    double on = optional(n, "onset", def_on > 0 ? def_on : defaults_.onset);
    double off = optional(n, "offset", def_off > 0 ? def_off : defaults_.offset);
    if (!(on > 0) || !(off > 0)) fail(n, "onset and offset must be > 0");
    if (on + off > d) {
      if (has_on && has_off) fail(n, "onset + offset exceed the duration");
      // shrink the defaulted part(s) so they fit
      const double room = has_on ? d - on : has_off ? d - off : d;
      if (room <= 0) fail(n, "onset + offset exceed the duration");
      if (!has_on && !has_off) {
        const double s = d / (on + off);
        on *= s;
        off *= s;
      } else if (has_on) {
        off = room;
      } else {
        on = room;
      }
    }
    return Timing{t, t + d, on, off};
  }

  std::string label(pugi::xml_node n) const {
    const auto l = locate(offset(n));
    return std::string(n.name()) + " at line " + std::to_string(l.line);
  }

  bool element(pugi::xml_node n, Script& s) const {
    switch (n.type()) {
      case pugi::node_comment:
      case pugi::node_declaration:
      case pugi::node_doctype:
        return false;
      case pugi::node_pcdata:
      case pugi::node_cdata: {
        const std::string v = n.value();
        if (std::all_of(v.begin(), v.end(), [](unsigned char c) { return std::isspace(c); })) return false;
        fail(n, "unexpected text outside an element");
      }
      case pugi::node_element:
        break;
      default:
        fail(n, "unexpected node");
    }
    if (n.first_child() && n.first_child().type() == pugi::node_element) fail(n, "elements cannot be nested here");
    const std::string name = core::ascii_lower(n.name());
    const ScriptLocation where = locate(offset(n));
    if (name == "phoneme") {
      check_attrs(n, {"time", "text"});
      SpeechItem it;
      it.time = required(n, "time");
      if (it.time < 0 || it.time > 1e6) fail(n, "time must be in [0, 1e6]");
      it.text = attr(n, "text").value();
      if (std::all_of(it.text.begin(), it.text.end(), [](unsigned char c) { return std::isspace(c); }))
        fail(n, "<PHONEME> needs a non-empty \"text\"");
      if (it.text.size() > 100000) fail(n, "text too long");
      it.where = where;
      s.speech.push_back(std::move(it));
    } else if (name == "viseme") {
      check_attrs(n, {"time", "duration", "name", "apex"});
      VisemeItem it;
      it.segment.start = required(n, "time");
      const double d = required(n, "duration");
      if (it.segment.start < 0 || !(d > 0) || it.segment.start > 1e6 || d > 1e6) fail(n, "need time >= 0 and duration > 0");
      it.segment.end = it.segment.start + d;
      it.segment.apex = optional(n, "apex", 0.0);
      if (it.segment.apex < 0 || it.segment.apex > d) fail(n, "apex must be in [0, duration]");
      it.segment.viseme = attr(n, "name").value();
      if (it.segment.viseme.empty()) fail(n, "<VISEME> needs a \"name\"");
      it.segment.label = label(n);
      it.where = where;
      s.visemes.push_back(std::move(it));
    } else if (name == "emotiondisplay" || name == "emblem") {
      EmotionItem it;
      it.emblem = name == "emblem";
      std::set<std::string> allowed = {"time", "duration", "onset", "offset"};
      for (const auto& e : emotion_names()) allowed.insert(e);
      check_attrs(n, allowed);
      it.timing = timing(n);
      bool any = false;
      for (std::size_t k = 0; k < 6; ++k) {
        const auto a = attr(n, emotion_names()[k]);
        if (!a) continue;
        const double v = number(n, a);
        if (v < 0 || v > 1) fail(n, "intensity of " + emotion_names()[k] + " must be in [0,1]");
        it.intensities[k] = v;
        any = true;
      }
      if (!any) fail(n, "<" + std::string(n.name()) + "> names no emotion (sadness, happiness, anger, fear, disgust, surprise)");
      it.where = where;
      s.emotions.push_back(it);
    } else if (name == "signal") {
      MovementItem it;
      it.channel = Channel::ConversationalSignal;
      it.movement.timing = timing(n);
      for (pugi::xml_attribute a : n.attributes()) {
        const std::string k = core::ascii_lower(a.name());
        if (k == "time" || k == "duration" || k == "onset" || k == "offset") continue;
        const double v = number(n, a);
        std::vector<std::string> params;
        if (!parameter_muscle(k).empty()) params = {k};
        else {
          const auto& m = muscle_names();
          if (std::find(m.begin(), m.end(), k) == m.end()) fail(n, "unknown parameter \"" + std::string(a.name()) + "\"");
          params = muscle_parameters(k);
        }
        if (v < 0 || v > 1) fail(n, "contraction of " + k + " must be in [0,1]");
        for (const auto& p : params) {
          for (const auto& t : it.movement.targets)
            if (t.parameter == p) fail(n, "parameter \"" + p + "\" given twice");
          it.movement.targets.push_back({p, v});
        }
      }
      if (it.movement.targets.empty()) fail(n, "<SIGNAL> names no parameter");
      it.movement.label = label(n);
      it.where = where;
      s.movements.push_back(std::move(it));
    } else if (name == "gaze" || name == "head") {
      const bool gaze = name == "gaze";
      MovementItem it;
      it.channel = gaze ? Channel::Gaze : Channel::Head;
      std::set<std::string> allowed = {"time", "duration", "onset", "offset", "yaw", "pitch"};
      if (!gaze) allowed.insert("roll");
      check_attrs(n, allowed);
      it.movement.timing = timing(n);
      for (const char* axis : {"yaw", "pitch", "roll"}) {
        const auto a = attr(n, axis);
        if (!a) continue;
        const double v = number(n, a);
        if (std::abs(v) > 1.6) fail(n, std::string(axis) + " must be within ±1.6 rad");
        it.movement.targets.push_back({std::string(gaze ? "eye_gaze_" : "head_") + axis, v});
      }
      if (it.movement.targets.empty()) fail(n, "<" + std::string(n.name()) + "> needs yaw, pitch or roll");
      it.movement.label = label(n);
      it.where = where;
      s.movements.push_back(std::move(it));
    } else if (name == "blink") {
      check_attrs(n, {"time", "duration", "onset", "offset", "closure"});
      MovementItem it;
      it.channel = Channel::Manipulator;
      const BlinkOptions b;
      it.movement.timing = timing(n, b.duration, b.onset, b.offset);
      const double c = optional(n, "closure", b.closure);
      if (!(c > 0 && c <= 1)) fail(n, "closure must be in (0,1]");
      it.movement.targets = {{"eye_blink_l", c}, {"eye_blink_r", c}};
      it.movement.label = label(n);
      it.where = where;
      s.movements.push_back(std::move(it));
    } else {
      fail(n, "unknown element <" + std::string(n.name()) + ">");
    }
    return true;
  }

  std::string text_;
  std::string file_;
  ScriptDefaults defaults_;
};

// The thesis prints its example with typographic quotes (“0”); accept them as plain quotes.
std::string normalise_quotes(std::string_view in) {
  std::string out;
  out.reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (i + 2 < in.size() && static_cast<unsigned char>(in[i]) == 0xE2 && static_cast<unsigned char>(in[i + 1]) == 0x80 &&
        (static_cast<unsigned char>(in[i + 2]) == 0x9C || static_cast<unsigned char>(in[i + 2]) == 0x9D)) {
      out += '"';
      i += 2;
    } else {
      out += in[i];
    }
  }
  return out;
}

[[noreturn]] void fail_item(const Script& s, const ScriptLocation& w, const std::string& msg) {
  SourceLocation loc;
  loc.file = s.file;
  loc.line = w.line;
  loc.column = w.column;
  throw FormatError(loc, msg);
}

}  // namespace

Script parse_script(std::string_view xml, const std::string& file, ScriptDefaults defaults) {
  if (xml.size() > (std::size_t{64} << 20)) throw InvalidInput("script larger than 64 MiB");
  return Parser(normalise_quotes(xml), file, defaults).run();
}

Script read_script(const std::string& path, ScriptDefaults defaults) {
  return parse_script(core::read_file(path), path, defaults);
}

void TimelineOptions::validate() const {
  blink.validate();
  gaze.validate();
  head.validate();
  if (!(silence_pad > 0 && silence_pad < 10)) throw InvalidInput("timeline: silence_pad must be in (0, 10) s");
  if (!(generated_margin >= 0 && generated_margin < 10)) throw InvalidInput("timeline: generated_margin must be in [0, 10) s");
  if (!(tail >= 0 && tail < 3600)) throw InvalidInput("timeline: tail must be in [0, 3600) s");
}

Timeline build_timeline(const Script& script, const std::vector<std::vector<PhonemeTiming>>& utterances,
                        const VisemeSet& visemes, const EmotionMapper& mapper,
                        const TimelineOptions& options, std::uint64_t seed) {
  options.validate();
  if (utterances.size() != script.speech.size())
    throw InvalidInput("build_timeline: need one phoneme list per <PHONEME> element");
  Timeline tl;
  struct Located {
    Movement m;
    ScriptLocation where;
  };
  std::array<std::vector<Located>, kChannelCount> lists;
  for (const MovementItem& it : script.movements)
    lists[static_cast<std::size_t>(it.channel)].push_back({it.movement, it.where});
  for (const EmotionItem& e : script.emotions) {
    if (!mapper) fail_item(script, e.where, "no emotion mapper to turn emotions into muscle targets");
    Movement m;
    m.targets = mapper(e.intensities);
    m.timing = e.timing;
    m.priority = e.priority;
    const auto l = e.where;
    m.label = std::string(e.emblem ? "EMBLEM" : "EMOTIONDISPLAY") + " at line " + std::to_string(l.line);
    lists[static_cast<std::size_t>(Channel::EmotionDisplay)].push_back({std::move(m), e.where});
  }
  // §4.5.2: the movements of a channel are sequential: Ts2 > Ts1 and Te2 > Te1
  for (auto& list : lists) {
    std::stable_sort(list.begin(), list.end(), [](const Located& a, const Located& b) { return a.m.timing.start < b.m.timing.start; });
    for (std::size_t k = 1; k < list.size(); ++k) {
      const Timing& a = list[k - 1].m.timing;
      const Timing& b = list[k].m.timing;
      if (!(b.start > a.start))
        fail_item(script, list[k].where, "starts at the same time as " + list[k - 1].m.label + " in the same channel");
      if (!(b.end > a.end))
        fail_item(script, list[k].where, "ends before " + list[k - 1].m.label + " ends (movements of a channel are sequential)");
    }
  }
  // lip channel: utterances (phonemes → visemes) and explicit visemes, padded with silence
  struct Span {
    double start, end;
    ScriptLocation where;
    std::vector<LipSegment> segs;
  };
  std::vector<Span> spans;
  for (std::size_t i = 0; i < utterances.size(); ++i) {
    Span sp{script.speech[i].time, script.speech[i].time, script.speech[i].where, {}};
    double prev_end = 0.0;
    for (const PhonemeTiming& p : utterances[i]) {
      if (!(p.end > p.start) || p.start < prev_end - 1e-9 || !std::isfinite(p.start) || !std::isfinite(p.end))
        throw InvalidInput("build_timeline: phoneme timings must increase");
      prev_end = p.end;
      sp.segs.push_back({visemes.viseme_for_phoneme(p.phoneme), sp.start + p.start, sp.start + p.end, 0.0, p.phoneme});
      sp.end = sp.start + p.end;
    }
    if (!sp.segs.empty()) spans.push_back(std::move(sp));
  }
  for (const VisemeItem& v : script.visemes) {
    if (!visemes.find(v.segment.viseme)) fail_item(script, v.where, "unknown viseme \"" + v.segment.viseme + "\"");
    spans.push_back({v.segment.start, v.segment.end, v.where, {v.segment}});
  }
  std::stable_sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.start < b.start; });
  for (std::size_t k = 0; k < spans.size(); ++k) {
    if (k > 0 && spans[k].start < spans[k - 1].end - 1e-9)
      fail_item(script, spans[k].where, "speech overlaps the previous lip movement");
    const double prev_end = tl.lip.empty() ? 0.0 : tl.lip.back().end;
    const double pad_before = std::min(options.silence_pad, spans[k].start - prev_end);
    if (pad_before > 1e-6)
      tl.lip.push_back({visemes.silence, spans[k].start - pad_before, spans[k].start, 0.0, "pad"});
    for (auto& s : spans[k].segs) tl.lip.push_back(std::move(s));
    const double next_start = k + 1 < spans.size() ? spans[k + 1].start : spans[k].end + options.silence_pad;
    const double pad_after = std::min(options.silence_pad, next_start - spans[k].end);
    if (pad_after > 1e-6) tl.lip.push_back({visemes.silence, spans[k].end, spans[k].end + pad_after, 0.0, "pad"});
  }
  // generated movements: blinks, gaze and head noise, each from its own seeded stream
  for (std::size_t c = 0; c < kChannelCount; ++c)
    for (auto& l : lists[c]) tl.movements[c].push_back(std::move(l.m));
  const double end = std::max(tl.end_time(), 0.0) + options.tail;
  const auto add = [&](Channel c, const std::vector<Movement>& gen) {
    auto& ms = tl.movements[static_cast<std::size_t>(c)];
    ms = merge_generated(std::move(ms), gen, options.generated_margin);
  };
  if (options.blinks) {
    core::Rng rng(seed, 1);
    add(Channel::Manipulator, generate_blinks(0.0, end, options.blink, rng));
  }
  if (options.gaze_noise) {
    core::Rng rng(seed, 5);
    add(Channel::Gaze, generate_noise(0.0, end, {"eye_gaze_yaw", "eye_gaze_pitch"}, options.gaze, rng, "gaze noise"));
  }
  if (options.head_noise) {
    core::Rng rng(seed, 6);
    add(Channel::Head, generate_noise(0.0, end, {"head_yaw", "head_pitch", "head_roll"}, options.head, rng, "head noise"));
  }
  return tl;
}

EmotionMapper side_parameter_mapper(SideParameterFunction to_sides) {
  static_assert(core::kSideParameterCount == 35);
  if (!to_sides) throw InvalidInput("side_parameter_mapper: empty function");
  return [to_sides = std::move(to_sides)](const std::array<double, 6>& esv) {
    const std::array<double, 35> sides = to_sides(esv);
    std::vector<Target> out;
    out.reserve(sides.size());
    for (std::size_t i = 0; i < sides.size(); ++i)
      out.push_back({core::side_parameter_names()[i], sides[i]});
    return out;
  };
}

}  // namespace emoface::channels
