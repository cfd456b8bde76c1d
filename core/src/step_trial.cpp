// One attempt at a step (docs/reference/engine.md, "A step"): the contacts are detected
// on the step-start geometry (begin_step), then the step's integrator takes its trial
// (integrator.hpp): Shi's implicit step here, the block terms assembled and the
// contact solve (Settings::contact_solver; contact_solve.hpp) finding D and the
// contact states that agree, or the explicit step's cycles (explicit_step.cpp). A step
// whose motion outran the contact search is redone with a wider one.
#include <algorithm>

#include "engine_impl.hpp"

namespace rheodda::core {

/// The step as the contact solve sees it: the engine's block terms, its
/// block system and linear solver, timed into the step report.
class Engine::Impl::Problem final : public StepProblem {
 public:
  Problem(Engine::Impl& e, StepReport& rep, double dt) : e_(e), rep_(rep), dt_(dt) {}
  std::span<const contact::BlockView> blocks() const override { return e_.views; }
  const std::vector<Mat6>& block_matrix() const override { return e_.base_diag; }
  const Eigen::VectorXd& block_rhs() const override { return e_.base_rhs; }
  ContactModel& contacts() override { return *e_.contacts; }
  const Settings& settings() const override { return e_.model.settings; }
  bool iterative_solver() const override {
    return e_.solver->iterative(static_cast<int>(e_.st.blocks.size()));
  }
  Eigen::VectorXd solve_system(bool loose) override {
    auto t0 = Clock::now();
    e_.system.reset(e_.base_diag, e_.base_rhs);
    e_.system.set_centroids(e_.views);  // the points the unknowns refer to (the amg solver's coarse spaces)
    e_.contacts->assemble(e_.views, e_.system);
    if (!e_.model.bolts.empty()) e_.bolt_set.assemble(e_.system);  // bolts.hpp, (3) and (4)
    e_.system.finalize();
    rep_.assembly_seconds += seconds_since(t0);
    t0 = Clock::now();
    Eigen::VectorXd d = loose ? e_.solver->solve(e_.system, e_.model.settings.solver_iterate_tolerance)
                              : e_.solver->solve(e_.system);
    rep_.solve_seconds += seconds_since(t0);
    return d;
  }
  bool dynamic() const override { return e_.dynamic_now(); }
  int iteration_limit() const override {
    const Settings& s = e_.model.settings;
    return e_.settling() && s.settle.open_close_limit > 0 ? s.settle.open_close_limit : s.open_close_limit;
  }
  ContactCheck check(const Eigen::VectorXd& d) override {
    ContactCheck c = e_.contacts->check(e_.views, d);
    rep_.changes += c.changes;
    // A bolt that started or stopped yielding asks for another iterate as a
    // contact that changed its state does (bolts.hpp).
    if (!e_.model.bolts.empty()) c.state_changes += e_.bolt_set.check(d);
    return c;
  }

 private:
  Engine::Impl& e_;
  StepReport& rep_;
  double dt_;  ///< the step's size [time]
};

Engine::Impl::Trial Engine::Impl::solve_trial(double dt, bool creep_error_wanted, StepReport& rep) {
  StepContext ctx = step_context(dt);
  ctx.creep_error_wanted = creep_error_wanted;
  ctx.dynamic = dynamic_now();
  ctx.inertia = 1.0 / (newmark().beta * dt * dt);  // as assemble_blocks adds M/(beta dt^2)
  contacts->begin_step(views, ctx);
  if (!model.bolts.empty()) bolt_set.begin_step(model, st.blocks, st.bolts, dt);
  Trial trial;
  try {
    trial = (this->*trial_now())(dt, rep);  // the integrator's trial (integrator.hpp)
  } catch (...) {
    contacts->abandon_step();  // leave the contacts at their step-start states
    throw;
  }
  trial.max_disp = trial.converged ? max_vertex_displacement(D) : 0.0;
  if (trial.converged && trial.max_disp > search_disp && search_disp < max_displacement_ratio_now() * w0) {
    // The step moved a vertex further than the contact search reached: a
    // contact beyond the search distance may have closed unseen. Redo the step
    // (same dt) with the search widened to cover the motion (docs/reference/engine.md,
    // "Contact search reach"); beyond max_displacement_ratio w0 the caller cuts dt as before.
    contacts->abandon_step();
    search_disp = std::min(max_displacement_ratio_now() * w0, 2.0 * trial.max_disp);
    ++rep.search_widenings;
    return solve_trial(dt, creep_error_wanted, rep);
  }
  return trial;
}

Engine::Impl::Trial Engine::Impl::implicit_trial(double dt, StepReport& rep) {
  Trial trial;
  auto t0 = Clock::now();
  assemble_blocks(dt, st.time + dt, base_diag, base_rhs);
  rep.assembly_seconds += seconds_since(t0);
  Problem problem(*this, rep, dt);
  try {
    const ContactSolveResult r = contact_solve->solve(problem, D);
    trial.converged = r.converged;
    trial.iterations = r.iterations;
    trial.check = r.check;
  } catch (const SingularSystemError& e) {
    contacts->abandon_step();
    trial.singular = e.what();
    trial.singular_block = e.block;
    trial.singular_unknown = e.unknown;
  }
  return trial;
}

}  // namespace rheodda::core
