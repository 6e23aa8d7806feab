// The runtime's documents: the character config ("emoface.character") and the snapshot of a whole
// character ("emoface.character_state").
#include "emoface/core/io.hpp"

#include <algorithm>
#include <filesystem>

#include "character_impl.hpp"
#include "emoface/channels/parameters.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/parlee/domain.hpp"
#include "emoface/parlee/io.hpp"
#include "emoface/runtime/character.hpp"
#include "emoface/runtime/streaming.hpp"
#include "json_util.hpp"

namespace emoface::runtime {

namespace ch = emoface::channels;
using detail::Json;
using detail::num;
using detail::Reader;

namespace {

constexpr core::FormatVersion kConfigVersion{1, 1};  // 1.1: the mindmotion source
constexpr core::FormatVersion kStateVersion{1, 0};

std::string resolve(const std::string& base, const std::string& path) {
  if (base.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(base) / path).string();
}

void read_timing(const Reader& r, const Json& o, const std::string& p, ch::Timing& t) {
  r.only(o, p, {"start", "end", "onset", "offset"});
  r.get(o, p, "start", t.start);
  r.get(o, p, "end", t.end);
  r.get(o, p, "onset", t.onset);
  r.get(o, p, "offset", t.offset);
}

}  // namespace

CharacterConfig parse_character_config(std::string_view text, const std::string& file,
                                       const std::string& base_dir) {
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "character", kConfigVersion, file);
  const Reader r{file};
  r.only(doc, "", {"format",       "version",
                   "generator",    "source",
                   "face",         "fps",
                   "lookahead",    "seed",
                   "display",      "blinks",
                   "gaze_noise",   "head_noise",
                   "blink",        "gaze",
                   "head",         "chunk_seconds",
                   "mix",          "coarticulation",
                   "silence_pad",  "speech",
                   "step_seconds", "direct_decay_per_second"});
  CharacterConfig c;
  CharacterOptions& o = c.options;
  if (doc.contains("source")) {
    const Json& s = r.object(doc["source"], "/source");
    std::string kind = "direct";
    r.get(s, "/source", "kind", kind);
    try {
      c.source = source_kind_from_string(kind);
    } catch (const InvalidInput& e) {
      r.fail("/source/kind", e.what());
    }
    if (c.source == SourceKind::Direct) r.only(s, "/source", {"kind"});
    if (c.source == SourceKind::Parlee) {
      r.only(s, "/source", {"kind", "domain", "domain_file", "agent", "agent_file"});
      if (s.contains("domain")) {
        r.get(s, "/source", "domain", c.domain_text);
      } else if (s.contains("domain_file")) {
        std::string path;
        r.get(s, "/source", "domain_file", path);
        c.domain_text = core::read_file(resolve(base_dir, path));
      } else {
        r.fail("/source", "a parlee source needs \"domain\" (text) or \"domain_file\"");
      }
      if (s.contains("agent")) {
        c.agent = parlee::parse_agent(r.object(s["agent"], "/source/agent").dump(),
                                      file + " /source/agent");
      } else if (s.contains("agent_file")) {
        std::string path;
        r.get(s, "/source", "agent_file", path);
        c.agent = parlee::read_agent_file(resolve(base_dir, path));
      }
    }
    if (c.source == SourceKind::MindMotion) {
      r.only(s, "/source",
             {"kind", "map", "map_file", "graph", "graph_file", "variation", "hint_path_fraction"});
      if (s.contains("graph")) {
        c.motion.graph =
            std::make_shared<const motiongraph::MotionGraph>(motiongraph::parse_graph_json(
                r.object(s["graph"], "/source/graph").dump(), file + " /source/graph"));
      } else if (s.contains("graph_file")) {
        r.get(s, "/source", "graph_file", c.motion.graph_file);
        c.motion.graph_file = resolve(base_dir, c.motion.graph_file);
        c.motion.graph = std::make_shared<const motiongraph::MotionGraph>(
            motiongraph::read_graph(c.motion.graph_file));
      } else {
        r.fail("/source", "a mindmotion source needs \"graph\" or \"graph_file\"");
      }
      r.get(s, "/source", "variation", c.motion.variation);
      r.get(s, "/source", "hint_path_fraction", c.motion.hint_path_fraction);
    }
    if (c.source == SourceKind::MindMap || c.source == SourceKind::MindMotion) {
      if (c.source == SourceKind::MindMap) r.only(s, "/source", {"kind", "map", "map_file"});
      if (s.contains("map")) {
        c.map = mindmap::parse_mind_map(r.object(s["map"], "/source/map").dump(),
                                        file + " /source/map");
      } else if (s.contains("map_file")) {
        std::string path;
        r.get(s, "/source", "map_file", path);
        c.map = mindmap::read_mind_map(resolve(base_dir, path));
      } else {
        r.fail("/source",
               "a " + std::string(to_string(c.source)) + " source needs \"map\" or \"map_file\"");
      }
    }
  }
  if (doc.contains("face")) {
    r.get(doc, "", "face", c.face);
    if (!c.face.empty() && c.face != "default" && c.face != "generic")
      c.face = resolve(base_dir, c.face);
  }
  r.get(doc, "", "fps", o.fps);
  r.get(doc, "", "lookahead", o.lookahead);
  r.get(doc, "", "seed", o.seed);
  if (doc.contains("display")) {
    const Json& d = r.object(doc["display"], "/display");
    r.only(d, "/display", {"onset", "offset", "tolerance"});
    r.get(d, "/display", "onset", o.display.onset);
    r.get(d, "/display", "offset", o.display.offset);
    r.get(d, "/display", "tolerance", o.display.tolerance);
  }
  r.get(doc, "", "blinks", o.blinks);
  r.get(doc, "", "gaze_noise", o.gaze_noise);
  r.get(doc, "", "head_noise", o.head_noise);
  if (doc.contains("blink")) {
    const Json& b = r.object(doc["blink"], "/blink");
    r.only(b, "/blink",
           {"mean_interval", "min_interval", "duration", "onset", "offset", "closure"});
    r.get(b, "/blink", "mean_interval", o.blink.mean_interval);
    r.get(b, "/blink", "min_interval", o.blink.min_interval);
    r.get(b, "/blink", "duration", o.blink.duration);
    r.get(b, "/blink", "onset", o.blink.onset);
    r.get(b, "/blink", "offset", o.blink.offset);
    r.get(b, "/blink", "closure", o.blink.closure);
  }
  for (const char* key : {"gaze", "head"}) {
    if (!doc.contains(key)) continue;
    const std::string p = std::string("/") + key;
    ch::NoiseOptions& n = std::string(key) == "gaze" ? o.gaze : o.head;
    const Json& j = r.object(doc[key], p);
    r.only(j, p, {"amplitude", "mean_hold", "min_hold", "transition"});
    r.get(j, p, "amplitude", n.amplitude);
    r.get(j, p, "mean_hold", n.mean_hold);
    r.get(j, p, "min_hold", n.min_hold);
    r.get(j, p, "transition", n.transition);
  }
  r.get(doc, "", "chunk_seconds", o.chunk_seconds);
  if (doc.contains("mix")) {
    const Json& m = r.object(doc["mix"], "/mix");
    r.only(m, "/mix", {"dmin_plus", "dmin_minus", "active_threshold", "priority"});
    r.get(m, "/mix", "dmin_plus", o.mix.dmin_plus);
    r.get(m, "/mix", "dmin_minus", o.mix.dmin_minus);
    r.get(m, "/mix", "active_threshold", o.mix.active_threshold);
    if (m.contains("priority")) {
      const Json& pr = m["priority"];
      if (!pr.is_array() || pr.size() != ch::kChannelCount)
        r.fail("/mix/priority", "expected 6 integers");
      for (std::size_t k = 0; k < ch::kChannelCount; ++k) {
        if (!pr[k].is_number_integer())
          r.fail("/mix/priority/" + std::to_string(k), "expected an integer");
        o.mix.priority[k] = pr[k].get<int>();
      }
    }
  }
  if (doc.contains("coarticulation")) {
    const Json& m = r.object(doc["coarticulation"], "/coarticulation");
    r.only(m, "/coarticulation", {"time_unit", "rest_dominance", "cutoff"});
    r.get(m, "/coarticulation", "time_unit", o.coarticulation.time_unit);
    r.get(m, "/coarticulation", "rest_dominance", o.coarticulation.rest_dominance);
    r.get(m, "/coarticulation", "cutoff", o.coarticulation.cutoff);
  }
  r.get(doc, "", "silence_pad", o.silence_pad);
  if (doc.contains("speech")) {
    const Json& s = r.object(doc["speech"], "/speech");
    r.only(s, "/speech", {"voice", "rate", "pitch", "program"});
    r.get(s, "/speech", "voice", o.speech.voice);
    r.get(s, "/speech", "rate", o.speech.rate);
    r.get(s, "/speech", "pitch", o.speech.pitch);
    r.get(s, "/speech", "program", o.speech.program);
  }
  r.get(doc, "", "step_seconds", o.step_seconds);
  r.get(doc, "", "direct_decay_per_second", o.direct_decay_per_second);
  try {
    c.validate();
  } catch (const InvalidInput& e) {
    r.fail("", e.what());
  }
  return c;
}

