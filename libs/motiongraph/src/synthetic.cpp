#include "emoface/motiongraph/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::motiongraph {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kPixelsPerUnit = 300.0;          // face width 0.94 units ≈ 282 px
const Eigen::Vector2d kImageCentre(320.0, 250.0);  // 640×490 image (CK+)

// Neutral iBUG-68 template, face units, y down (see docs/motiongraph.md).
Eigen::MatrixXd make_template() {
  Eigen::MatrixXd p(68, 2);
  for (int i = 0; i <= 16; ++i) {  // jaw: right ear → chin → left ear (image left → right)
    const double a = kPi * i / 16.0;
    p.row(i) << -0.47 * std::cos(a), -0.05 + 0.60 * std::sin(a);
  }
  for (int i = 0; i < 5; ++i) {  // brows, arched
    const double s = i / 4.0;
    p.row(17 + i) << -0.38 + 0.30 * s, -0.30 - 0.05 * std::sin(kPi * (0.3 + 0.6 * s));
    p.row(26 - i) << 0.38 - 0.30 * s, -0.30 - 0.05 * std::sin(kPi * (0.3 + 0.6 * s));
  }
  for (int i = 0; i < 4; ++i) p.row(27 + i) << 0.0, -0.20 + 0.085 * i;  // nose bridge
  for (int i = 0; i < 5; ++i) p.row(31 + i) << -0.09 + 0.045 * i, 0.11 + 0.025 * std::sin(kPi * i / 4.0);
  auto eye = [&](int first, double cx, bool right_eye) {  // corners, two upper, two lower
    const double w = 0.085, h = 0.032, cy = -0.17;
    const double s = right_eye ? 1.0 : 1.0;
    p.row(first + 0) << cx - s * w, cy;
    p.row(first + 1) << cx - s * w / 3, cy - h;
    p.row(first + 2) << cx + s * w / 3, cy - h;
    p.row(first + 3) << cx + s * w, cy;
    p.row(first + 4) << cx + s * w / 3, cy + h;
    p.row(first + 5) << cx - s * w / 3, cy + h;
  };
  eye(36, -0.21, true);
  eye(42, 0.21, false);
  for (int k = 0; k < 12; ++k) {  // outer lips: 48 left corner, 51 top, 54 right corner, 57 bottom
    const double a = kPi - k * kPi / 6.0;
    const double s = std::sin(a);
    p.row(48 + k) << 0.19 * std::cos(a), 0.30 - (s > 0 ? 0.055 : 0.065) * s;
  }
  for (int k = 0; k < 8; ++k) {  // inner lips: 60 left corner, 62 top, 64 right corner, 66 bottom
    const double a = kPi - k * kPi / 4.0;
    p.row(60 + k) << 0.13 * std::cos(a), 0.30 - 0.006 * std::sin(a);
  }
  return p;
}

// FACS action-unit displacement fields at full intensity (face units, y down, image left = the
// subject's right). Magnitudes follow typical CK+ peak displacements (a few % of face width).
using Field = Eigen::MatrixXd;
void move(Field& f, std::initializer_list<int> ids, double dx, double dy) {
  for (int i : ids) f.row(i) += Eigen::RowVector2d(dx, dy);
}
Field au(int code, const Eigen::MatrixXd& t) {
  Field f = Field::Zero(68, 2);
  switch (code) {
    case 1:  // inner brow raiser
      move(f, {20, 21, 22, 23}, 0.0, -0.045);
      move(f, {19, 24}, 0.0, -0.025);
      break;
    case 2:  // outer brow raiser
      move(f, {17, 18, 25, 26}, 0.0, -0.045);
      move(f, {19, 24}, 0.0, -0.025);
      break;
    case 4:  // brow lowerer: down and together
      move(f, {17, 18, 19, 24, 25, 26}, 0.0, 0.025);
      move(f, {20, 21}, 0.02, 0.035);
      move(f, {22, 23}, -0.02, 0.035);
      break;
    case 5:  // upper lid raiser
      move(f, {37, 38, 43, 44}, 0.0, -0.018);
      break;
    case 6:  // cheek raiser: lower lids and cheeks up
      move(f, {40, 41, 46, 47}, 0.0, -0.012);
      move(f, {1, 2, 3, 13, 14, 15}, 0.0, -0.012);
      break;
    case 7:  // lid tightener
      move(f, {40, 41, 46, 47}, 0.0, -0.014);
      move(f, {37, 38, 43, 44}, 0.0, 0.006);
      break;
    case 9:  // nose wrinkler
      move(f, {31, 32, 33, 34, 35}, 0.0, -0.02);
      move(f, {29, 30}, 0.0, -0.012);
      move(f, {20, 21, 22, 23}, 0.0, 0.012);
      break;
    case 10:  // upper lip raiser
      move(f, {49, 50, 51, 52, 53, 61, 62, 63}, 0.0, -0.03);
      break;
    case 12:  // lip corner puller
      move(f, {48, 60}, -0.045, -0.04);
      move(f, {54, 64}, 0.045, -0.04);
      move(f, {49, 59}, -0.02, -0.02);
      move(f, {53, 55}, 0.02, -0.02);
      break;
    case 14:  // dimpler, subject's left side only (contempt)
      move(f, {54, 64}, 0.03, -0.02);
      move(f, {53, 55}, 0.012, -0.008);
      break;
    case 15:  // lip corner depressor
      move(f, {48, 54, 60, 64}, 0.0, 0.035);
      move(f, {49, 53, 59, 55}, 0.0, 0.015);
      break;
    case 17:  // chin raiser
      move(f, {56, 57, 58, 65, 66, 67}, 0.0, -0.02);
      move(f, {7, 8, 9}, 0.0, -0.015);
      break;
    case 20:  // lip stretcher
      move(f, {48, 60}, -0.05, 0.005);
      move(f, {54, 64}, 0.05, 0.005);
      break;
    case 23:  // lip tightener: lips towards the mouth centre
      for (int i = 48; i < 68; ++i) f.row(i) += 0.15 * (Eigen::RowVector2d(0.0, 0.30) - t.row(i));
      break;
    case 26:  // jaw drop
      move(f, {55, 56, 57, 58, 59, 65, 66, 67}, 0.0, 0.10);
      move(f, {8}, 0.0, 0.10);
      move(f, {7, 9}, 0.0, 0.085);
      move(f, {6, 10}, 0.0, 0.055);
      move(f, {5, 11}, 0.0, 0.03);
      move(f, {4, 12}, 0.0, 0.01);
      move(f, {48, 54, 60, 64}, 0.0, 0.04);
      break;
    default:
      break;
  }
  return f;
}
}  // namespace

