// Captures → labelled database (issue 19, item 1): cleaning, head-pose stabilisation, trimming into
// neutral-to-peak segments, labels; and the example generator.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <optional>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/motiongraph/capture.hpp"
#include "emoface/motiongraph/preprocess.hpp"

namespace emoface::motiongraph {

namespace {

// Per-landmark median of frames [0, count).
Pose median_pose(const std::vector<Pose>& frames, std::size_t count) {
  count = std::min(count, frames.size());
  Pose out = frames[0];
  std::vector<double> v(count);
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    for (Eigen::Index c = 0; c < out.cols(); ++c) {
      for (std::size_t i = 0; i < count; ++i) v[i] = frames[i](r, c);
      std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(count / 2), v.end());
      double m = v[count / 2];
      if (count % 2 == 0) {
        m = 0.5 *
            (m + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(count / 2)));
      }
      out(r, c) = m;
    }
  return out;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto i = static_cast<std::size_t>(std::floor(pos));
  const double w = pos - static_cast<double>(i);
  return i + 1 < v.size() ? (1.0 - w) * v[i] + w * v[i + 1] : v[i];
}

Eigen::MatrixXd rows(const Pose& p, const std::vector<int>& ids) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(ids.size()), p.cols());
  for (std::size_t i = 0; i < ids.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = p.row(ids[i]);
  return out;
}

TrackedFrames slice(const TrackedFrames& t, std::size_t a, std::size_t b, const std::string& id) {
  TrackedFrames s;
  s.id = id;
  s.dimensions = t.dimensions;
  s.au_names = t.au_names;
  for (std::size_t i = a; i < b; ++i) {
    s.times.push_back(t.times[i]);
    s.confidence.push_back(t.confidence[i]);
    s.success.push_back(t.success[i]);
    s.frames.push_back(t.frames[i]);
    if (!t.labels.empty()) s.labels.push_back(t.labels[i]);
    if (!t.au.empty()) s.au.push_back(t.au[i]);
  }
  return s;
}

}  // namespace

void FrameFilterOptions::validate() const {
  if (!(min_confidence >= 0.0 && min_confidence <= 1.0))
    throw InvalidInput("frame filter: min_confidence must be in [0, 1]");
  if (max_gap > 1000) throw InvalidInput("frame filter: max_gap must be in [0, 1000]");
  if (min_frames < 2) throw InvalidInput("frame filter: min_frames must be >= 2");
}

std::vector<TrackedFrames> clean_frames(const TrackedFrames& take,
                                        const FrameFilterOptions& options) {
  options.validate();
  take.validate();
  const std::size_t n = take.size();
  std::vector<char> good(n);
  for (std::size_t i = 0; i < n; ++i)
    good[i] = take.confidence[i] >= options.min_confidence &&
              (!options.require_success || take.success[i]);
  // Parts: maximal ranges of good frames joined across gaps of at most max_gap bad frames.
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  std::size_t i = 0;
  while (i < n) {
    while (i < n && !good[i]) ++i;
    if (i == n) break;
    std::size_t last_good = i, j = i + 1;
    while (j < n) {
      if (good[j]) {
        last_good = j++;
        continue;
      }
      std::size_t k = j;
      while (k < n && !good[k]) ++k;
      if (k == n || k - j > options.max_gap) break;
      j = k;
    }
    parts.emplace_back(i, last_good + 1);
    i = last_good + 1;
  }
  std::vector<TrackedFrames> out;
  for (const auto& [a, b] : parts) {
    if (b - a < options.min_frames) continue;
    const std::string id =
        parts.size() == 1 ? take.id : take.id + ".p" + std::to_string(out.size());
    TrackedFrames s = slice(take, a, b, id);
    // Fill the short gaps: linear interpolation between the neighbouring good frames.
    for (std::size_t f = 0; f < s.size(); ++f) {
      if (good[a + f]) continue;
      std::size_t prev = f - 1, next = f + 1;  // f > 0 and next exists: parts start and end good
      while (!good[a + next]) ++next;
      const double w = (s.times[f] - s.times[prev]) / (s.times[next] - s.times[prev]);
      s.frames[f] = (1.0 - w) * s.frames[prev] + w * s.frames[next];
      if (!s.au.empty())
        for (std::size_t k = 0; k < s.au[f].size(); ++k)
          s.au[f][k] = (1.0 - w) * s.au[prev][k] + w * s.au[next][k];
      if (!s.labels.empty()) s.labels[f] = w < 0.5 ? s.labels[prev] : s.labels[next];
      s.success[f] = 1;
      s.confidence[f] = std::min(s.confidence[prev], s.confidence[next]);
    }
    out.push_back(std::move(s));
  }
  return out;
}