CharacterConfig read_character_config(const std::string& path) {
  const std::string base = std::filesystem::path(path).parent_path().string();
  return parse_character_config(core::read_file(path), path, base);
}

std::string format_character_config(const CharacterConfig& c) {
  c.validate();
  const CharacterOptions& o = c.options;
  Json doc = core::make_envelope("character", kConfigVersion);
  Json s;
  s["kind"] = std::string(to_string(c.source));
  if (c.source == SourceKind::Parlee) {
    s["domain"] = c.domain_text;
    s["agent"] = Json::parse(parlee::write_agent(c.agent));
  }
  if (c.source == SourceKind::MindMap || c.source == SourceKind::MindMotion)
    s["map"] = Json::parse(mindmap::to_json_text(c.map));
  if (c.source == SourceKind::MindMotion) {
    if (c.motion.graph_file.empty())
      s["graph"] = Json::parse(motiongraph::graph_to_json(*c.motion.graph));
    else
      s["graph_file"] = c.motion.graph_file;
    s["variation"] = c.motion.variation;
    s["hint_path_fraction"] = c.motion.hint_path_fraction;
  }
  doc["source"] = s;
  if (!c.face.empty()) doc["face"] = c.face;
  doc["fps"] = o.fps;
  doc["lookahead"] = o.lookahead;
  doc["seed"] = o.seed;
  doc["display"] = {
      {"onset", o.display.onset}, {"offset", o.display.offset}, {"tolerance", o.display.tolerance}};
  doc["blinks"] = o.blinks;
  doc["gaze_noise"] = o.gaze_noise;
  doc["head_noise"] = o.head_noise;
  doc["blink"] = {{"mean_interval", o.blink.mean_interval},
                  {"min_interval", o.blink.min_interval},
                  {"duration", o.blink.duration},
                  {"onset", o.blink.onset},
                  {"offset", o.blink.offset},
                  {"closure", o.blink.closure}};
  for (const auto& [key, n] :
       {std::pair<const char*, const ch::NoiseOptions*>{"gaze", &o.gaze}, {"head", &o.head}})
    doc[key] = {{"amplitude", n->amplitude},
                {"mean_hold", n->mean_hold},
                {"min_hold", n->min_hold},
                {"transition", n->transition}};
  doc["chunk_seconds"] = o.chunk_seconds;
  doc["mix"] = {{"dmin_plus", o.mix.dmin_plus},
                {"dmin_minus", o.mix.dmin_minus},
                {"active_threshold", o.mix.active_threshold},
                {"priority", o.mix.priority}};
  doc["coarticulation"] = {{"time_unit", o.coarticulation.time_unit},
                           {"rest_dominance", o.coarticulation.rest_dominance},
                           {"cutoff", o.coarticulation.cutoff}};
  doc["silence_pad"] = o.silence_pad;
  doc["speech"] = {{"voice", o.speech.voice},
                   {"rate", o.speech.rate},
                   {"pitch", o.speech.pitch},
                   {"program", o.speech.program}};
  doc["step_seconds"] = o.step_seconds;
  doc["direct_decay_per_second"] = o.direct_decay_per_second;
  return doc.dump(1) + "\n";
}