ParametricLandmarkModel::ParametricLandmarkModel() : neutral_(make_template()) {
  fields_.assign(all_labels().size(), Field::Zero(68, 2));
  auto set = [&](Label l, std::initializer_list<std::pair<int, double>> units) {
    Field& f = fields_[static_cast<std::size_t>(l)];
    for (const auto& [code, w] : units) f += w * au(code, neutral_);
  };
  // EMFACS prototypes (Ekman & Friesen; Lucey et al. 2010, CK+ emotion criteria).
  set(Label::Happiness, {{6, 1.0}, {12, 1.0}});
  set(Label::Sadness, {{1, 1.0}, {4, 0.5}, {15, 1.0}, {17, 0.6}});
  set(Label::Surprise, {{1, 1.0}, {2, 1.0}, {5, 1.0}, {26, 1.0}});
  set(Label::Fear, {{1, 1.0}, {2, 0.8}, {4, 0.6}, {5, 1.0}, {20, 1.0}, {26, 0.5}});
  set(Label::Anger, {{4, 1.0}, {5, 0.5}, {7, 1.0}, {23, 1.0}});
  set(Label::Disgust, {{9, 1.0}, {10, 1.0}, {15, 0.5}, {17, 0.5}});
  set(Label::Contempt, {{14, 1.0}, {12, 0.3}});
}

const Eigen::MatrixXd& ParametricLandmarkModel::field(Label label) const {
  return fields_.at(static_cast<std::size_t>(label));
}

Eigen::MatrixXd ParametricLandmarkModel::landmarks(Label label, double intensity,
                                                   const Identity& identity) const {
  if (!(intensity >= 0.0 && intensity <= 1.0)) throw InvalidInput("landmark model: intensity must be in [0, 1]");
  if (!(identity.scale > 0.0)) throw InvalidInput("landmark model: identity scale must be > 0");
  if (identity.shape.size() != 0 && (identity.shape.rows() != 68 || identity.shape.cols() != 2))
    throw InvalidInput("landmark model: identity shape must be 68 by 2");
  Eigen::MatrixXd units = neutral_ + intensity * field(label);
  const double c = std::cos(identity.roll), s = std::sin(identity.roll);
  Eigen::Matrix2d rot;
  rot << c, -s, s, c;
  Eigen::MatrixXd px = (units * rot.transpose()) * (kPixelsPerUnit * identity.scale);
  px.rowwise() += (kImageCentre + identity.translation).transpose();
  if (identity.shape.size() != 0) px += identity.shape;
  return px;
}

// thesis §4.4: φ+(x, Do) = exp(ln2·x/Do) − 1.
double onset_curve(double x, double onset_duration) {
  if (!(onset_duration > 0.0)) throw InvalidInput("onset_curve: duration must be > 0");
  return std::exp(std::log(2.0) * x / onset_duration) - 1.0;
}