void StabiliseOptions::validate() const {
  if (anchors.size() < 3) throw InvalidInput("stabilise: need at least 3 anchor landmarks");
  for (int a : anchors)
    if (a < 0 || a >= 68)
      throw InvalidInput("stabilise: anchor landmarks must be iBUG indices 0–67");
  if (reference_frames < 1) throw InvalidInput("stabilise: reference_frames must be >= 1");
}

std::vector<double> stabilise_head(TrackedFrames& take, const StabiliseOptions& options) {
  options.validate();
  take.validate();
  std::vector<double> residual;
  if (take.frames.empty()) return residual;
  const Eigen::MatrixXd ref =
      rows(median_pose(take.frames, options.reference_frames), options.anchors);
  for (Pose& p : take.frames) {
    const Eigen::MatrixXd transform = procrustes(rows(p, options.anchors), ref);
    p = apply_transform(transform, p);
    const Eigen::MatrixXd d = rows(p, options.anchors) - ref;
    residual.push_back(std::sqrt(d.rowwise().squaredNorm().mean()));
  }
  return residual;
}

void TrimOptions::validate() const {
  if (reference_frames < 1) throw InvalidInput("trim: reference_frames must be >= 1");
  if (!(low > 0.0 && low < high && high <= 1.0))
    throw InvalidInput("trim: need 0 < low < high <= 1");
  if (!(weight_low > 0.0 && weight_low < weight_high && weight_high <= 1.0))
    throw InvalidInput("trim: need 0 < weight_low < weight_high <= 1");
  if (!(baseline_window > 0.0 && baseline_window <= 600.0))
    throw InvalidInput("trim: baseline_window must be in (0, 600] s");
  if (min_frames < 2) throw InvalidInput("trim: min_frames must be >= 2");
  if (!(top_fraction > 0.0 && top_fraction <= 1.0))
    throw InvalidInput("trim: top_fraction must be in (0, 1]");
}

std::vector<TakeSegment> find_segments(const TrackedFrames& take, const TrimOptions& options,
                                       std::vector<double>* magnitude) {
  options.validate();
  take.validate();
  const std::size_t n = take.size();
  std::vector<TakeSegment> out;
  if (n < 2) return out;
  const Pose ref = median_pose(take.frames, options.reference_frames);
  std::vector<double> raw(n), m(n);
  // RMS over the most displaced `top_fraction` of the landmarks: a local expression (one mouth
  // corner for contempt) is not diluted by the still rest of the face.
  const auto count = static_cast<std::size_t>(ref.rows());  // 68 landmarks, or weight channels
  const auto top = static_cast<std::size_t>(
      std::max(1.0, std::round(options.top_fraction * static_cast<double>(count))));
  std::vector<double> d2(count);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::VectorXd sq = (take.frames[i] - ref).rowwise().squaredNorm();
    for (std::size_t l = 0; l < count; ++l) d2[l] = sq[static_cast<Eigen::Index>(l)];
    std::nth_element(d2.begin(), d2.begin() + static_cast<std::ptrdiff_t>(top - 1), d2.end(),
                     std::greater<double>());
    double sum = 0.0;
    for (std::size_t l = 0; l < top; ++l) sum += d2[l];
    raw[i] = std::sqrt(sum / static_cast<double>(top));
  }
  for (std::size_t i = 0; i < n; ++i) {  // centred 3-frame mean (2 at the ends)
    const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(n - 1, i + 1);
    double s = 0.0;
    for (std::size_t k = a; k <= b; ++k) s += raw[k];
    m[i] = s / static_cast<double>(b - a + 1);
  }
  // Landmarks: thresholds relative to the outer-eye-corner distance; weights: absolute.
  const bool weights = take.dimensions == 1;
  const double iod = weights ? 1.0 : (ref.row(36) - ref.row(45)).norm();  // outer eye corners
  if (!(iod > 0.0))
    throw InvalidInput("trim: take \"" + take.id + "\" has coincident outer eye corners");
  // Slow drift of the rest pose (tracker drift, changed head pose the similarity cannot remove) is
  // removed by a moving baseline: the minimum of m within ±baseline_window seconds.
  std::vector<double> dt;
  for (std::size_t k = 1; k < n; ++k) dt.push_back(take.times[k] - take.times[k - 1]);
  const auto w = static_cast<std::size_t>(std::lround(options.baseline_window / quantile(dt, 0.5)));
  std::vector<double> above(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k > w ? k - w : 0, b = std::min(n - 1, k + w);
    above[k] = m[k] - *std::min_element(m.begin() + static_cast<std::ptrdiff_t>(a),
                                        m.begin() + static_cast<std::ptrdiff_t>(b + 1));
  }
  if (magnitude) *magnitude = above;
  const double low = weights ? options.weight_low : options.low * iod;
  const double high = weights ? options.weight_high : options.high * iod;
  m = above;
  std::size_t i = 0;
  while (i < n) {
    if (m[i] <= low) {
      ++i;
      continue;
    }
    std::size_t j = i;
    std::size_t peak = i;
    while (j < n && m[j] > low) {
      if (m[j] > m[peak]) peak = j;
      ++j;
    }
    const std::size_t first = i == 0 ? 0 : i - 1;  // the last frame at rest
    if (m[peak] > high && peak - first + 1 >= options.min_frames) out.push_back({first, peak});
    i = j;
  }
  return out;
}

