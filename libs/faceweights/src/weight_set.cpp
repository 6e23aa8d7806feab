#include "emoface/faceweights/weight_set.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"
#include "emoface/faceweights/names.hpp"

namespace emoface::faceweights {
namespace detail {
std::string_view builtin_arkit_json();
std::string_view builtin_facs_json();
}  // namespace detail

namespace {

using Json = nlohmann::ordered_json;


/// "<name>+" / "<name>-" → ("<name>", sign); plain name → (name, 0).
std::pair<std::string, int> split_input(const std::string& input) {
  if (!input.empty() && (input.back() == '+' || input.back() == '-'))
    return {input.substr(0, input.size() - 1), input.back() == '+' ? 1 : -1};
  return {input, 0};
}

// Reads a weight set through core::JsonReader: located errors and the unknown-field rule of
// docs/formats.md at every level (a newer minor version may add fields, which are ignored).
WeightSet parse_document(const core::JsonValue& doc) {
  doc.only_keys({"set", "naming", "description", "ranges", "sources", "targets"});
  WeightSet set;
  set.set = doc.at("set").string();
  set.naming = doc.at("naming").string();
  set.description = doc.string_or("description", "");
  if (auto ranges = doc.find("ranges"))
    for (const auto& [name, v] : ranges->members()) set.ranges[name] = v.number();
  for (const core::JsonValue& s : doc.at("sources").items()) {
    s.only_keys({"id", "citation"});
    set.sources.push_back({s.at("id").string(), s.at("citation").string()});
  }
  for (const core::JsonValue& t : doc.at("targets").items()) {
    t.only_keys({"name", "terms", "facs", "sources", "note"});
    Target target;
    target.name = t.at("name").string();
    for (const auto& [input, w] : t.at("terms").members())
      target.terms.push_back({input, w.number()});
    target.facs = t.string_or("facs", "");
    target.note = t.string_or("note", "");
    if (auto s = t.find("sources"))
      for (const core::JsonValue& id : s->items()) target.sources.push_back(id.string());
    set.targets.push_back(std::move(target));
  }
  try {
    set.validate();
  } catch (const InvalidInput& e) {
    doc.at("targets").fail(e.what());
  }
  return set;
}

}  // namespace

std::optional<std::size_t> WeightSet::find(std::string_view name) const {
  std::string key = core::ascii_lower(name);
  if (naming == "arkit") {
    if (auto raw = arkit_raw_name(name)) key = core::ascii_lower(*raw);
  }
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (core::ascii_lower(targets[i].name) == key) return i;
  }
  return std::nullopt;
}

std::vector<std::string> WeightSet::target_names() const {
  std::vector<std::string> out;
  for (const auto& t : targets) out.push_back(t.name);
  return out;
}

void WeightSet::validate() const {
  if (set.empty()) throw InvalidInput("weight set: empty \"set\" name");
  if (targets.empty()) throw InvalidInput("weight set '" + set + "': no targets");
  std::set<std::string> ids;
  for (const auto& s : sources) {
    if (s.id.empty() || !ids.insert(s.id).second)
      throw InvalidInput("weight set '" + set + "': empty or repeated source id '" + s.id + "'");
  }
  for (const auto& [name, r] : ranges) {
    if (!(r > 0.0) || !std::isfinite(r))
      throw InvalidInput("weight set '" + set + "': range of '" + name + "' must be > 0");
  }
  std::set<std::string> names;
  std::map<std::string, int> usage;  // parameter → 0 plain, ±1 signed
  for (const auto& t : targets) {
    const std::string where = "weight set '" + set + "', target '" + t.name + "'";
    if (t.name.empty()) throw InvalidInput("weight set '" + set + "': a target has no name");
    if (!names.insert(core::ascii_lower(t.name)).second)
      throw InvalidInput(where + ": repeated name");
    if (naming == "arkit" && !arkit_raw_name(t.name))
      throw InvalidInput(where + ": not an ARKit blend shape name");
    if (t.terms.empty() && t.note.empty())
      throw InvalidInput(where + ": a target without terms needs a note saying why");
    std::set<std::string> inputs;
    for (const auto& term : t.terms) {
      if (!std::isfinite(term.weight) || std::fabs(term.weight) > 10.0)
        throw InvalidInput(where + ": weight of '" + term.input + "' must be finite, |w| <= 10");
      if (!inputs.insert(term.input).second)
        throw InvalidInput(where + ": input '" + term.input + "' repeated");
      const auto [param, sign] = split_input(term.input);
      if (param.empty()) throw InvalidInput(where + ": empty input name");
      if (sign != 0 && !ranges.count(param))
        throw InvalidInput(where + ": signed input '" + term.input + "' needs ranges/" + param);
      auto [it, fresh] = usage.emplace(param, sign == 0 ? 0 : 1);
      if (!fresh && (it->second == 0) != (sign == 0))
        throw InvalidInput(where + ": '" + param + "' is used both as a level and as a signed angle");
    }
    for (const auto& s : t.sources) {
      if (!ids.count(s)) throw InvalidInput(where + ": unknown source id '" + s + "'");
    }
  }
}

WeightSet parse_weight_set(std::string_view text, const std::string& file) {
  const core::JsonReader reader(text, file, kWeightSetKind, {kWeightSetMajor, kWeightSetMinor});
  return parse_document(reader.root());
}

WeightSet read_weight_set(const std::string& path) {
  return parse_weight_set(core::read_file(path), path);
}

std::string format_weight_set(const WeightSet& set) {
  set.validate();
  Json doc = core::make_envelope(kWeightSetKind, {kWeightSetMajor, kWeightSetMinor});
  doc["set"] = set.set;
  doc["naming"] = set.naming;
  doc["description"] = set.description;
  doc["ranges"] = Json::object();
  for (const auto& [k, v] : set.ranges) doc["ranges"][k] = v;
  doc["sources"] = Json::array();
  for (const auto& s : set.sources) doc["sources"].push_back({{"id", s.id}, {"citation", s.citation}});
  doc["targets"] = Json::array();
  for (const auto& t : set.targets) {
    Json row;
    row["name"] = t.name;
    row["terms"] = Json::object();
    for (const auto& term : t.terms) row["terms"][term.input] = term.weight;
    row["facs"] = t.facs;
    row["sources"] = t.sources;
    if (!t.note.empty()) row["note"] = t.note;
    doc["targets"].push_back(std::move(row));
  }
  return doc.dump(1) + "\n";
}

void write_weight_set(const std::string& path, const WeightSet& set) {
  core::write_file_atomic(path, format_weight_set(set));
}

const WeightSet& builtin_weight_set(std::string_view name) {
  static const WeightSet arkit =
      parse_weight_set(detail::builtin_arkit_json(), "<built-in data/faceweights/arkit.json>");
  static const WeightSet facs =
      parse_weight_set(detail::builtin_facs_json(), "<built-in data/faceweights/facs.json>");
  if (name == "arkit") return arkit;
  if (name == "facs") return facs;
  throw InvalidInput("unknown weight set '" + std::string(name) + "' (known: arkit, facs)");
}

std::vector<std::string> builtin_weight_set_names() { return {"arkit", "facs"}; }

}  // namespace emoface::faceweights
