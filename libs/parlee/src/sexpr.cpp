#include "sexpr.hpp"

namespace emoface::parlee::detail {

std::vector<SNode> parse_sexprs(const std::string& text, const std::string& file,
                                std::size_t max_depth) {
  std::vector<SNode> top;
  std::vector<SNode> stack;  // open lists
  std::size_t line = 1, col = 1;
  auto fail = [&](std::size_t l, std::size_t c, const std::string& msg) {
    throw FormatError(SourceLocation{file, "", l, c}, msg);
  };
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const char ch = text[i];
    if (ch == '\n') {
      ++line;
      col = 1;
      ++i;
      continue;
    }
    if (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v') {
      ++i;
      ++col;
      continue;
    }
    if (ch == ';') {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    if (ch == '(') {
      if (stack.size() >= max_depth) fail(line, col, "nesting deeper than " + std::to_string(max_depth));
      SNode node;
      node.is_list = true;
      node.line = line;
      node.column = col;
      stack.push_back(std::move(node));
      ++i;
      ++col;
      continue;
    }
    if (ch == ')') {
      if (stack.empty()) fail(line, col, "unexpected ')'");
      SNode done = std::move(stack.back());
      stack.pop_back();
      if (stack.empty()) top.push_back(std::move(done));
      else stack.back().items.push_back(std::move(done));
      ++i;
      ++col;
      continue;
    }
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f || ch == '"') {
      fail(line, col, "unexpected character");
    }
    SNode atom;
    atom.line = line;
    atom.column = col;
    while (i < n) {
      const char c = text[i];
      if (c == '(' || c == ')' || c == ';' || c == ' ' || c == '\t' || c == '\n' || c == '\r' ||
          c == '\f' || c == '\v' || c == '"' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        break;
      atom.atom.push_back(c);
      ++i;
      ++col;
    }
    if (stack.empty()) fail(atom.line, atom.column, "symbol '" + atom.atom + "' outside a form");
    stack.back().items.push_back(std::move(atom));
  }
  if (!stack.empty()) {
    fail(stack.back().line, stack.back().column,
         "unterminated form: missing ')' (file truncated?)");
  }
  return top;
}

}  // namespace emoface::parlee::detail
