// A parameter's expression of the others: parser and evaluation with its gradient (expression.hpp).
#include "expression.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace rheodda::fit::detail {

// Recursive descent over
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary (('^' | '**') unary)?
//   primary := number | name | '(' sum ')'
class ExpressionParser {
 public:
  ExpressionParser(const std::string& text, const std::vector<std::string>& names, Expression& e)
      : s_(text), names_(names), e_(e) {}

  void run() {
    e_.root_ = sum();
    skip();
    if (i_ < s_.size()) fail(fmt::format("unexpected '{}'", s_[i_]));
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument(fmt::format("expression '{}': {} at character {}", s_, what, i_ + 1));
  }
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(const char* token) {
    skip();
    const std::string t(token);
    if (s_.compare(i_, t.size(), t) != 0) return false;
    if (t == "*" && s_.compare(i_, 2, "**") == 0) return false;  // a power, not a product
    i_ += t.size();
    return true;
  }
  int add(Expression::Node n) {
    e_.nodes_.push_back(n);
    return static_cast<int>(e_.nodes_.size()) - 1;
  }
  int binary(char op, int a, int b) { return add({op, 0.0, 0, a, b}); }

  int sum() {
    int a = product();
    while (true) {
      if (eat("+")) a = binary('+', a, product());
      else if (eat("-")) a = binary('-', a, product());
      else return a;
    }
  }
  int product() {
    int a = unary();
    while (true) {
      if (eat("*")) a = binary('*', a, unary());
      else if (eat("/")) a = binary('/', a, unary());
      else return a;
    }
  }
  int unary() {
    if (eat("-")) return add({'~', 0.0, 0, unary(), -1});
    if (eat("+")) return unary();
    return power();
  }
  int power() {
    const int a = primary();
    if (eat("^") || eat("**")) return binary('^', a, unary());
    return a;
  }
  int primary() {
    skip();
    if (i_ >= s_.size()) fail("a number, a parameter name or '(' expected, found the end");
    if (eat("(")) {
      const int a = sum();
      if (!eat(")")) fail("')' expected");
      return a;
    }
    const char c = s_[i_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const char* begin = s_.c_str() + i_;
      char* end = nullptr;
      const double v = std::strtod(begin, &end);
      if (end == begin) fail("a number expected");
      i_ += static_cast<std::size_t>(end - begin);
      return add({'n', v, 0, -1, -1});
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i_;
      while (j < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[j])) || s_[j] == '_')) ++j;
      const std::string name = s_.substr(i_, j - i_);
      const auto it = std::find(names_.begin(), names_.end(), name);
      if (it == names_.end()) {
        std::string known;
        for (const auto& n : names_) known += (known.empty() ? "" : ", ") + n;
        fail(fmt::format("unknown name '{}' (the parameters: {})", name, known));
      }
      const auto k = static_cast<std::size_t>(it - names_.begin());
      if (std::find(e_.uses_.begin(), e_.uses_.end(), k) == e_.uses_.end()) e_.uses_.push_back(k);
      i_ = j;
      return add({'p', 0.0, k, -1, -1});
    }
    fail(fmt::format("a number, a parameter name or '(' expected, found '{}'", c));
  }

  const std::string& s_;
  const std::vector<std::string>& names_;
  Expression& e_;
  std::size_t i_ = 0;
};

Expression Expression::parse(const std::string& text, const std::vector<std::string>& names) {
  Expression e;
  e.text_ = text;
  e.np_ = names.size();
  ExpressionParser(text, names, e).run();
  return e;
}

double Expression::evaluate(const std::vector<double>& p, std::vector<double>* grad) const {
  if (grad) grad->assign(np_, 0.0);
  return eval(root_, p, grad);
}

// Forward mode: each node returns its value and adds its gradient into `grad`
// (the operands' gradients computed into scratch vectors first):
//   (a ± b)' = a' ± b',  (ab)' = a'b + ab',  (a/b)' = a'/b - a b'/b^2,
//   (a^b)' = b a^(b-1) a' + a^b ln(a) b'  (the second term only where b varies).
double Expression::eval(int i, const std::vector<double>& p, std::vector<double>* grad) const {
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  switch (n.op) {
    case 'n':
      return n.number;
    case 'p':
      if (grad) (*grad)[n.param] += 1.0;
      return p[n.param];
    case '~': {
      std::vector<double> ga;
      const double a = eval(n.a, p, grad ? (ga.assign(np_, 0.0), &ga) : nullptr);
      if (grad)
        for (std::size_t k = 0; k < np_; ++k) (*grad)[k] -= ga[k];
      return -a;
    }
    default:
      break;
  }
  std::vector<double> ga, gb;
  if (grad) ga.assign(np_, 0.0), gb.assign(np_, 0.0);
  const double a = eval(n.a, p, grad ? &ga : nullptr);
  const double b = eval(n.b, p, grad ? &gb : nullptr);
  double v = 0.0, da = 0.0, db = 0.0;  // value and its partial derivatives in a and b
  switch (n.op) {
    case '+': v = a + b, da = 1.0, db = 1.0; break;
    case '-': v = a - b, da = 1.0, db = -1.0; break;
    case '*': v = a * b, da = b, db = a; break;
    case '/': v = a / b, da = 1.0 / b, db = -a / (b * b); break;
    default: {  // '^'
      v = std::pow(a, b);
      da = b * std::pow(a, b - 1.0);
      bool b_varies = false;
      if (grad)
        for (double g : gb) b_varies = b_varies || g != 0.0;
      db = b_varies ? v * std::log(a) : 0.0;
    }
  }
  if (grad)
    for (std::size_t k = 0; k < np_; ++k) (*grad)[k] += da * ga[k] + (db != 0.0 ? db * gb[k] : 0.0);
  return v;
}

}  // namespace rheodda::fit::detail
