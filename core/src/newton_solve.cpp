// A semismooth Newton solve of the step (docs/reference/contacts.md, "Contact solves").
//
// The step's equations are R(D) = F0 - K0 D - f(D) = 0, with f(D) the forces
// of the contacts at D (ContactModel::contact_forces): piecewise linear in D,
// one piece per set of contact states. Shi's open-close iteration is Newton's
// method on them - each iterate solves the linear system of the piece the
// last D lies on - but it stops only when no contact changes its state. That
// test is stricter than the equations: on a vibrating wall or a settling rock
// mass, contacts that carry next to nothing flip between open and closed or
// between stuck and sliding from one iterate to the next while the forces they
// move are round-off next to the loads, and the iteration goes on (and is cut)
// for them. This solve converges on the residual instead: the step is
// accepted when, after the contacts have checked D,
// |R(D)| <= Settings::contact_residual_tolerance x |f(D)| (each block's
// rotation and strain rows divided by its size, so that every row is a force),
// whether or not a state changed. A dynamic step starts, as in the open-close
// solve, from the states of the last step (the states at the Newmark predictor
// are those of a free fall, every contact open: docs/notes/contact-solves.md).
// Where the open-close iteration converges it converges too, to a D within the
// tolerance of the same equations (tests/contact/engine/contact_solve_test.cpp).
#include <cmath>
#include <limits>
#include <vector>

#include "contact_solves.hpp"

namespace rheodda::core {

namespace {

class NewtonSolve final : public ContactSolve {
 public:
  ContactSolveResult solve(StepProblem& p, Eigen::VectorXd& D) override {
    prepare_weights(p);
    const double tolerance = p.settings().contact_residual_tolerance;
    return iterate_contacts(p, D, [&](const ContactCheck& c) {
      return c.state_changes == 0 || converged(p, D, tolerance);
    });
  }

 private:
  /// 1 / size of each block (its largest centroid-to-vertex distance) [1/length]:
  /// the rotation and strain rows of R are force x length.
  std::vector<double> inverse_size_;

  void prepare_weights(const StepProblem& p) {
    const auto blocks = p.blocks();
    inverse_size_.resize(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      double r = 0.0;
      for (const auto& v : blocks[b].vertices) r = std::max(r, (v - blocks[b].centroid).norm());
      inverse_size_[b] = r > 0.0 ? 1.0 / r : 1.0;
    }
  }

  /// |R(D)| <= tolerance |f(D)| in the weighted norm.
  bool converged(StepProblem& p, const Eigen::VectorXd& D, double tolerance) {
    if (!(tolerance > 0.0)) return false;
    Eigen::VectorXd f = Eigen::VectorXd::Zero(D.size());
    if (!p.contacts().contact_forces(D, f)) return false;
    const std::vector<Mat6>& K0 = p.block_matrix();
    const Eigen::VectorXd& F0 = p.block_rhs();
    double r2 = 0.0, f2 = 0.0;
    for (std::size_t b = 0; b < K0.size(); ++b) {
      const auto i = 6 * static_cast<Eigen::Index>(b);
      Vec6 r = F0.segment<6>(i) - K0[b] * D.segment<6>(i) - f.segment<6>(i);
      Vec6 g = f.segment<6>(i);
      r.tail<4>() *= inverse_size_[b];
      g.tail<4>() *= inverse_size_[b];
      r2 += r.squaredNorm();
      f2 += g.squaredNorm();
    }
    return std::sqrt(r2) <= tolerance * std::sqrt(f2);
  }
};

}  // namespace

std::unique_ptr<ContactSolve> make_newton_solve() { return std::make_unique<NewtonSolve>(); }

}  // namespace rheodda::core
