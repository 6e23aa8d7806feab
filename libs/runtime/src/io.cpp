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
using detail::get;
using detail::Json;
using detail::JsonValue;
using detail::num;

namespace {

constexpr core::FormatVersion kConfigVersion{1, 1};  // 1.1: the mindmotion source
constexpr core::FormatVersion kStateVersion{1, 0};

std::string resolve(const std::string& base, const std::string& path) {
  if (base.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(base) / path).string();
}

void read_timing(const JsonValue& o, ch::Timing& t) {
  o.only_keys({"start", "end", "onset", "offset"});
  get(o, "start", t.start);
  get(o, "end", t.end);
  get(o, "onset", t.onset);
  get(o, "offset", t.offset);
}

}  // namespace

CharacterConfig parse_character_config(std::string_view text, const std::string& file,
                                       const std::string& base_dir) {
  const core::JsonReader reader(text, file, "character", kConfigVersion);
  const JsonValue doc = reader.root();
  doc.only_keys({"source", "face", "fps", "lookahead", "seed", "display", "blinks", "gaze_noise",
                 "head_noise", "blink", "gaze", "head", "chunk_seconds", "mix", "coarticulation",
                 "silence_pad", "speech", "step_seconds", "direct_decay_per_second"});
  CharacterConfig c;
  CharacterOptions& o = c.options;
  if (const auto s = doc.find("source")) {
    s->expect_object();
    std::string kind = "direct";
    get(*s, "kind", kind);
    try {
      c.source = source_kind_from_string(kind);
    } catch (const InvalidInput& e) {
      s->at("kind").fail(e.what());
    }
    switch (c.source) {
      case SourceKind::Direct:
        s->only_keys({"kind"});
        break;
      case SourceKind::Parlee:
        s->only_keys({"kind", "domain", "domain_file", "agent", "agent_file"});
        break;
      case SourceKind::MindMap:
        s->only_keys({"kind", "map", "map_file"});
        break;
      case SourceKind::MindMotion:
        s->only_keys(
            {"kind", "map", "map_file", "graph", "graph_file", "variation", "hint_path_fraction"});
        break;
    }
    if (c.source == SourceKind::Parlee) {
      if (const auto d = s->find("domain")) {
        c.domain_text = d->string();
      } else if (const auto f = s->find("domain_file")) {
        c.domain_text = core::read_file(resolve(base_dir, f->string()));
      } else {
        s->fail("a parlee source needs \"domain\" (text) or \"domain_file\"");
      }
      if (const auto a = s->find("agent")) {
        c.agent = parlee::parse_agent(a->expect_object().json().dump(), file + " /source/agent");
      } else if (const auto f = s->find("agent_file")) {
        c.agent = parlee::read_agent_file(resolve(base_dir, f->string()));
      }
    }
    if (c.source == SourceKind::MindMotion) {
      if (const auto g = s->find("graph")) {
        c.motion.graph =
            std::make_shared<const motiongraph::MotionGraph>(motiongraph::parse_graph_json(
                g->expect_object().json().dump(), file + " /source/graph"));
      } else if (const auto f = s->find("graph_file")) {
        c.motion.graph_file = resolve(base_dir, f->string());
        c.motion.graph = std::make_shared<const motiongraph::MotionGraph>(
            motiongraph::read_graph(c.motion.graph_file));
      } else {
        s->fail("a mindmotion source needs \"graph\" or \"graph_file\"");
      }
      get(*s, "variation", c.motion.variation);
      get(*s, "hint_path_fraction", c.motion.hint_path_fraction);
    }
    if (c.source == SourceKind::MindMap || c.source == SourceKind::MindMotion) {
      if (const auto m = s->find("map")) {
        c.map = mindmap::parse_mind_map(m->expect_object().json().dump(), file + " /source/map");
      } else if (const auto f = s->find("map_file")) {
        c.map = mindmap::read_mind_map(resolve(base_dir, f->string()));
      } else {
        s->fail("a " + std::string(to_string(c.source)) + " source needs \"map\" or \"map_file\"");
      }
    }
  }
  if (const auto f = doc.find("face")) {
    c.face = f->string();
    if (!c.face.empty() && c.face != "default" && c.face != "generic")
      c.face = resolve(base_dir, c.face);
  }
  get(doc, "fps", o.fps);
  get(doc, "lookahead", o.lookahead);
  get(doc, "seed", o.seed);
  if (const auto d = doc.find("display")) {
    d->only_keys({"onset", "offset", "tolerance"});
    get(*d, "onset", o.display.onset);
    get(*d, "offset", o.display.offset);
    get(*d, "tolerance", o.display.tolerance);
  }
  get(doc, "blinks", o.blinks);
  get(doc, "gaze_noise", o.gaze_noise);
  get(doc, "head_noise", o.head_noise);
  if (const auto b = doc.find("blink")) {
    b->only_keys({"mean_interval", "min_interval", "duration", "onset", "offset", "closure"});
    get(*b, "mean_interval", o.blink.mean_interval);
    get(*b, "min_interval", o.blink.min_interval);
    get(*b, "duration", o.blink.duration);
    get(*b, "onset", o.blink.onset);
    get(*b, "offset", o.blink.offset);
    get(*b, "closure", o.blink.closure);
  }
  for (const char* key : {"gaze", "head"}) {
    const auto j = doc.find(key);
    if (!j) continue;
    ch::NoiseOptions& n = std::string(key) == "gaze" ? o.gaze : o.head;
    j->only_keys({"amplitude", "mean_hold", "min_hold", "transition"});
    get(*j, "amplitude", n.amplitude);
    get(*j, "mean_hold", n.mean_hold);
    get(*j, "min_hold", n.min_hold);
    get(*j, "transition", n.transition);
  }
  get(doc, "chunk_seconds", o.chunk_seconds);
  if (const auto m = doc.find("mix")) {
    m->only_keys({"dmin_plus", "dmin_minus", "active_threshold", "priority"});
    get(*m, "dmin_plus", o.mix.dmin_plus);
    get(*m, "dmin_minus", o.mix.dmin_minus);
    get(*m, "active_threshold", o.mix.active_threshold);
    if (const auto pr = m->find("priority")) {
      pr->expect_array(ch::kChannelCount);
      for (std::size_t k = 0; k < ch::kChannelCount; ++k)
        o.mix.priority[k] = static_cast<int>((*pr)[k].integer(-1000000000, 1000000000));
    }
  }
  if (const auto m = doc.find("coarticulation")) {
    m->only_keys({"time_unit", "rest_dominance", "cutoff"});
    get(*m, "time_unit", o.coarticulation.time_unit);
    get(*m, "rest_dominance", o.coarticulation.rest_dominance);
    get(*m, "cutoff", o.coarticulation.cutoff);
  }
  get(doc, "silence_pad", o.silence_pad);
  if (const auto s = doc.find("speech")) {
    s->only_keys({"voice", "rate", "pitch", "program"});
    get(*s, "voice", o.speech.voice);
    get(*s, "rate", o.speech.rate);
    get(*s, "pitch", o.speech.pitch);
    get(*s, "program", o.speech.program);
  }
  get(doc, "step_seconds", o.step_seconds);
  get(doc, "direct_decay_per_second", o.direct_decay_per_second);
  try {
    c.validate();
  } catch (const InvalidInput& e) {
    doc.fail(e.what());
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

std::vector<double> numbers(const JsonValue& v, std::size_t n, bool allow_null) {
  v.expect_array();
  if (n != SIZE_MAX && v.size() != n)
    v.fail("expected an array of " + std::to_string(n) + " numbers, got " +
           std::to_string(v.size()) + " elements");
  std::vector<double> out;
  out.reserve(v.size());
  for (const JsonValue& x : v.items())
    out.push_back(allow_null ? detail::number_or_null(x) : x.number());
  return out;
}

void restore_channel(const JsonValue& v, StreamingChannel& c) {
  std::vector<StreamingChannel::Item> items;
  const std::size_t np = c.parameters().size();
  for (const JsonValue& o : v.items()) {
    o.only_keys({"timing", "target", "start_value", "overlaps", "previous_offset", "previous_end"});
    StreamingChannel::Item it;
    read_timing(o.at("timing").expect_object(), it.timing);
    it.target = numbers(o.at("target"), np, false);
    it.start_value = numbers(o.at("start_value"), np, false);
    get(o, "overlaps", it.overlaps);
    get(o, "previous_offset", it.previous_offset);
    if (const auto p = o.find("previous_end")) it.previous_end = detail::number_or_null(*p);
    items.push_back(std::move(it));
  }
  try {
    c.restore(std::move(items));
  } catch (const InvalidInput& e) {
    v.fail(e.what());
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
  const core::JsonReader reader(text, file, "character_state", kStateVersion);
  const JsonValue doc = reader.root();
  doc.only_keys({"config", "time", "source", "display", "channels", "chunks", "speech", "mixer",
                 "esv_ring", "esv_out"});
  for (const char* k : {"config", "time", "source", "display", "channels", "chunks", "speech",
                        "mixer", "esv_ring", "esv_out"})
    doc.at(k);  // "missing field" before anything is built
  auto impl = std::make_unique<Character::Impl>(
      parse_character_config(doc.at("config").expect_object().json().dump(), file + " /config"));
  Character::Impl& m = *impl;
  const JsonValue time = doc.at("time");
  m.time = time.number();
  if (!(m.time >= 0 && m.time <= 1e9)) time.fail("must be in [0, 1e9] s");
  const JsonValue src = doc.at("source").expect_object();
  switch (m.config.source) {
    case SourceKind::MindMotion:
      doc.at("config").fail("a mindmotion character has no snapshot");
    case SourceKind::Direct: {
      const JsonValue values = src.at("values");
      const auto v = numbers(values, 6, false);
      for (double x : v)
        if (!(x >= 0 && x <= 1)) values.fail("emotion intensities must be in [0, 1]");
      std::copy(v.begin(), v.end(), m.direct.begin());
      get(src, "time", m.direct_time);
      if (!(m.direct_time >= 0 && m.direct_time <= m.time))
        src.at("time").fail("must be in [0, /time]");
      break;
    }
    case SourceKind::Parlee: {
      for (const JsonValue& e : src.at("events").items()) {
        e.only_keys({"time", "action", "outcome", "note", "feedback"});
        parlee::Event pe;
        get(e, "time", pe.time);
        get(e, "action", pe.action);
        get(e, "outcome", pe.outcome);
        get(e, "note", pe.note);
        if (const auto f = e.find("feedback")) pe.feedback = f->number();
        try {
          m.agent->step(pe);
        } catch (const std::exception& ex) {
          e.fail(std::string("event does not replay: ") + ex.what());
        }
        m.parlee_log.push_back(pe);
      }
      const JsonValue emotions = src.at("emotions");
      const auto occ = numbers(emotions, parlee::kEmotionCount, false);
      for (std::size_t i = 0; i < occ.size(); ++i)
        if (!(occ[i] >= 0 && occ[i] <= m.config.agent.emotions.omega[i]))
          emotions[i].fail("intensity must be in [0, omega]");
      std::copy(occ.begin(), occ.end(), m.occ_last.begin());
      get(src, "t_last", m.t_last);
      if (!(m.t_last >= 0 && m.t_last <= m.time)) src.at("t_last").fail("must be in [0, /time]");
      break;
    }
    case SourceKind::MindMap: {
      for (const JsonValue& e : src.at("events").items()) {
        e.only_keys({"time", "target", "stimulus", "source", "weights"});
        mindmap::Event me;
        get(e, "time", me.time);
        get(e, "target", me.target);
        get(e, "stimulus", me.stimulus);
        get(e, "source", me.source);
        if (const auto w = e.find("weights"))
          for (const auto& [name, value] : w->members())
            me.weights.emplace_back(name, value.number());
        try {
          if (me.time > m.world->time()) m.world->advance_to(me.time, nullptr);
          m.world->apply(me, nullptr);
        } catch (const std::exception& ex) {
          e.fail(std::string("stimulus does not replay: ") + ex.what());
        }
        m.mind_log.push_back(me);
      }
      double wt = 0;
      get(src, "world_time", wt);
      if (wt > m.world->time()) m.world->advance_to(wt, nullptr);
      break;
    }
  }
  const JsonValue d = doc.at("display");
  d.only_keys({"any", "shown"});
  get(d, "any", m.shown_any);
  const auto shown = numbers(d.at("shown"), 6, false);
  for (double x : shown)
    if (!(x >= 0 && x <= 1)) d.at("shown").fail("emotion intensities must be in [0, 1]");
  std::copy(shown.begin(), shown.end(), m.shown.begin());
  const JsonValue chs = doc.at("channels");
  chs.only_keys({"emotion", "blinks", "gaze", "head"});
  restore_channel(chs.at("emotion"), m.emotion);
  restore_channel(chs.at("blinks"), m.blinks);
  restore_channel(chs.at("gaze"), m.gaze);
  restore_channel(chs.at("head"), m.head);
  m.chunks = detail::unsigned_integer(doc.at("chunks"));
  for (const JsonValue& u : doc.at("speech").items()) {
    u.only_keys({"start", "end", "segments"});
    Character::Impl::Utt utt;
    get(u, "start", utt.start);
    get(u, "end", utt.end);
    for (const JsonValue& seg : u.at("segments").items()) {
      seg.expect_array(5);
      utt.segs.push_back(
          {seg[0].string(), seg[1].number(), seg[2].number(), seg[3].number(), seg[4].string()});
    }
    try {
      m.build_utt(utt);
    } catch (const InvalidInput& e) {
      u.fail(e.what());
    }
    m.utts.push_back(std::move(utt));
  }
  const JsonValue mx = doc.at("mixer");
  mx.only_keys({"frames_in", "ring", "last_inhibited", "output"});
  StreamingMixer::State st;
  st.frames_in = static_cast<std::size_t>(detail::unsigned_integer(mx.at("frames_in")));
  st.ring = numbers(mx.at("ring"), SIZE_MAX, false);
  st.last_inhibited = numbers(mx.at("last_inhibited"), SIZE_MAX, true);
  st.output = numbers(mx.at("output"), SIZE_MAX, false);
  try {
    m.mixer.restore(st);
  } catch (const InvalidInput& e) {
    mx.fail(e.what());
  }
  m.params_out = st.output;
  // the clocks must agree (update() computes every frame n with n/fps <= time): a foreign or edited
  // snapshot must not make the next update() loop for ages
  const double fps = m.config.options.fps;
  const bool due_ok = st.frames_in == 0
                          ? !(0.0 <= m.time + 1e-9)
                          : static_cast<double>(st.frames_in - 1) / fps <= m.time + 1e-9 &&
                                !(static_cast<double>(st.frames_in) / fps <= m.time + 1e-9);
  if (!due_ok) mx.at("frames_in").fail("does not match /time at the configured fps");
  const JsonValue ring = doc.at("esv_ring");
  ring.expect_array(m.esv_ring.size());
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const auto v = numbers(ring[i], 6, false);
    for (double x : v)
      if (!(x >= 0 && x <= 1)) ring[i].fail("emotion intensities must be in [0, 1]");
    std::copy(v.begin(), v.end(), m.esv_ring[i].begin());
  }
  const auto eo = numbers(doc.at("esv_out"), 6, false);
  std::copy(eo.begin(), eo.end(), m.esv_out.begin());
  return Character(std::move(impl));
}

}  // namespace emoface::runtime