CharacterConfig mindmotion_config(const std::string& graph_file, const std::string& map_file,
                                  CharacterConfig base) {
  if (base.source != SourceKind::Direct)
    throw InvalidInput("mindmotion config: the base config has the " +
                       std::string(to_string(base.source)) +
                       " source; the graph and the map make the source");
  base.source = SourceKind::MindMotion;
  base.map = mindmap::read_mind_map(map_file);
  base.motion.graph =
      std::make_shared<const motiongraph::MotionGraph>(motiongraph::read_graph(graph_file));
  base.motion.graph_file = graph_file;
  base.validate();
  return base;
}

// ------------------------------------------------------------------------------------ snapshots

namespace {

Json channel_json(const StreamingChannel& c) {
  Json items = Json::array();
  for (const auto& it : c.items()) {
    items.push_back({{"timing",
                      {{"start", it.timing.start},
                       {"end", it.timing.end},
                       {"onset", it.timing.onset},
                       {"offset", it.timing.offset}}},
                     {"target", it.target},
                     {"start_value", it.start_value},
                     {"overlaps", it.overlaps},
                     {"previous_offset", it.previous_offset},
                     {"previous_end", num(it.previous_end)}});
  }
  return items;
}

std::vector<double> numbers(const Reader& r, const Json& j, const std::string& p, std::size_t n,
                            bool allow_null) {
  if (!j.is_array() || (n != SIZE_MAX && j.size() != n))
    r.fail(p, "expected an array of " +
                  (n == SIZE_MAX ? std::string("numbers") : std::to_string(n) + " numbers"));
  std::vector<double> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i)
    out.push_back(allow_null ? r.number(j[i], p + "/" + std::to_string(i))
                             : r.finite(j[i], p + "/" + std::to_string(i)));
  return out;
}

