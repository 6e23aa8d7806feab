#pragma once
// Reduced landmark set and facial regions (paper §4, fig. 3): which source landmarks enter graph
// building, grouped into regions (eyes, eyebrows, nose, mouth, cheeks+jaw), each with the markers its
// regional Procrustes alignment uses. Editable data: data/motiongraph/layout_ibug68.json.
#include <cstddef>
#include <string>
#include <vector>

namespace emoface::motiongraph {

struct Region {
  std::string name;            ///< e.g. "mouth"
  std::vector<int> landmarks;  ///< source landmark indices in this region's graph (reduced set)
  /// Source landmark indices used to align this region between samples (regional Procrustes on the
  /// neutral poses). Empty = use `landmarks`.
  std::vector<int> alignment;
};

struct LandmarkLayout {
  std::size_t source_landmark_count = 68;  ///< landmarks per pose of the databases it applies to
  std::vector<Region> regions;             ///< disjoint landmark sets
  /// All region landmarks, region by region (the order of synthesized poses).
  std::vector<int> reduced_landmarks() const;
  /// Throws InvalidInput: no regions, empty/duplicate names, indices out of range, a landmark in two
  /// regions, fewer than 2 alignment markers.
  void validate() const;
};

/// The built-in iBUG-68 layout (same content as data/motiongraph/layout_ibug68.json).
LandmarkLayout default_layout();

/// The trivial layout: one region "all" holding every landmark (for databases that are not iBUG-68).
LandmarkLayout single_region_layout(std::size_t landmark_count);

}  // namespace emoface::motiongraph