LabelTable parse_label_table(std::string_view text, const std::string& file) {
  // core::CsvTable: stamp and comment lines, blank lines and repeated headers skipped; rows of the
  // header's width.
  const core::CsvTable table = core::CsvTable::parse(text, file);
  if (table.header() != std::vector<std::string>{"take", "segment", "label"})
    throw FormatError({file, "", table.header_line(), 1},
                      "expected the header \"take,segment,label\"");
  LabelTable t;
  for (std::size_t r = 0; r < table.size(); ++r) {
    const std::vector<std::string>& fields = table.rows()[r].fields;
    if (fields[0].empty()) table.fail(r, 0, "empty take id");
    const std::string& seg = fields[1];
    if (seg != "*" &&
        (seg.empty() || seg.size() > 9 ||
         !std::all_of(seg.begin(), seg.end(), [](char c) { return c >= '0' && c <= '9'; })))
      table.fail(r, 1, "segment must be a 0-based index or *");
    Label label;
    try {
      label = label_from_string(fields[2]);
    } catch (const InvalidInput& e) {
      table.fail(r, 2, e.what());
    }
    const std::string key = seg == "*" ? "*" : std::to_string(std::stoul(seg));
    if (!t.entries.emplace(std::make_pair(fields[0], key), label).second)
      table.fail(r, 0, "take \"" + fields[0] + "\" segment " + seg + " is labelled twice");
  }
  return t;
}

LabelTable read_label_table(const std::string& path) {
  return parse_label_table(core::read_file(path), path);
}

std::string label_table_csv(const LabelTable& table) {
  std::string out = core::csv_stamp() + "take,segment,label\n";
  for (const auto& [key, label] : table.entries) {
    core::append_csv_field(out, key.first);
    out += ',' + key.second + ',' + to_string(label) + '\n';
  }
  return out;
}

LabelTable segment_label_table(const std::vector<TrackedFrames>& takes) {
  LabelTable side;
  for (const TrackedFrames& t : takes) {
    if (t.labels.size() != t.size())
      throw InvalidInput("segment_label_table: take \"" + t.id + "\" has no label column");
    std::size_t k = 0;  // segment index over the take's parts, as capture_database counts them
    for (TrackedFrames& part : clean_frames(t)) {
      stabilise_head(part);
      for (const TakeSegment& seg : find_segments(part)) {
        const Label l = label_from_string(part.labels[seg.peak]);
        if (l != Label::Neutral) side.entries[{t.id, std::to_string(k)}] = l;
        ++k;
      }
    }
  }
  return side;
}