void SyntheticOptions::validate() const {
  if (sequences_per_label < 1) throw InvalidInput("synthetic: sequences_per_label must be >= 1");
  if (labels.empty()) throw InvalidInput("synthetic: no labels");
  if (subjects < 1) throw InvalidInput("synthetic: subjects must be >= 1");
  if (min_frames < 2 || max_frames < min_frames) throw InvalidInput("synthetic: need 2 <= min_frames <= max_frames");
  if (max_frames > 10000) throw InvalidInput("synthetic: max_frames must be <= 10000");
  if (!(min_intensity > 0.0 && min_intensity <= max_intensity && max_intensity <= 1.0))
    throw InvalidInput("synthetic: need 0 < min_intensity <= max_intensity <= 1");
  for (double v : {scale_std, shape_std, translation_std, roll_std, noise_std})
    if (!(v >= 0.0) || !std::isfinite(v)) throw InvalidInput("synthetic: standard deviations must be >= 0");
  if (!(frame_rate > 0.0) || !std::isfinite(frame_rate)) throw InvalidInput("synthetic: frame_rate must be > 0");
}

namespace {
std::vector<Identity> identities(const SyntheticOptions& options) {
  core::Rng id_rng(options.seed, 1);
  std::vector<Identity> people(options.subjects);
  for (Identity& p : people) {
    p.scale = std::max(0.5, id_rng.normal(1.0, options.scale_std));
    p.roll = id_rng.normal(0.0, options.roll_std);
    p.translation = Eigen::Vector2d(id_rng.normal(0.0, options.translation_std),
                                    id_rng.normal(0.0, options.translation_std));
    p.shape.resize(68, 2);
    for (Eigen::Index i = 0; i < p.shape.size(); ++i) p.shape.data()[i] = id_rng.normal(0.0, options.shape_std);
  }
  return people;
}

Sequence make_sequence(const LandmarkModel& model, const SyntheticOptions& options,
                       const std::vector<Identity>& people, std::size_t index) {
  core::Rng rng(options.seed, 100 + index);
  const Label label = options.labels[index % options.labels.size()];
  const std::size_t subject = index % options.subjects;
  Identity who = people[subject];
  // Each recording: the head sits a little differently.
  who.translation += Eigen::Vector2d(rng.normal(0.0, 3.0), rng.normal(0.0, 3.0));
  const std::size_t n =
      options.min_frames + static_cast<std::size_t>(rng.uniform_int(options.max_frames - options.min_frames + 1));
  const double peak = rng.uniform(options.min_intensity, options.max_intensity);
  Sequence seq;
  char name[48];
  std::snprintf(name, sizeof name, "S%03zu", subject + 1);
  seq.subject = name;
  // The k-th recording of a subject (sequences are dealt to subjects round-robin).
  std::snprintf(name, sizeof name, "_%03zu", index / options.subjects + 1);
  seq.id = seq.subject + name;
  seq.label = label;
  for (std::size_t f = 0; f < n; ++f) {
    const double x = onset_curve(static_cast<double>(f), static_cast<double>(n - 1));
    Eigen::MatrixXd pose = model.landmarks(label, peak * x, who);
    for (Eigen::Index i = 0; i < pose.size(); ++i) pose.data()[i] += rng.normal(0.0, options.noise_std);
    seq.frames.push_back(std::move(pose));
  }
  return seq;
}
}  // namespace

std::size_t synthetic_sequence_count(const SyntheticOptions& options) {
  options.validate();
  return options.sequences_per_label * options.labels.size();
}

Sequence synthetic_sequence(const LandmarkModel& model, const SyntheticOptions& options, std::size_t index) {
  if (index >= synthetic_sequence_count(options)) throw InvalidInput("synthetic: sequence index out of range");
  return make_sequence(model, options, identities(options), index);
}

Database generate_synthetic_database(const LandmarkModel& model, const SyntheticOptions& options) {
  return generate_synthetic_database(model, options, {0, synthetic_sequence_count(options)});
}

Database generate_synthetic_database(const LandmarkModel& model, const SyntheticOptions& options,
                                     std::pair<std::size_t, std::size_t> block) {
  const std::size_t count = synthetic_sequence_count(options);
  if (block.first > block.second || block.second > count)
    throw InvalidInput("generate_synthetic_database: block [" + std::to_string(block.first) + ", " +
                       std::to_string(block.second) + ") is not within the " +
                       std::to_string(count) + " sequences");
  const std::vector<Identity> people = identities(options);
  Database db;
  db.dimensions = 2;
  db.landmark_count = 68;
  db.frame_rate = options.frame_rate;
  for (std::size_t index = block.first; index < block.second; ++index)
    db.sequences.push_back(make_sequence(model, options, people, index));
  return db;
}

}  // namespace emoface::motiongraph
