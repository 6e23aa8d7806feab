#include "emoface/faceweights/mapper.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "emoface/core/errors.hpp"

namespace emoface::faceweights {

Mapper::Mapper(WeightSet set, std::vector<std::string> parameter_names, BoxLsqOptions fit)
    : set_(std::move(set)), names_(std::move(parameter_names)) {
  set_.validate();
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (!index.emplace(names_[i], i).second)
      throw InvalidInput("Mapper: parameter '" + names_[i] + "' listed twice");
  }
  level_.assign(names_.size(), 0);
  signed_.assign(names_.size(), 0);
  std::map<std::string, std::size_t> input_index;
  std::set<std::string> unbound;
  rows_.resize(set_.targets.size());
  for (std::size_t t = 0; t < set_.targets.size(); ++t) {
    for (const auto& term : set_.targets[t].terms) {
      std::string param = term.input;
      int sign = 0;
      if (param.back() == '+' || param.back() == '-') {
        sign = param.back() == '+' ? 1 : -1;
        param.pop_back();
      }
      auto it = index.find(param);
      if (it == index.end()) {
        unbound.insert(param);
        continue;
      }
      auto [in, fresh] = input_index.emplace(term.input, inputs_.size());
      if (fresh) {
        inputs_.push_back({it->second, sign, sign ? set_.ranges.at(param) : 1.0});
        (sign ? signed_ : level_)[it->second] = 1;
      }
      rows_[t].push_back({in->second, term.weight});
    }
    if (!rows_[t].empty()) fitted_rows_.push_back(t);
  }
  unbound_.assign(unbound.begin(), unbound.end());
  if (!inputs_.empty() && !fitted_rows_.empty()) {
    std::vector<double> a(fitted_rows_.size() * inputs_.size(), 0.0);
    for (std::size_t r = 0; r < fitted_rows_.size(); ++r) {
      for (const auto& b : rows_[fitted_rows_[r]]) a[r * inputs_.size() + b.input] += b.weight;
    }
    solver_ = std::make_unique<BoxLeastSquares>(std::move(a), fitted_rows_.size(), inputs_.size(),
                                                std::vector<double>(inputs_.size(), 0.0),
                                                std::vector<double>(inputs_.size(), 1.0), fit);
  }
}

double Mapper::input_value(const Input& in, const double* params) const {
  const double v = params[in.param];
  if (in.sign == 0) return v;
  return std::clamp(std::max(0.0, in.sign * v) / in.range, 0.0, 1.0);
}

void Mapper::forward(const double* params, double* weights) const {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const double v = params[i];
    if (!std::isfinite(v)) throw InvalidInput("parameter '" + names_[i] + "' is not finite");
    if (level_[i] && (v < 0.0 || v > 1.0))
      throw InvalidInput("parameter '" + names_[i] + "' = " + std::to_string(v) +
                         " is outside [0, 1]");
  }
  for (std::size_t t = 0; t < rows_.size(); ++t) {
    double s = 0.0;
    for (const auto& b : rows_[t]) s += b.weight * input_value(inputs_[b.input], params);
    weights[t] = std::clamp(s, 0.0, 1.0);
  }
}

std::vector<double> Mapper::forward(const std::vector<double>& params) const {
  if (params.size() != names_.size())
    throw InvalidInput("Mapper::forward: expected " + std::to_string(names_.size()) +
                       " parameters, got " + std::to_string(params.size()));
  std::vector<double> w(rows_.size());
  forward(params.data(), w.data());
  return w;
}

FitReport Mapper::inverse(const std::vector<double>& weights, std::vector<double>& params) const {
  if (weights.size() != rows_.size())
    throw InvalidInput("Mapper::inverse: expected " + std::to_string(rows_.size()) + " '" +
                       set_.set + "' weights, got " + std::to_string(weights.size()));
  for (std::size_t t = 0; t < weights.size(); ++t) {
    const double w = weights[t];
    if (!std::isfinite(w))
      throw InvalidInput("weight of '" + set_.targets[t].name + "' is not finite");
    if (w < 0.0 || w > 1.0)
      throw InvalidInput("weight of '" + set_.targets[t].name + "' = " + std::to_string(w) +
                         " is outside [0, 1]");
  }
  if (params.size() != names_.size()) params.assign(names_.size(), 0.0);
  FitReport report;
  for (std::size_t t = 0; t < rows_.size(); ++t) {
    if (rows_[t].empty() && weights[t] != 0.0) report.unrepresented.push_back(set_.targets[t].name);
  }
  if (!solver_) {
    report.converged = true;
    report.message = "nothing to fit";
    return report;
  }
  std::vector<double> b(fitted_rows_.size());
  for (std::size_t r = 0; r < fitted_rows_.size(); ++r) b[r] = weights[fitted_rows_[r]];
  std::vector<double> x(inputs_.size());
  for (std::size_t j = 0; j < inputs_.size(); ++j) {
    const double v = std::isfinite(params[inputs_[j].param]) ? params[inputs_[j].param] : 0.0;
    x[j] = std::clamp(inputs_[j].sign == 0 ? v : input_value(inputs_[j], params.data()), 0.0, 1.0);
  }
  static_cast<BoxLsqReport&>(report) = solver_->solve(b, x);
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (signed_[i]) params[i] = 0.0;
  }
  for (std::size_t j = 0; j < inputs_.size(); ++j) {
    const auto& in = inputs_[j];
    if (in.sign == 0)
      params[in.param] = x[j];
    else
      params[in.param] += in.sign * x[j] * in.range;
  }
  return report;
}

std::vector<double> to_facs(const std::vector<double>& params, const std::vector<std::string>& names) {
  return Mapper(builtin_weight_set("facs"), names).forward(params);
}

std::vector<double> to_arkit(const std::vector<double>& params, const std::vector<std::string>& names) {
  return Mapper(builtin_weight_set("arkit"), names).forward(params);
}

std::vector<double> from_arkit(const std::vector<double>& weights,
                               const std::vector<std::string>& names, FitReport* report) {
  const Mapper m(builtin_weight_set("arkit"), names);
  std::vector<double> params(names.size(), 0.0);
  FitReport r = m.inverse(weights, params);
  if (report) *report = std::move(r);
  return params;
}

}  // namespace emoface::faceweights