void CaptureOptions::validate() const {
  filter.validate();
  stabilisation.validate();
  trimming.validate();
}

Database capture_database(const std::vector<TrackedFrames>& takes, const CaptureOptions& options,
                          const LabelTable* labels, ReadReport* report) {
  options.validate();
  if (takes.empty()) throw InvalidInput("capture: no takes");
  Database db;
  db.dimensions = takes[0].dimensions;
  db.landmark_count = takes[0].frames.empty() ? 68 : static_cast<std::size_t>(takes[0].frames[0].rows());
  std::vector<double> rates;
  auto problem = [&](const std::string& msg) {
    if (options.on_error == OnError::Stop) throw InvalidInput(msg);
    if (report) report->skipped.push_back(msg);
  };
  for (const TrackedFrames& take : takes) {
    if (take.dimensions != db.dimensions)
      throw InvalidInput("capture: takes mix 2D, 3D landmarks or weights");
    if (!take.frames.empty() && static_cast<std::size_t>(take.frames[0].rows()) != db.landmark_count)
      throw InvalidInput("capture: take \"" + take.id + "\" has " +
                         std::to_string(take.frames[0].rows()) + " channels, the first take " +
                         std::to_string(db.landmark_count));
    std::vector<TrackedFrames> parts = clean_frames(take, options.filter);
    if (parts.empty()) {
      problem("capture: take \"" + take.id + "\" has no usable part (confidence, success, length)");
      continue;
    }
    for (TrackedFrames& part : parts) {
      std::vector<double> dt;
      for (std::size_t i = 1; i < part.size(); ++i) dt.push_back(part.times[i] - part.times[i - 1]);
      rates.push_back(1.0 / quantile(dt, 0.5));
      // Weights carry no head pose: nothing to stabilise.
      if (options.stabilise && part.dimensions != 1) stabilise_head(part, options.stabilisation);
      std::vector<TakeSegment> segments;
      if (options.trim) {
        segments = find_segments(part, options.trimming);
      } else {
        segments.push_back({0, part.size() - 1});
      }
      for (std::size_t k = 0; k < segments.size(); ++k) {
        const TakeSegment& s = segments[k];
        std::optional<Label> label;
        if (labels) {
          auto it = labels->entries.find({take.id, std::to_string(k)});
          if (it == labels->entries.end()) it = labels->entries.find({take.id, "*"});
          if (it != labels->entries.end()) label = it->second;
        }
        const std::string id = part.id + "/" + std::to_string(k);
        if (!label && !part.labels.empty()) {
          try {
            label = label_from_string(part.labels[s.peak]);
          } catch (const InvalidInput&) {
            problem("capture: segment \"" + id + "\": peak label \"" + part.labels[s.peak] +
                    "\" is not a label");
            continue;
          }
        }
        if (!label || *label == Label::Neutral) {
          problem("capture: segment \"" + id + "\" (frames " + std::to_string(s.first) + "–" +
                  std::to_string(s.peak) + ") has " + (label ? "the label neutral" : "no label") +
                  " (side file or label column)");
          continue;
        }
        Sequence seq;
        seq.id = id;
        seq.subject = take.id;
        seq.label = *label;
        seq.frames.assign(part.frames.begin() + static_cast<std::ptrdiff_t>(s.first),
                          part.frames.begin() + static_cast<std::ptrdiff_t>(s.peak + 1));
        db.sequences.push_back(std::move(seq));
      }
    }
  }
  if (rates.empty()) throw InvalidInput("capture: no usable take");
  const double rate = quantile(rates, 0.5);
  for (double r : rates)
    if (std::abs(r - rate) > 0.05 * rate)
      throw InvalidInput("capture: takes have different frame rates (" + std::to_string(r) +
                         " vs " + std::to_string(rate) + " fps); resample them first");
  db.frame_rate = rate;
  if (db.sequences.empty())
    throw InvalidInput("capture: no labelled neutral-to-peak segment found");
  return db;
}

void CaptureExampleOptions::validate() const {
  if (rest_frames < 1) throw InvalidInput("capture example: rest_frames must be >= 1");
  if (!(head_roll >= 0.0 && head_roll <= 0.5))
    throw InvalidInput("capture example: head_roll must be in [0, 0.5]");
  if (!(head_shift >= 0.0 && head_shift <= 100.0))
    throw InvalidInput("capture example: head_shift must be in [0, 100]");
  if (!(head_scale >= 0.0 && head_scale <= 0.3))
    throw InvalidInput("capture example: head_scale must be in [0, 0.3]");
}

