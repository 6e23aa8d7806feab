#include "emoface/channels/conflicts.hpp"

#include <algorithm>
#include <set>
#include <utility>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {

namespace {
bool is_muscle(const std::string& n) {
  const auto& m = muscle_names();
  return std::find(m.begin(), m.end(), n) != m.end();
}

// The side of a parameter: 'l', 'r' or 0 (unpaired muscle).
char side_of(const std::string& parameter) {
  const std::string muscle = parameter_muscle(parameter);
  if (muscle.empty() || !is_paired_muscle(muscle)) return 0;
  return parameter.back();
}

// Parameters an entry (muscle or parameter name) stands for.
std::vector<std::string> expand_name(const std::string& n) {
  if (is_muscle(n)) return muscle_parameters(n);
  return {n};
}
}  // namespace

void ConflictTable::validate() const {
  std::set<std::pair<std::string, std::string>> seen;
  for (const ConflictPair& p : pairs) {
    for (const std::string* n : {&p.a, &p.b})
      if (!is_muscle(*n) && parameter_muscle(*n).empty())
        throw InvalidInput("conflict table: '" + *n + "' is not a muscle or a face parameter");
    if (p.a == p.b) throw InvalidInput("conflict table: '" + p.a + "' conflicts with itself");
    const auto key = std::minmax(p.a, p.b);
    if (!seen.emplace(key.first, key.second).second)
      throw InvalidInput("conflict table: pair " + p.a + " – " + p.b + " listed twice");
  }
}

std::vector<std::vector<std::size_t>> ConflictTable::expand(
    const std::vector<std::string>& parameters) const {
  std::vector<std::vector<std::size_t>> out(parameters.size());
  const auto index_of = [&](const std::string& n) -> int {
    const auto it = std::find(parameters.begin(), parameters.end(), n);
    return it == parameters.end() ? -1 : static_cast<int>(it - parameters.begin());
  };
  for (const ConflictPair& pair : pairs) {
    for (const std::string& pa : expand_name(pair.a)) {
      for (const std::string& pb : expand_name(pair.b)) {
        const char sa = side_of(pa), sb = side_of(pb);
        if (sa && sb && sa != sb) continue;  // paired muscles conflict on the same side only
        const int ia = index_of(pa), ib = index_of(pb);
        if (ia < 0 || ib < 0) continue;
        auto add = [&](int i, int j) {
          auto& v = out[static_cast<std::size_t>(i)];
          if (std::find(v.begin(), v.end(), static_cast<std::size_t>(j)) == v.end())
            v.push_back(static_cast<std::size_t>(j));
        };
        add(ia, ib);
        add(ib, ia);
      }
    }
  }
  for (auto& v : out) std::sort(v.begin(), v.end());
  return out;
}

// Reconstruction of thesis Table 4.1 (seeds README): the five pairs the text states plus 13 pairs
// from FACS incompatibilities (Appendix A), chosen so every row has the surviving mark count
// (01:4 02:4 03:3 04:3 05:2 06:3 07:5 08:4 09:1 11:3 12:1 16:2 17:1).
ConflictTable default_conflict_table() {
  return ConflictTable{{
      // stated in the thesis text (§4.1, §4.3)
      {"levator_labii_superioris", "orbicularis_oris_pressor",
       "stated (§4.3, Fig. 4.2): AU10 parts the lips, AU24 presses them together"},
      {"orbicularis_oris_funneler", "zygomatic_major",
       "stated (§4.1): AU22 purses the lips, AU12 pulls the corners outward"},
      {"orbicularis_oris_funneler", "zygomatic_minor",
       "stated (§4.1): AU22 purses the lips, AU13/AU11 pull the corners and upper lip outward"},
      {"levator_palpebrae_superioris", "orbicularis_oculi_palpebralis",
       "stated (§4.3): AU5 opens the eyelid, AU43/45 closes it"},
      {"frontalis_medialis", "levator_labii_nasi",
       "stated (§4.3): AU1 raises the inner brows, AU9 wrinkles the nose and pulls them down"},
      // reconstructed from FACS (Appendix A)
      {"zygomatic_major", "triangularis", "AU12 raises the lip corners, AU15 depresses them"},
      {"zygomatic_minor", "triangularis", "AU13 raises the lip corners, AU15 depresses them"},
      {"zygomatic_major", "risorius", "AU12 pulls the corner up and back, AU20 stretches it sideways"},
      {"zygomatic_minor", "risorius", "AU13 pulls the corner up, AU20 stretches it sideways"},
      {"zygomatic_major", "mentalis", "AU12 pulls the corners outward, AU17 pushes the lower lip up into a pout"},
      {"zygomatic_minor", "mentalis", "AU13 pulls the corners outward, AU17 pushes the lower lip up into a pout"},
      {"orbicularis_oris_funneler", "risorius", "AU22 funnels the lips, AU20 stretches them flat"},
      {"orbicularis_oris_funneler", "triangularis", "AU22 rounds the lips, AU15 pulls the corners down"},
      {"orbicularis_oris_funneler", "orbicularis_oris_pressor",
       "AU22 protrudes open lips, AU24 presses closed lips together"},
      {"orbicularis_oris_pressor", "depressor_labii", "AU24 presses the lips together, AU16 pulls the lower lip down"},
      {"orbicularis_oris_pressor", "levator_labii_nasi", "AU24 presses the lips together, AU9 raises the upper lip"},
      {"depressor_labii", "mentalis", "AU16 lowers the lower lip, AU17 pushes it up"},
      {"levator_labii_nasi", "levator_palpebrae_superioris",
       "AU9 narrows the eye aperture (cheek raise, brow lowering), AU5 widens it"},
  }};
}

}  // namespace emoface::channels
