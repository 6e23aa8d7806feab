#pragma once
// Minimal s-expression reader for the domain language (private). Comments start with ';'.
#include <cstddef>
#include <string>
#include <vector>

#include "emoface/core/errors.hpp"

namespace emoface::parlee::detail {

struct SNode {
  bool is_list = false;
  std::string atom;  ///< symbol text when !is_list
  std::vector<SNode> items;
  std::size_t line = 0, column = 0;
};

/// Parses every top-level form of `text`. Throws FormatError on unbalanced parentheses, stray
/// ')' or nesting deeper than max_depth.
std::vector<SNode> parse_sexprs(const std::string& text, const std::string& file,
                                std::size_t max_depth = 64);

}  // namespace emoface::parlee::detail
