#include "emoface/motiongraph/layout.hpp"

#include <set>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

std::vector<int> LandmarkLayout::reduced_landmarks() const {
  std::vector<int> out;
  for (const Region& r : regions) out.insert(out.end(), r.landmarks.begin(), r.landmarks.end());
  return out;
}

void LandmarkLayout::validate() const {
  if (source_landmark_count == 0) throw InvalidInput("layout: source_landmark_count must be > 0");
  if (regions.empty()) throw InvalidInput("layout: no regions");
  std::set<std::string> names;
  std::set<int> used;
  auto check_index = [&](const Region& r, int i) {
    if (i < 0 || static_cast<std::size_t>(i) >= source_landmark_count)
      throw InvalidInput("layout: region \"" + r.name + "\" landmark " + std::to_string(i) +
                         " outside [0, " + std::to_string(source_landmark_count) + ")");
  };
  for (const Region& r : regions) {
    if (r.name.empty()) throw InvalidInput("layout: a region has an empty name");
    if (!names.insert(r.name).second) throw InvalidInput("layout: duplicate region \"" + r.name + "\"");
    if (r.landmarks.empty()) throw InvalidInput("layout: region \"" + r.name + "\" has no landmarks");
    for (int i : r.landmarks) {
      check_index(r, i);
      if (!used.insert(i).second)
        throw InvalidInput("layout: landmark " + std::to_string(i) + " appears twice (region \"" +
                           r.name + "\")");
    }
    for (int i : r.alignment) check_index(r, i);
    const std::size_t markers = r.alignment.empty() ? r.landmarks.size() : r.alignment.size();
    if (markers < 2)
      throw InvalidInput("layout: region \"" + r.name + "\" needs at least 2 alignment markers");
  }
}

// Reduced set and regions of paper §4 / fig. 3 on the iBUG-68 numbering (0–16 jaw, 17–26 brows,
// 27–35 nose, 36–47 eyes, 48–67 mouth). The figure is lost in the text; this choice keeps the eye
// corners and lid midpoints, brow ends and middles, nose bridge/tip/wings, outer mouth corners and
// midlines plus inner lip midpoints, and every other jaw point. Alignment markers are the region's
// most rigid neighbours (eye corners, nose bridge, jaw ends).
LandmarkLayout default_layout() {
  LandmarkLayout l;
  l.source_landmark_count = 68;
  l.regions = {
      {"eyes", {36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47}, {36, 39, 42, 45, 27}},
      {"eyebrows", {17, 19, 21, 22, 24, 26}, {36, 39, 42, 45, 27}},
      {"nose", {27, 30, 31, 33, 35}, {27, 30, 31, 35, 39, 42}},
      {"mouth", {48, 50, 51, 52, 54, 56, 57, 58, 62, 66}, {31, 33, 35, 48, 54}},
      {"cheeks_jaw", {2, 4, 6, 8, 10, 12, 14}, {0, 16, 27, 30}},
  };
  return l;
}

LandmarkLayout single_region_layout(std::size_t landmark_count) {
  LandmarkLayout l;
  l.source_landmark_count = landmark_count;
  Region r;
  r.name = "all";
  for (std::size_t i = 0; i < landmark_count; ++i) r.landmarks.push_back(static_cast<int>(i));
  l.regions.push_back(r);
  return l;
}

}  // namespace emoface::motiongraph
