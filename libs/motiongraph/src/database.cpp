#include "emoface/motiongraph/database.hpp"

#include <array>
#include <cmath>
#include <set>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

namespace {
constexpr std::array<const char*, 8> kLabelNames = {"neutral", "happiness", "sadness", "disgust",
                                                    "surprise", "anger", "fear", "contempt"};
}

const std::vector<Label>& all_labels() {
  static const std::vector<Label> labels = {Label::Neutral, Label::Happiness, Label::Sadness,
                                            Label::Disgust, Label::Surprise,  Label::Anger,
                                            Label::Fear,    Label::Contempt};
  return labels;
}

std::string to_string(Label label) { return kLabelNames.at(static_cast<std::size_t>(label)); }

Label label_from_string(std::string_view name) {
  for (std::size_t i = 0; i < kLabelNames.size(); ++i)
    if (name == kLabelNames[i]) return static_cast<Label>(i);
  std::string known;
  for (const char* n : kLabelNames) known += std::string(known.empty() ? "" : ", ") + n;
  throw InvalidInput("unknown expression label \"" + std::string(name) + "\" (known: " + known + ")");
}

void validate(const Database& db, std::size_t min_frames) {
  if (db.dimensions < 1 || db.dimensions > 3)
    throw InvalidInput("database dimensions must be 1 (weights), 2 or 3, got " +
                       std::to_string(db.dimensions));
  if (db.landmark_count == 0) throw InvalidInput("database landmark_count must be > 0");
  if (!(db.frame_rate > 0.0) || !std::isfinite(db.frame_rate))
    throw InvalidInput("database frame_rate must be a positive finite number");
  if (!db.landmark_ids.empty() && db.landmark_ids.size() != db.landmark_count)
    throw InvalidInput("database landmark_ids has " + std::to_string(db.landmark_ids.size()) +
                       " entries, expected landmark_count = " + std::to_string(db.landmark_count));
  std::set<std::string> ids;
  for (std::size_t s = 0; s < db.sequences.size(); ++s) {
    const Sequence& seq = db.sequences[s];
    const std::string name = "sequence " + std::to_string(s) + " (\"" + seq.id + "\")";
    if (seq.id.empty()) throw InvalidInput("sequence " + std::to_string(s) + " has an empty id");
    if (!ids.insert(seq.id).second) throw InvalidInput(name + ": duplicate sequence id");
    if (seq.frames.size() < min_frames)
      throw InvalidInput(name + " has " + std::to_string(seq.frames.size()) +
                         " frame(s); at least " + std::to_string(min_frames) + " needed");
    for (std::size_t f = 0; f < seq.frames.size(); ++f) {
      const Pose& p = seq.frames[f];
      if (static_cast<std::size_t>(p.rows()) != db.landmark_count || p.cols() != db.dimensions)
        throw InvalidInput(name + ", frame " + std::to_string(f) + ": pose is " +
                           std::to_string(p.rows()) + "x" + std::to_string(p.cols()) + ", expected " +
                           std::to_string(db.landmark_count) + "x" + std::to_string(db.dimensions));
      if (!p.allFinite())
        throw InvalidInput(name + ", frame " + std::to_string(f) + ": NaN or infinite coordinate");
    }
  }
}

}  // namespace emoface::motiongraph