void restore_channel(const Reader& r, const Json& j, const std::string& p, StreamingChannel& c) {
  if (!j.is_array()) r.fail(p, "expected an array of movements");
  std::vector<StreamingChannel::Item> items;
  const std::size_t np = c.parameters().size();
  for (std::size_t k = 0; k < j.size(); ++k) {
    const std::string q = p + "/" + std::to_string(k);
    const Json& o = r.object(j[k], q);
    r.only(o, q,
           {"timing", "target", "start_value", "overlaps", "previous_offset", "previous_end"});
    StreamingChannel::Item it;
    if (!o.contains("timing")) r.fail(q + "/timing", "missing");
    read_timing(r, r.object(o["timing"], q + "/timing"), q + "/timing", it.timing);
    if (!o.contains("target") || !o.contains("start_value"))
      r.fail(q, "missing target or start_value");
    it.target = numbers(r, o["target"], q + "/target", np, false);
    it.start_value = numbers(r, o["start_value"], q + "/start_value", np, false);
    r.get(o, q, "overlaps", it.overlaps);
    r.get(o, q, "previous_offset", it.previous_offset);
    it.previous_end =
        o.contains("previous_end") ? r.number(o["previous_end"], q + "/previous_end") : -INFINITY;
    items.push_back(std::move(it));
  }
  try {
    c.restore(std::move(items));
  } catch (const InvalidInput& e) {
    r.fail(p, e.what());
  }
}

}  // namespace

