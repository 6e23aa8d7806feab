#pragma once
// Small databases built in code for the motiongraph tests.
#include <cmath>

#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthetic.hpp"

namespace emoface::motiongraph::test {

/// A database of `landmarks` 2D points moving linearly from `start` by `step` per frame.
inline Sequence line_sequence(const std::string& id, Label label, std::size_t frames, std::size_t landmarks,
                              double step) {
  Sequence s;
  s.id = id;
  s.subject = "S1";
  s.label = label;
  for (std::size_t f = 0; f < frames; ++f) {
    Pose p(static_cast<Eigen::Index>(landmarks), 2);
    for (std::size_t i = 0; i < landmarks; ++i)
      p.row(static_cast<Eigen::Index>(i)) << 10.0 * static_cast<double>(i) + step * static_cast<double>(f),
          5.0 * static_cast<double>(i * i);
    s.frames.push_back(p);
  }
  return s;
}

inline Database small_synthetic(std::size_t per_label = 2, std::uint64_t seed = 7) {
  SyntheticOptions o;
  o.seed = seed;
  o.sequences_per_label = per_label;
  o.subjects = 4;
  o.min_frames = 6;
  o.max_frames = 12;
  return generate_synthetic_database(ParametricLandmarkModel(), o);
}

inline const PreparedDatabase& small_prepared() {
  static const PreparedDatabase data = preprocess(small_synthetic(), default_layout());
  return data;
}

}  // namespace emoface::motiongraph::test
