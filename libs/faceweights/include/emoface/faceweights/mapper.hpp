#pragma once
// Face parameters ↔ weight-set targets (FACS action units, ARKit blend shapes).
//
//   auto names = emoface::muscles::parameter_names();              // or channels' / fuzzyexpr's list
//   emoface::faceweights::Mapper arkit(builtin_weight_set("arkit"), names);
//   std::vector<double> w = arkit.forward(params);                 // 52 weights in [0, 1]
//   std::vector<double> p;  auto report = arkit.inverse(w, p);     // bounded least-squares fit
//
// The mapper binds the set's inputs to positions in a caller-given parameter list, so this library
// needs no mesh and no copy of the parameter names: any list works (the 42 of muscles, the 35 side
// parameters of fuzzyexpr). Inputs the list lacks read as 0 and are not fitted (unbound_inputs()).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "emoface/faceweights/box_lsq.hpp"
#include "emoface/faceweights/weight_set.hpp"

namespace emoface::faceweights {

struct FitReport : BoxLsqReport {
  /// Targets with a non-zero weight that no bound parameter can produce (no muscle: tongueOut, …).
  std::vector<std::string> unrepresented;
};

class Mapper {
 public:
  /// Throws InvalidInput if the set is invalid, the names repeat, or a bound parameter is used by
  /// the set both as a level and as a signed angle.
  Mapper(WeightSet set, std::vector<std::string> parameter_names, BoxLsqOptions fit = {});

  const WeightSet& set() const noexcept { return set_; }
  const std::vector<std::string>& parameter_names() const noexcept { return names_; }
  std::size_t target_count() const noexcept { return set_.targets.size(); }
  std::size_t parameter_count() const noexcept { return names_.size(); }
  /// Set inputs (parameter names) absent from parameter_names(); they read as 0.
  const std::vector<std::string>& unbound_inputs() const noexcept { return unbound_; }

  /// params: parameter_count() values (levels in [0, 1], angles finite, radians) → target_count()
  /// weights, each clamp(Σ w·input, 0, 1). Throws InvalidInput naming the parameter on bad values.
  void forward(const double* params, double* weights) const;
  std::vector<double> forward(const std::vector<double>& params) const;

  /// The inverse fit: parameters whose forward() weights best match `weights` (target_count()
  /// values in [0, 1], finite) in the least-squares sense, levels bounded to [0, 1], each signed
  /// angle split into two halves in [0, 1]·range (BoxLeastSquares; the clamp of forward() is not
  /// modelled). `params` is the warm start (resized to parameter_count() and zeroed if its size
  /// differs); only parameters the set uses are written, the others keep their values.
  /// Throws InvalidInput naming the target on bad weights.
  FitReport inverse(const std::vector<double>& weights, std::vector<double>& params) const;

 private:
  struct Input {
    std::size_t param;  // index into names_
    int sign;           // 0 level, ±1 half of a signed angle
    double range;       // radians (signed inputs)
  };
  struct Bound {
    std::size_t input;
    double weight;
  };
  WeightSet set_;
  std::vector<std::string> names_;
  std::vector<std::string> unbound_;
  std::vector<Input> inputs_;               // one per distinct bound input = one fit unknown
  std::vector<std::vector<Bound>> rows_;    // per target
  std::vector<std::size_t> fitted_rows_;    // targets with at least one bound term
  std::vector<char> level_;                 // per parameter: used as a level input
  std::vector<char> signed_;                // per parameter: used as a signed input
  std::unique_ptr<BoxLeastSquares> solver_;
  double input_value(const Input& in, const double* params) const;
};

/// One-off conversions with the built-in sets ("facs", "arkit"); `names` orders `params`.
std::vector<double> to_facs(const std::vector<double>& params, const std::vector<std::string>& names);
std::vector<double> to_arkit(const std::vector<double>& params, const std::vector<std::string>& names);
/// ARKit weights (arkit_names() order) → parameters in `names` order (zeros where not fitted).
std::vector<double> from_arkit(const std::vector<double>& weights,
                               const std::vector<std::string>& names, FitReport* report = nullptr);

}  // namespace emoface::faceweights