std::string Character::snapshot() const {
  const Impl& m = *impl_;
  if (m.config.source == SourceKind::MindMotion)
    throw InvalidInput(
        "snapshot: not available for the mindmotion source (the motion player's state is not "
        "serialisable yet)");
  Json doc = core::make_envelope("character_state", kStateVersion);
  doc["config"] = Json::parse(format_character_config(m.config));
  doc["time"] = m.time;
  Json src;
  switch (m.config.source) {
    case SourceKind::Direct:
      src = {{"values", m.direct}, {"time", m.direct_time}};
      break;
    case SourceKind::Parlee: {
      Json events = Json::array();
      for (const auto& e : m.parlee_log) {
        Json ev = {
            {"time", e.time}, {"action", e.action}, {"outcome", e.outcome}, {"note", e.note}};
        if (e.feedback) ev["feedback"] = *e.feedback;
        events.push_back(ev);
      }
      src = {{"events", events}, {"emotions", m.occ_last}, {"t_last", m.t_last}};
      break;
    }
    case SourceKind::MindMotion:
      break;  // refused above
    case SourceKind::MindMap: {
      Json events = Json::array();
      for (const auto& e : m.mind_log) {
        Json w = Json::object();
        for (const auto& [k, v] : e.weights) w[k] = v;
        events.push_back({{"time", e.time},
                          {"target", e.target},
                          {"stimulus", e.stimulus},
                          {"source", e.source},
                          {"weights", w}});
      }
      src = {{"events", events}, {"world_time", m.world->time()}};
      break;
    }
  }
  doc["source"] = src;
  doc["display"] = {{"any", m.shown_any}, {"shown", m.shown}};
  doc["channels"] = {{"emotion", channel_json(m.emotion)},
                     {"blinks", channel_json(m.blinks)},
                     {"gaze", channel_json(m.gaze)},
                     {"head", channel_json(m.head)}};
  doc["chunks"] = m.chunks;
  Json utts = Json::array();
  for (const auto& u : m.utts) {
    Json segs = Json::array();
    for (const auto& s : u.segs) segs.push_back({s.viseme, s.start, s.end, s.apex, s.label});
    utts.push_back({{"start", u.start}, {"end", u.end}, {"segments", segs}});
  }
  doc["speech"] = utts;
  const StreamingMixer::State ms = m.mixer.state();
  Json inh = Json::array();
  for (double v : ms.last_inhibited) inh.push_back(num(v));
  doc["mixer"] = {{"frames_in", ms.frames_in},
                  {"ring", ms.ring},
                  {"last_inhibited", inh},
                  {"output", ms.output}};
  doc["esv_ring"] = m.esv_ring;
  doc["esv_out"] = m.esv_out;
  return doc.dump() + "\n";
}

