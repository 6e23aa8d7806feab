#include "emoface/faceweights/weight_set.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/faceweights/names.hpp"

namespace emoface::faceweights {
namespace detail {
std::string_view builtin_arkit_json();
std::string_view builtin_facs_json();
}  // namespace detail

namespace {

using Json = nlohmann::ordered_json;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// "<name>+" / "<name>-" → ("<name>", sign); plain name → (name, 0).
std::pair<std::string, int> split_input(const std::string& input) {
  if (!input.empty() && (input.back() == '+' || input.back() == '-'))
    return {input.substr(0, input.size() - 1), input.back() == '+' ? 1 : -1};
  return {input, 0};
}

class Parser {
 public:
  explicit Parser(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    throw FormatError(SourceLocation{file_, pointer, 0, 0}, message);
  }
  std::string string(const Json& obj, const char* key, const std::string& at, bool required) const {
    auto it = obj.find(key);
    if (it == obj.end()) {
      if (required) fail(at, std::string("missing string field \"") + key + "\"");
      return {};
    }
    if (!it->is_string()) fail(at + "/" + key, "expected a string");
    return it->get<std::string>();
  }
  double number(const Json& v, const std::string& at) const {
    if (!v.is_number()) fail(at, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(at, "expected a finite number");
    return x;
  }
  WeightSet parse(const Json& doc) const {
    core::check_envelope(doc, kWeightSetKind, {kWeightSetMajor, kWeightSetMinor}, file_);
    static const std::set<std::string> known = {"format", "version", "generator", "set",
                                                "naming", "description", "ranges", "sources",
                                                "targets"};
    const auto version = core::parse_format_version(doc["version"].get<std::string>());
    for (auto it = doc.begin(); it != doc.end(); ++it) {
      if (!known.count(it.key()) && version.minor <= kWeightSetMinor)
        fail("/" + core::json_pointer_token(it.key()), "unknown field \"" + it.key() + "\"");
    }
    WeightSet set;
    set.set = string(doc, "set", "", true);
    set.naming = string(doc, "naming", "", true);
    set.description = string(doc, "description", "", false);
    if (auto it = doc.find("ranges"); it != doc.end()) {
      if (!it->is_object()) fail("/ranges", "expected an object {parameter: radians}");
      for (auto r = it->begin(); r != it->end(); ++r)
        set.ranges[r.key()] = number(r.value(), "/ranges/" + core::json_pointer_token(r.key()));
    }
    auto sources = doc.find("sources");
    if (sources == doc.end() || !sources->is_array()) fail("/sources", "missing array \"sources\"");
    for (std::size_t i = 0; i < sources->size(); ++i) {
      const auto& s = (*sources)[i];
      const std::string at = "/sources/" + std::to_string(i);
      if (!s.is_object()) fail(at, "expected an object {id, citation}");
      set.sources.push_back({string(s, "id", at, true), string(s, "citation", at, true)});
    }
    auto targets = doc.find("targets");
    if (targets == doc.end() || !targets->is_array()) fail("/targets", "missing array \"targets\"");
    for (std::size_t i = 0; i < targets->size(); ++i) {
      const auto& t = (*targets)[i];
      const std::string at = "/targets/" + std::to_string(i);
      if (!t.is_object()) fail(at, "expected an object {name, terms, facs, sources, note}");
      Target target;
      target.name = string(t, "name", at, true);
      auto terms = t.find("terms");
      if (terms == t.end() || !terms->is_object()) fail(at + "/terms", "expected an object {input: weight}");
      for (auto it = terms->begin(); it != terms->end(); ++it)
        target.terms.push_back(
            {it.key(), number(it.value(), at + "/terms/" + core::json_pointer_token(it.key()))});
      target.facs = string(t, "facs", at, false);
      target.note = string(t, "note", at, false);
      if (auto s = t.find("sources"); s != t.end()) {
        if (!s->is_array()) fail(at + "/sources", "expected an array of source ids");
        for (std::size_t k = 0; k < s->size(); ++k) {
          if (!(*s)[k].is_string()) fail(at + "/sources/" + std::to_string(k), "expected a string");
          target.sources.push_back((*s)[k].get<std::string>());
        }
      }
      set.targets.push_back(std::move(target));
    }
    try {
      set.validate();
    } catch (const InvalidInput& e) {
      fail("/targets", e.what());
    }
    return set;
  }

 private:
  std::string file_;
};

}  // namespace

std::optional<std::size_t> WeightSet::find(std::string_view name) const {
  std::string key = lower(name);
  if (naming == "arkit") {
    if (auto raw = arkit_raw_name(name)) key = lower(*raw);
  }
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (lower(targets[i].name) == key) return i;
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
    if (!names.insert(lower(t.name)).second) throw InvalidInput(where + ": repeated name");
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
  const Json doc = core::parse_json(text, file);
  return Parser(file).parse(doc);
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
