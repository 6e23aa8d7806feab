#include "emoface/mindmap/dot.hpp"

#include <cmath>
#include <cstdio>

#include "emoface/core/errors.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/mindmap/chart.hpp"

namespace emoface::mindmap {

namespace {
std::string hex(std::uint32_t c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%06x", c & 0xffffffu);
  return buf;
}
std::string fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string emotion_id(std::size_t e) { return "e" + std::to_string(e); }
std::string action_id(std::size_t a) { return "a" + std::to_string(a); }
}  // namespace

void MindMapDotOptions::validate(const MindMap& map) const {
  if (mood.empty()) return;
  if (mood.size() != map.emotion_count())
    throw InvalidInput("mind_map_dot: the mood needs " + std::to_string(map.emotion_count()) +
                       " values");
  for (double v : mood)
    if (!(v >= 0.0 && v <= 1.0)) throw InvalidInput("mind_map_dot: mood values must be in [0, 1]");
}

std::string mind_map_dot(const MindMap& map, const MindMapDotOptions& options) {
  validate(map);
  options.validate(map);
  using core::dot_quote;
  std::string out = "digraph " + dot_quote("mind map " + map.character) + " {\n";
  out += "  graph [layout=neato, overlap=false, splines=true, fontname=\"Helvetica\"];\n";
  out +=
      "  node [fontname=\"Helvetica\", fontsize=11];\n  edge [fontname=\"Helvetica\", "
      "fontsize=9];\n";
  out += "  character [shape=doubleoctagon, style=filled, fillcolor=\"#eeeeee\", label=" +
         dot_quote(map.character) + "];\n";
  for (std::size_t e = 0; e < map.emotion_count(); ++e) {
    std::string label = map.emotions[e];
    std::string width = "1";
    if (!options.mood.empty()) {
      label += "\nmood " + fixed(options.mood[e]);
      width = fixed(1.0 + 4.0 * options.mood[e]);
    }
    // The background context (issue 19: may change at run time, World::traits).
    if (!map.traits.background_context.empty()) label += "\ncontext " + fixed(map.traits.background_context[e]);
    out += "  " + emotion_id(e) + " [shape=ellipse, style=filled, fillcolor=\"" +
           hex(emotion_colour(e)) + "40\", color=\"" + hex(emotion_colour(e)) +
           "\", penwidth=" + width + ", label=" + dot_quote(label) + "];\n";
    out += "  character -> " + emotion_id(e) + " [arrowhead=none, color=\"#999999\"];\n";
  }
  for (std::size_t a = 0; a < map.actions.size(); ++a) {
    const ActionNode& n = map.actions[a];
    std::string label = n.name;
    if (n.performable) label += "\n[" + n.label + "]";
    const char* shape = n.performable ? (n.receivable ? "hexagon" : "box") : "note";
    out += "  " + action_id(a) + " [shape=" + shape + (n.performable ? ", style=rounded" : "") +
           ", label=" + dot_quote(label) + "];\n";
  }
  for (const StimulusEdge& s : map.stimulus_edges)
    out += "  " + action_id(s.action) + " -> " + emotion_id(s.emotion) + " [color=\"" +
           hex(emotion_colour(s.emotion)) + "\"" +
           (options.weights ? ", label=" + dot_quote(fixed(s.weight)) : "") + "];\n";
  for (const ResponseEdge& r : map.response_edges)
    out += "  " + emotion_id(r.emotion) + " -> " + action_id(r.action) + " [color=\"" +
           hex(emotion_colour(r.emotion)) + "\"" +
           (options.weights ? ", label=" + dot_quote(fixed(r.weight)) : "") + "];\n";
  for (const ChainEdge& c : map.chain_edges)
    out +=
        "  " + action_id(c.from) + " -> " + action_id(c.to) + " [style=dashed, label=\"then\"];\n";
  for (std::size_t e = 0; e < map.emotion_count(); ++e)
    if (const std::size_t a = map.representative_of(e); a != kNone)
      out += "  " + emotion_id(e) + " -> " + action_id(a) + " [style=dotted, label=\"decay\"];\n";
  // Affection rows (the moods towards other characters, eq. 2): a node per other character, the
  // edge labelled with its non-zero entries.
  for (std::size_t k = 0; k < map.traits.affection.size(); ++k) {
    const auto& [who, row] = map.traits.affection[k];
    std::string text;
    for (std::size_t e = 0; e < row.size(); ++e)
      if (row[e] > 0.0) text += (text.empty() ? "" : "\n") + map.emotions[e] + " " + fixed(row[e]);
    const std::string id = "other" + std::to_string(k);
    out += "  " + id + " [shape=octagon, style=dashed, label=" + dot_quote(who) + "];\n";
    out += "  character -> " + id + " [style=dashed, color=\"#666666\", label=" +
           dot_quote("affection\n" + (text.empty() ? std::string("none") : text)) + "];\n";
  }
  return out + "}\n";
}

std::vector<double> mood_at(const SimulationResult& result, std::size_t character, double time) {
  if (character >= result.mood.size() || result.times.empty())
    throw InvalidInput("mood_at: character index out of range or no mood samples");
  std::size_t k = 0;
  while (k + 1 < result.times.size() && result.times[k + 1] <= time + 1e-9) ++k;
  const std::size_t n = result.mood[character].size() / result.times.size();
  return {result.mood[character].begin() + static_cast<std::ptrdiff_t>(k * n),
          result.mood[character].begin() + static_cast<std::ptrdiff_t>((k + 1) * n)};
}

std::string mind_map_dot_at(const std::vector<MindMap>& maps, const std::string& character,
                            const std::vector<Event>* events, double time,
                            SimulationOptions simulation) {
  std::size_t c = maps.size();
  for (std::size_t i = 0; i < maps.size(); ++i)
    if (maps[i].character == character) c = i;
  if (c == maps.size()) throw InvalidInput("no mind map of \"" + character + "\"");
  MindMapDotOptions o;
  if (events) {
    if (!(time >= 0.0)) throw InvalidInput("mind_map_dot_at: events need a time >= 0");
    simulation.duration = time;
    o.mood = mood_at(simulate(maps, *events, simulation), c, time);
    return mind_map_dot(map_at(maps, *events, c, time, simulation), o);  // as it stands by then
  }
  if (time >= 0.0) o.mood = maps[c].traits.starting_mood;  // no stimuli: the starting mood
  return mind_map_dot(maps[c], o);
}

}  // namespace emoface::mindmap
