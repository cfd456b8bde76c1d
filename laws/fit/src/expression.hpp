// Internal to rheodda_fit: a parameter given by an expression of the others,
// as lmfit's Parameter(expr=...) (expression.cpp; docs/guide/fitting.md,
// "Initial values, bounds, fixed parameters and weights"). The grammar is
// arithmetic only: numbers, parameter names, + - * / and powers (^ or **),
// parentheses, unary signs; powers bind tighter than a sign and to the right
// (-a**2 = -(a**2), a**b**c = a**(b**c)), as in Python, whose syntax lmfit's
// expressions use.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace rheodda::fit::detail {

class Expression {
 public:
  /// Parses `text` over the parameter `names`; std::invalid_argument with the
  /// position and what was expected, or the unknown name and the known ones.
  static Expression parse(const std::string& text, const std::vector<std::string>& names);

  /// The value at parameter values `p` (indexed as `names`) and, with `grad`,
  /// its derivative with respect to each p_k (forward mode, exact: the chain
  /// rule through every operation).
  double evaluate(const std::vector<double>& p, std::vector<double>* grad = nullptr) const;

  const std::string& text() const { return text_; }
  /// The parameters it refers to (indices into `names`), each once.
  const std::vector<std::size_t>& uses() const { return uses_; }

 private:
  struct Node {
    char op = 0;           // 'n' number, 'p' parameter, '~' negation, or + - * / ^
    double number = 0.0;
    std::size_t param = 0;
    int a = -1, b = -1;    // operands (indices into nodes_)
  };
  double eval(int i, const std::vector<double>& p, std::vector<double>* grad) const;

  std::string text_;
  std::vector<Node> nodes_;
  int root_ = -1;
  std::size_t np_ = 0;
  std::vector<std::size_t> uses_;
  friend class ExpressionParser;
};

}  // namespace rheodda::fit::detail