Character restore_character(std::string_view text, const std::string& file) {
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "character_state", kStateVersion, file);
  const Reader r{file};
  r.only(doc, "",
         {"format", "version", "generator", "config", "time", "source", "display", "channels",
          "chunks", "speech", "mixer", "esv_ring", "esv_out"});
  for (const char* k : {"config", "time", "source", "display", "channels", "chunks", "speech",
                        "mixer", "esv_ring", "esv_out"})
    if (!doc.contains(k)) r.fail(std::string("/") + k, "missing");
  auto impl = std::make_unique<Character::Impl>(
      parse_character_config(r.object(doc["config"], "/config").dump(), file + " /config"));
  Character::Impl& m = *impl;
  m.time = r.finite(doc["time"], "/time");
  const Json& src = r.object(doc["source"], "/source");
  switch (m.config.source) {
    case SourceKind::MindMotion:
      r.fail("/config/source/kind", "a mindmotion character has no snapshot");
    case SourceKind::Direct: {
      const auto v =
          numbers(r, src.contains("values") ? src["values"] : Json(), "/source/values", 6, false);
      for (double x : v)
        if (!(x >= 0 && x <= 1)) r.fail("/source/values", "emotion intensities must be in [0, 1]");
      std::copy(v.begin(), v.end(), m.direct.begin());
      r.get(src, "/source", "time", m.direct_time);
      if (!(m.direct_time >= 0 && m.direct_time <= m.time))
        r.fail("/source/time", "must be in [0, /time]");
      break;
    }
    case SourceKind::Parlee: {
      const Json& ev = src.contains("events") ? src["events"] : Json();
      if (!ev.is_array()) r.fail("/source/events", "expected an array");
      for (std::size_t i = 0; i < ev.size(); ++i) {
        const std::string p = "/source/events/" + std::to_string(i);
        const Json& e = r.object(ev[i], p);
        parlee::Event pe;
        r.get(e, p, "time", pe.time);
        r.get(e, p, "action", pe.action);
        r.get(e, p, "outcome", pe.outcome);
        r.get(e, p, "note", pe.note);
        if (e.contains("feedback")) pe.feedback = r.finite(e["feedback"], p + "/feedback");
        try {
          m.agent->step(pe);
        } catch (const std::exception& ex) {
          r.fail(p, std::string("event does not replay: ") + ex.what());
        }
        m.parlee_log.push_back(pe);
      }
      const auto occ = numbers(r, src.contains("emotions") ? src["emotions"] : Json(),
                               "/source/emotions", parlee::kEmotionCount, false);
      for (std::size_t i = 0; i < occ.size(); ++i)
        if (!(occ[i] >= 0 && occ[i] <= m.config.agent.emotions.omega[i]))
          r.fail("/source/emotions/" + std::to_string(i), "intensity must be in [0, omega]");
      std::copy(occ.begin(), occ.end(), m.occ_last.begin());
      r.get(src, "/source", "t_last", m.t_last);
      if (!(m.t_last >= 0 && m.t_last <= m.time)) r.fail("/source/t_last", "must be in [0, /time]");
      break;
    }
    case SourceKind::MindMap: {
      const Json& ev = src.contains("events") ? src["events"] : Json();
      if (!ev.is_array()) r.fail("/source/events", "expected an array");
      for (std::size_t i = 0; i < ev.size(); ++i) {
        const std::string p = "/source/events/" + std::to_string(i);
        const Json& e = r.object(ev[i], p);
        mindmap::Event me;
        r.get(e, p, "time", me.time);
        r.get(e, p, "target", me.target);
        r.get(e, p, "stimulus", me.stimulus);
        r.get(e, p, "source", me.source);
        if (e.contains("weights"))
          for (auto w = e["weights"].begin(); w != e["weights"].end(); ++w)
            me.weights.emplace_back(w.key(), r.finite(w.value(), p + "/weights"));
        try {
          if (me.time > m.world->time()) m.world->advance_to(me.time, nullptr);
          m.world->apply(me, nullptr);
        } catch (const std::exception& ex) {
          r.fail(p, std::string("stimulus does not replay: ") + ex.what());
        }
        m.mind_log.push_back(me);
      }
      double wt = 0;
      r.get(src, "/source", "world_time", wt);
      if (wt > m.world->time()) m.world->advance_to(wt, nullptr);
      break;
    }
  }
  const Json& d = r.object(doc["display"], "/display");
  r.get(d, "/display", "any", m.shown_any);
  const auto shown =
      numbers(r, d.contains("shown") ? d["shown"] : Json(), "/display/shown", 6, false);
  for (double x : shown)
    if (!(x >= 0 && x <= 1)) r.fail("/display/shown", "emotion intensities must be in [0, 1]");
  std::copy(shown.begin(), shown.end(), m.shown.begin());
  const Json& chs = r.object(doc["channels"], "/channels");
  restore_channel(r, chs.contains("emotion") ? chs["emotion"] : Json(), "/channels/emotion",
                  m.emotion);
  restore_channel(r, chs.contains("blinks") ? chs["blinks"] : Json(), "/channels/blinks", m.blinks);
  restore_channel(r, chs.contains("gaze") ? chs["gaze"] : Json(), "/channels/gaze", m.gaze);
  restore_channel(r, chs.contains("head") ? chs["head"] : Json(), "/channels/head", m.head);
  if (!doc["chunks"].is_number_unsigned()) r.fail("/chunks", "expected a non-negative integer");
  m.chunks = doc["chunks"].get<std::uint64_t>();
  const Json& sp = doc["speech"];
  if (!sp.is_array()) r.fail("/speech", "expected an array");
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const std::string p = "/speech/" + std::to_string(i);
    const Json& u = r.object(sp[i], p);
    Character::Impl::Utt utt;
    utt.start = u.contains("start") ? r.finite(u["start"], p + "/start") : 0.0;
    utt.end = u.contains("end") ? r.finite(u["end"], p + "/end") : 0.0;
    const Json& segs = u.contains("segments") ? u["segments"] : Json();
    if (!segs.is_array()) r.fail(p + "/segments", "expected an array");
    for (std::size_t k = 0; k < segs.size(); ++k) {
      const std::string q = p + "/segments/" + std::to_string(k);
      const Json& s = segs[k];
      if (!s.is_array() || s.size() != 5 || !s[0].is_string() || !s[4].is_string())
        r.fail(q, "expected [viseme, start, end, apex, label]");
      utt.segs.push_back({s[0].get<std::string>(), r.finite(s[1], q + "/1"),
                          r.finite(s[2], q + "/2"), r.finite(s[3], q + "/3"),
                          s[4].get<std::string>()});
    }
    try {
      m.build_utt(utt);
    } catch (const InvalidInput& e) {
      r.fail(p, e.what());
    }
    m.utts.push_back(std::move(utt));
  }
  const Json& mx = r.object(doc["mixer"], "/mixer");
  StreamingMixer::State st;
  if (!mx.contains("frames_in") || !mx["frames_in"].is_number_unsigned())
    r.fail("/mixer/frames_in", "expected an integer");
  st.frames_in = mx["frames_in"].get<std::size_t>();
  st.ring = numbers(r, mx.contains("ring") ? mx["ring"] : Json(), "/mixer/ring", SIZE_MAX, false);
  st.last_inhibited = numbers(r, mx.contains("last_inhibited") ? mx["last_inhibited"] : Json(),
                              "/mixer/last_inhibited", SIZE_MAX, true);
  st.output =
      numbers(r, mx.contains("output") ? mx["output"] : Json(), "/mixer/output", SIZE_MAX, false);
  try {
    m.mixer.restore(st);
  } catch (const InvalidInput& e) {
    r.fail("/mixer", e.what());
  }
  m.params_out = st.output;
  // the clocks must agree (update() computes every frame n with n/fps <= time): a foreign or edited
  // snapshot must not make the next update() loop for ages
  const double fps = m.config.options.fps;
  if (!(m.time >= 0 && m.time <= 1e9)) r.fail("/time", "must be in [0, 1e9] s");
  const bool due_ok = st.frames_in == 0
                          ? !(0.0 <= m.time + 1e-9)
                          : static_cast<double>(st.frames_in - 1) / fps <= m.time + 1e-9 &&
                                !(static_cast<double>(st.frames_in) / fps <= m.time + 1e-9);
  if (!due_ok) r.fail("/mixer/frames_in", "does not match /time at the configured fps");
  const Json& ring = doc["esv_ring"];
  if (!ring.is_array() || ring.size() != m.esv_ring.size()) r.fail("/esv_ring", "wrong size");
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const auto v = numbers(r, ring[i], "/esv_ring/" + std::to_string(i), 6, false);
    for (double x : v)
      if (!(x >= 0 && x <= 1))
        r.fail("/esv_ring/" + std::to_string(i), "emotion intensities must be in [0, 1]");
    std::copy(v.begin(), v.end(), m.esv_ring[i].begin());
  }
  const auto eo = numbers(r, doc["esv_out"], "/esv_out", 6, false);
  std::copy(eo.begin(), eo.end(), m.esv_out.begin());
  return Character(std::move(impl));
}

}  // namespace emoface::runtime