std::vector<TrackedFrames> generate_capture_takes(const LandmarkModel& model,
                                                  const CaptureExampleOptions& options) {
  options.validate();
  const std::size_t count = synthetic_sequence_count(options.database);
  std::vector<Sequence> sequences;
  for (std::size_t i = 0; i < count; ++i)
    sequences.push_back(synthetic_sequence(model, options.database, i));
  std::vector<std::string> subjects;
  for (const auto& s : sequences)
    if (std::find(subjects.begin(), subjects.end(), s.subject) == subjects.end())
      subjects.push_back(s.subject);
  const double fps = options.database.frame_rate;
  std::vector<TrackedFrames> takes;
  for (std::size_t k = 0; k < subjects.size(); ++k) {
    core::Rng rng(options.database.seed, 0x7a6b0000u + k);
    TrackedFrames t;
    t.id = "take_" + subjects[k];
    t.dimensions = 2;
    std::vector<Pose> poses;
    std::vector<std::string> labels;
    std::vector<char> rest;
    auto noisy = [&](const Pose& p) {
      Pose q = p;
      for (Eigen::Index i = 0; i < q.size(); ++i)
        q.data()[i] += rng.normal(0.0, options.database.noise_std);
      return q;
    };
    auto at_rest = [&](const Pose& neutral) {
      for (std::size_t i = 0; i < options.rest_frames; ++i) {
        poses.push_back(noisy(neutral));
        labels.push_back("neutral");
        rest.push_back(1);
      }
    };
    const Pose* neutral = nullptr;
    for (const Sequence& s : sequences) {
      if (s.subject != subjects[k]) continue;
      if (!neutral) at_rest(s.frames.front());
      neutral = &s.frames.front();
      for (const Pose& p : s.frames)
        poses.push_back(p), labels.push_back(to_string(s.label)), rest.push_back(0);
      for (std::size_t i = 0; i < options.hold_frames; ++i)
        poses.push_back(noisy(s.frames.back())), labels.push_back(to_string(s.label)),
            rest.push_back(0);
      for (std::size_t i = s.frames.size() - 1; i-- > 1;)
        poses.push_back(noisy(s.frames[i])), labels.push_back(to_string(s.label)),
            rest.push_back(0);
      at_rest(s.frames.front());
    }
    // Slow rigid head motion about the face centre (periods of a few seconds, random phases).
    const double p1 = rng.uniform() * 6.283, p2 = rng.uniform() * 6.283, p3 = rng.uniform() * 6.283;
    std::size_t rest_count = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const double time = static_cast<double>(i) / fps;
      const double roll = options.head_roll * std::sin(2.0 * 3.14159265358979 * time / 5.3 + p1);
      const double scale =
          1.0 + options.head_scale * std::sin(2.0 * 3.14159265358979 * time / 7.1 + p2);
      const Eigen::RowVector2d shift(
          options.head_shift * std::sin(2.0 * 3.14159265358979 * time / 4.7 + p3),
          0.5 * options.head_shift * std::cos(2.0 * 3.14159265358979 * time / 6.1 + p1));
      const Eigen::RowVector2d c = poses[i].colwise().mean();
      Eigen::Matrix2d r;
      r << std::cos(roll), std::sin(roll), -std::sin(roll), std::cos(roll);
      Pose moved = ((poses[i].rowwise() - c) * r * scale).rowwise() + (c + shift);
      bool drop = false;
      if (rest[i] && options.dropout_every > 0) drop = ++rest_count % options.dropout_every == 0;
      t.times.push_back(time);
      t.confidence.push_back(drop ? 0.1 : std::min(1.0, 0.93 + 0.05 * rng.uniform()));
      t.success.push_back(drop ? 0 : 1);
      t.frames.push_back(drop ? Pose(Pose::Zero(68, 2)) : moved);
      t.labels.push_back(labels[i]);
    }
    takes.push_back(std::move(t));
  }
  return takes;
}

}  // namespace emoface::motiongraph
