// The built-in viseme set. The thesis (§4.2) takes its dominance functions from DeCarlo et al.
// (2002) without printing them; these values are hand-set (docs/channels.md, "Visemes"):
// consonants that need a closure or a lip-teeth contact get a high magnitude α and a fast fall-off
// θ (they must hit their target), vowels a lower α and slower θ (they are coarticulated most), in
// the spirit of Cohen & Massaro (1993). τ is measured in units of CoarticulationOptions::time_unit
// (10 ms). Spread vowels raise the upper lip (levator labii superioris) rather than stretch it with
// the risorius, which conflicts with the smile (Table 4.1): as in the thesis' Fig. 4.8 a smile goes
// on through "I like it" and only the funneler of "v" (and the lip closure of "m") inhibits it.
#include "emoface/channels/dominance.hpp"

namespace emoface::channels {

namespace {
// a paired muscle at the same level on both sides
void both(std::vector<Target>& t, const char* muscle, double v) {
  t.push_back({std::string(muscle) + "_l", v});
  t.push_back({std::string(muscle) + "_r", v});
}
}  // namespace

VisemeSet default_viseme_set() {
  const Dominance consonant{1.0, 0.40, 0.40, 1.0, 0.0};
  const Dominance closure{1.5, 0.50, 0.50, 1.0, 0.0};
  const Dominance vowel{0.6, 0.25, 0.25, 1.0, 0.0};
  const Dominance rounded{0.9, 0.20, 0.25, 1.0, -0.01};  // lip rounding anticipates (earlier peak)
  VisemeSet s;
  s.silence = "sil";
  auto add = [&](const char* name, std::vector<Target> t, Dominance d) { s.visemes.push_back({name, std::move(t), d, {}}); };
  // silence dominates the edges of utterances (strong, slowest decay), so lips close between words
  add("sil", {}, Dominance{1.0, 0.15, 0.15, 1.0, 0.0});
  add("PBM", {{"orbicularis_oris_pressor", 0.8}}, closure);  // lips pressed together
  {
    std::vector<Target> t{{"orbicularis_oris_funneler", 0.5}, {"masseter", 0.1}};  // thesis §4.6: "v" uses the funneler
    both(t, "mentalis", 0.3);
    add("FV", std::move(t), closure);
  }
  {
    std::vector<Target> t{{"masseter", 0.15}};
    both(t, "levator_labii_superioris", 0.2);
    add("TH", std::move(t), consonant);
  }
  add("TDNL", {{"masseter", 0.2}}, consonant);
  {
    std::vector<Target> t{{"masseter", 0.1}};
    both(t, "levator_labii_superioris", 0.2);
    add("SZ", std::move(t), consonant);
  }
  add("SH", {{"orbicularis_oris_funneler", 0.6}, {"masseter", 0.15}}, consonant);
  add("KG", {{"masseter", 0.25}}, Dominance{0.7, 0.35, 0.35, 1.0, 0.0});
  add("R", {{"orbicularis_oris_funneler", 0.45}, {"masseter", 0.15}}, consonant);
  add("W", {{"orbicularis_oris_funneler", 0.9}, {"masseter", 0.1}}, rounded);
  add("AA", {{"masseter", 0.7}}, vowel);
  {
    std::vector<Target> t{{"masseter", 0.4}};
    both(t, "levator_labii_superioris", 0.15);
    add("EH", std::move(t), vowel);
  }
  {
    std::vector<Target> t{{"masseter", 0.15}};
    both(t, "levator_labii_superioris", 0.3);
    add("IY", std::move(t), vowel);
  }
  add("OH", {{"orbicularis_oris_funneler", 0.6}, {"masseter", 0.45}}, rounded);
  add("UW", {{"orbicularis_oris_funneler", 0.8}, {"masseter", 0.2}}, rounded);
  // espeak-ng English phoneme mnemonics (voice en-us); unknown ones and pauses fall back to "sil"
  const std::pair<const char*, const char*> map[] = {
      {"p", "PBM"},  {"b", "PBM"},  {"m", "PBM"},  {"f", "FV"},   {"v", "FV"},    {"T", "TH"},
      {"D", "TH"},   {"t", "TDNL"}, {"d", "TDNL"}, {"n", "TDNL"}, {"l", "TDNL"},  {"t#", "TDNL"},
      {"n-", "TDNL"}, {"l-", "TDNL"}, {"s", "SZ"}, {"z", "SZ"},   {"S", "SH"},    {"Z", "SH"},
      {"tS", "SH"},  {"dZ", "SH"},  {"k", "KG"},   {"g", "KG"},   {"N", "KG"},    {"h", "KG"},
      {"j", "IY"},   {"r", "R"},    {"r-", "R"},   {"3", "R"},    {"w", "W"},     {"u", "UW"},
      {"U", "UW"},   {"U@", "UW"},  {"aU", "AA"},  {"a", "AA"},   {"A", "AA"},    {"aI", "AA"},
      {"A@", "AA"},  {"aa", "AA"},  {"a#", "AA"},  {"V", "EH"},   {"@", "EH"},    {"@-", "EH"},
      {"@2", "EH"},  {"@5", "EH"},  {"E", "EH"},   {"e", "EH"},   {"eI", "EH"},   {"e@", "EH"},
      {"I", "IY"},   {"i", "IY"},   {"i@", "IY"},  {"I2", "IY"},  {"I#", "IY"},   {"0", "OH"},
      {"O", "OH"},   {"o", "OH"},   {"oU", "OH"},  {"OI", "OH"},  {"O@", "OH"},   {"o@", "OH"},
      {"@U", "OH"},  {"aI@", "AA"}, {"aU@", "AA"}, {"i@3", "IY"}, {"@L", "TDNL"}, {"_", "sil"},
      {"_:", "sil"}, {"_!", "sil"}, {"_|", "sil"}, {"?", "sil"},  {"3:", "R"},    {"A:", "AA"},
      {"O:", "OH"},  {"i:", "IY"},  {"u:", "UW"}};
  for (const auto& [ph, v] : map) s.phoneme_to_viseme[ph] = v;
  return s;
}

}  // namespace emoface::channels
