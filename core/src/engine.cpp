// The DDA time step (Shi 1988; docs/engine.md).
//
// Per step, with D_i = (u0, v0, r0, ex, ey, gxy) the unknowns of block i at
// its centroid (x0, y0) and T_i(x, y) the first-order displacement matrix
// (contact/kinematics.hpp, the seed's eq. 27):
//   K_ii += S E_e                              elastic strain energy
//   F_i  -= S sigma                            initial (carried) stress
//   F_i  += T_i(p)^T f(t + dt)                 point load at p
//   F_i  += rho S (gx, gy, 0, 0, 0, 0)         body force
//   K_ii += 2/dt^2 M_i,  F_i += 2/dt M_i v_i   inertia, M_i = rho int T^T T dA
//   K_ii += p T^T T,     F_i += p T^T (x0 - x) fixed point (penalty spring)
// then the contacts add their springs and friction through the SystemSink,
// K D = F is solved (the seed's eq. 30) and the contacts check the trial D.
#include "rheodda/core/engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "block_terms.hpp"
#include "rheodda/core/block_system.hpp"
#include "rheodda/core/polygon.hpp"
#include "rheodda/core/solver.hpp"

namespace rheodda::core {

namespace {

using Clock = std::chrono::steady_clock;

/// Adaptive creep stepping rejects a step whose creep error estimate exceeds
/// this multiple of Settings::creep_tolerance [-] (docs/speed-accuracy.md).
constexpr double kRejectFactor = 2.0;
/// Adaptive creep stepping steps onto a damage law's failure when it is within
/// this many steps (docs/rheology-in-dda.md, "Failure") [-].
constexpr double kFailureReach = 8.0;
/// The contact search of a large model (g2 w0 above this fraction of the median
/// block size) reaches only as far as the motion needs, not below this fraction
/// (docs/engine.md, "Contact search reach") [-].
constexpr double kSearchFloor = 0.1;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

std::string at(const char* list, std::size_t k) { return std::string(list) + "[" + std::to_string(k) + "]"; }

/// Is p inside the polygon or within tol of its boundary?
bool inside_or_near(std::span<const Vec2> v, const Vec2& p, double tol) {
  bool inside = false;
  const std::size_t n = v.size();
  for (std::size_t k = 0, j = n - 1; k < n; j = k++) {
    const Vec2& a = v[k];
    const Vec2& b = v[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
    const Vec2 e = b - a;
    const double s = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    if ((a + s * e - p).norm() <= tol) return true;
  }
  return inside;
}

/// " (the last of its iterates still changed 2: 1 slipped, 1 stuck)": why an
/// open-close iteration was cut, for the error message (empty when the contact
/// model does not tell the kinds apart).
std::string last_changes(const ContactCheck& c) {
  const ContactChanges& k = c.changes;
  if (k.total() == 0) return {};
  std::string s = " (the last of its iterates still changed " + std::to_string(k.total()) + ":";
  const std::pair<int, const char*> kinds[] = {{k.closed, "closed"},
                                               {k.opened, "opened"},
                                               {k.slipped, "slipped"},
                                               {k.stuck, "stuck"},
                                               {k.refinements, "friction refinements"}};
  const char* sep = " ";
  for (const auto& [n, word] : kinds)
    if (n > 0) s += sep + std::to_string(n) + " " + word, sep = ", ";
  return s + ")";
}

}  // namespace

struct Engine::Impl {
  Model model;
  NullContactModel null_contacts;
  ContactModel* contacts = nullptr;

  EngineState st;
  std::vector<PolygonIntegrals> moments;  // central integrals of the step-start geometry
  std::vector<char> held;                 // block held by two or more fixed points
  std::vector<contact::BlockView> views;
  std::vector<Eigen::Matrix3d> elastic;   // per material
  double w0 = 0.0;                        // half model size [length]
  /// The displacement per step the contact search covers (StepContext::
  /// max_displacement; contacts are looked for within search_factor x it):
  /// g2 w0 where that is below search_floor, else adapted to the motion
  /// (search_reach(), docs/engine.md, "Contact search reach") [length].
  double search_disp = 0.0;
  double search_floor = 0.0;  // kSearchFloor x the median block size [length]
  double search_reach(const Eigen::VectorXd& d) const;
  double fixed_k = 0.0;                   // fixed point penalty [force/length]
  /// Share of the velocity the step starting now carries: the analysis's
  /// dynamic_ratio, or 1 in a dynamic settling stage (Settings::settle_dynamic).
  double ratio_now() const {
    return settling() && model.settings.settle_dynamic ? 1.0 : model.settings.dynamic_ratio;
  }
  /// The step starting now carries velocity (a dynamic step).
  bool dynamic_now() const { return ratio_now() > 0.0; }

  /// Newmark parameters of the current step. The trapezoidal rule needs the
  /// acceleration at the step start; the first step has none, so it uses Shi's
  /// scheme (exact for a constant acceleration), which yields it.
  struct Newmark {
    double beta, gamma;
  };
  Newmark newmark() const {
    if (model.settings.time_integration == TimeIntegration::trapezoidal && st.step > 0)
      return {0.25, 0.5};
    return {0.5, 1.0};
  }
  /// Newmark predictor Dp = v dt + (1/2 - beta) dt^2 a from the carried v, a.
  Vec6 predictor(const BlockState& b, double dt, const Newmark& nm) const {
    return ratio_now() * (dt * b.velocity + (0.5 - nm.beta) * dt * dt * b.acceleration);
  }

  BlockSystem system;
  std::unique_ptr<LinearSolver> solver;
  Eigen::VectorXd D;
  std::vector<Mat6> base_diag;  // block terms of the step being solved (scratch)
  Eigen::VectorXd base_rhs;
  std::vector<StepReport> reports;
  std::vector<StepObserver> observers;
  EnergyAccount energy;  // the balance itself is st.energy (energy.hpp)
  EnergyInputs energy_inputs() const {
    return {model, st.blocks, moments, elastic, fixed_k, ratio_now()};
  }

  void validate();
  void initialise();
  void refresh_geometry();
  void assemble_blocks(double dt, double t_end, std::vector<Mat6>& diag, Eigen::VectorXd& rhs) const;
  double max_vertex_displacement(const Eigen::VectorXd& d) const;
  /// End of the collapse stage in progress, or of the last one (Settings::
  /// collapse_dt; docs/engine.md, "Collapse stages"); 0 before any [time].
  double collapse_until = 0.0;
  /// End of the stage the run is in or was last in: the settling stage or a
  /// collapse stage [time].
  double stage_end() const { return std::max(model.settings.settle_until, collapse_until); }
  /// In the settling stage (Settings::settle_until; docs/engine.md, "Settling
  /// stage") or in a collapse stage.
  bool settling() const {
    const double end = stage_end();
    return end > 0.0 && st.time < end - 1e-12 * std::max(1.0, std::abs(end));
  }
  /// A static step of dt whose trial D moves as a mechanism (collapse stages).
  bool collapses(double dt) const {
    return EnergyAccount::static_trial_share(energy_inputs(), D, dt, newmark().beta, st.time + dt) >
           kMechanismStepShare;
  }
  /// The displacement limit g2 in force now: settle_g2 in the settling stage.
  double g2_now() const { return settling() ? model.settings.settle_g2 : model.settings.g2; }
  void accept(const Eigen::VectorXd& d, double dt, int step_index, double t_end);
  void record_measurements(int step_index);
  StepReport step(double dt_cap);
  /// After a static trial of dt that moved as a mechanism (docs/engine.md,
  /// "Collapse stages"): cuts dt towards collapse_dt and returns false, or, at
  /// collapse_dt, opens a collapse stage from the step's start, sets dt to the
  /// stage's first step and returns true.
  bool open_collapse_stage(double& dt, StepReport& rep);

  /// One attempt at a step of dt from the current state: begin_step, then the
  /// open-close iteration up to max_open_close iterates. The contacts are left
  /// in their trial states: the caller ends or abandons the step.
  struct Trial {
    bool converged = false;
    int iterations = 0;
    double max_disp = 0.0;  // largest vertex displacement of the converged D [length]
    ContactCheck check;
    /// Set when a solve found the matrix not positive definite (the attempt is
    /// cut like one that did not converge: a shorter step stiffens the inertia
    /// terms 2M/dt^2; after max_cuts the error is thrown with this diagnosis).
    std::string singular;
    int singular_block = -1, singular_unknown = -1;
  };
  Trial solve_trial(double dt, bool creep_error_wanted, StepReport& rep);
  /// Cuts dt after a failed attempt (dt *= dt_cut), or throws after max_cuts cuts.
  void cut(double& dt, const Trial& trial, StepReport& rep) const;
  /// Attempts a step of dt and accepts it (contacts end_step, blocks move) when
  /// it converges within g2 w0; otherwise abandons it. No creep estimate.
  bool take(double dt, StepReport& rep, Trial& trial);
  /// A step under Settings::step_tolerance: step doubling with local extrapolation.
  StepReport doubling_step(double dt_cap);
  /// First point-load sample time after the current time (inf if none) [time].
  double next_load_break() const;
  /// Next step of an adaptive control from the error estimate err of a step dt [time].
  double next_adaptive_dt(double dt, double tolerance, double err, double load_break) const;
};

void Engine::Impl::validate() {
  const Model& m = model;
  if (m.materials.empty()) throw ModelError("materials", "at least one material is required");
  for (std::size_t k = 0; k < m.materials.size(); ++k) {
    const Material& mat = m.materials[k];
    if (!(mat.density > 0.0 && std::isfinite(mat.density)))
      throw ModelError(at("materials", k) + ".density", "must be > 0 (mass/length^3)");
    if (!(mat.young_modulus > 0.0 && std::isfinite(mat.young_modulus)))
      throw ModelError(at("materials", k) + ".young_modulus", "must be > 0 (stress)");
    if (!(mat.poisson_ratio >= 0.0 && mat.poisson_ratio < 0.5))
      throw ModelError(at("materials", k) + ".poisson_ratio", "must be in [0, 0.5)");
    if (!(mat.damping_ratio >= 0.0 && mat.damping_ratio <= 1.0))
      throw ModelError(at("materials", k) + ".damping_ratio", "must be in [0, 1]");
    if (mat.damping_ratio > 0.0 && !m.settings.has_dynamic_steps())
      throw ModelError(at("materials", k) + ".damping_ratio",
                       "damps velocities; a static analysis (dynamic_ratio 0) without a dynamic "
                       "settling stage has none");
  }
  if (m.blocks.empty()) throw ModelError("blocks", "at least one block is required");
  const Settings& s = m.settings;
  for (std::size_t k = 0; k < m.blocks.size(); ++k) {
    const BlockDef& b = m.blocks[k];
    const std::string key = at("blocks", k);
    if (b.vertices.size() < 3)
      throw ModelError(key + ".vertices", "a block needs at least 3 vertices");
    for (const auto& v : b.vertices)
      if (!finite(v)) throw ModelError(key + ".vertices", "vertex coordinates must be finite");
    if (!is_simple_polygon(b.vertices))
      throw ModelError(key + ".vertices",
                       "not a simple polygon (edges cross, touch or have zero length)");
    if (polygon_integrals(b.vertices).S == 0.0)
      throw ModelError(key + ".vertices", "the polygon has zero area");
    if (!b.edge_joint_set.empty() && b.edge_joint_set.size() != b.vertices.size())
      throw ModelError(key + ".edge_joint_set",
                       "needs one joint set per edge (" + std::to_string(b.vertices.size()) +
                           "), or none");
    for (int j : b.edge_joint_set)
      if (j < 0) throw ModelError(key + ".edge_joint_set", "joint set indices must be >= 0");
    if (b.material < 0 || b.material >= static_cast<int>(m.materials.size()))
      throw ModelError(key + ".material", "no material with index " + std::to_string(b.material));
    if (!b.initial_stress.allFinite())
      throw ModelError(key + ".initial_stress", "must be finite");
    if (!finite(b.initial_velocity) || !std::isfinite(b.initial_angular_velocity))
      throw ModelError(key + ".initial_velocity", "must be finite");
    if (s.dynamic_ratio == 0.0 &&
        (b.initial_velocity != Vec2::Zero() || b.initial_angular_velocity != 0.0))
      throw ModelError(key + ".initial_velocity",
                       "a static analysis (settings.dynamic_ratio = 0) carries no velocities");
  }
  auto check_point = [&](const std::string& key, int block, const Vec2& p) {
    if (block < 0 || block >= static_cast<int>(m.blocks.size()))
      throw ModelError(key + ".block", "no block with index " + std::to_string(block));
    if (!finite(p)) throw ModelError(key + ".point", "must be finite");
    const auto& v = m.blocks[block].vertices;
    Eigen::AlignedBox2d box;
    for (const auto& q : v) box.extend(q);
    if (!inside_or_near(v, p, 1e-9 * box.diagonal().norm()))
      throw ModelError(key + ".point", "lies outside block " + std::to_string(block));
  };
  for (std::size_t k = 0; k < m.point_loads.size(); ++k) {
    const PointLoad& l = m.point_loads[k];
    const std::string key = at("point_loads", k);
    check_point(key, l.block, l.point);
    if (l.history.empty()) throw ModelError(key + ".history", "needs at least one sample");
    for (std::size_t i = 0; i < l.history.size(); ++i) {
      if (!std::isfinite(l.history[i].time) || !finite(l.history[i].force))
        throw ModelError(key + ".history", "time and force must be finite");
      if (i > 0 && !(l.history[i].time > l.history[i - 1].time))
        throw ModelError(key + ".history", "times must increase strictly");
    }
  }
  for (std::size_t k = 0; k < m.fixed_points.size(); ++k)
    check_point(at("fixed_points", k), m.fixed_points[k].block, m.fixed_points[k].point);
  for (std::size_t k = 0; k < m.measurement_points.size(); ++k)
    check_point(at("measurement_points", k), m.measurement_points[k].block,
                m.measurement_points[k].point);

  if (!(s.dt > 0.0 && std::isfinite(s.dt))) throw ModelError("settings.dt", "must be > 0 (time)");
  if (!(s.dt_growth >= 1.0 && std::isfinite(s.dt_growth)))
    throw ModelError("settings.dt_growth", "must be >= 1");
  if (!(s.dt_cut > 0.0 && s.dt_cut < 1.0)) throw ModelError("settings.dt_cut", "must be in (0, 1)");
  if (s.max_cuts < 0) throw ModelError("settings.max_cuts", "must be >= 0");
  if (!(s.creep_tolerance >= 0.0 && std::isfinite(s.creep_tolerance)))
    throw ModelError("settings.creep_tolerance", "must be >= 0 (length; 0 = fixed dt)");
  if (s.creep_tolerance > 0.0 && s.dt_max > 0.0 && s.dt_max < s.dt)
    throw ModelError("settings.dt_max", "must be >= dt (the first step) under creep_tolerance");
  if (!(s.step_tolerance >= 0.0 && std::isfinite(s.step_tolerance)))
    throw ModelError("settings.step_tolerance", "must be >= 0 (length; 0 = off)");
  if (s.step_tolerance > 0.0 && s.creep_tolerance > 0.0)
    throw ModelError("settings.step_tolerance",
                     "give step_tolerance or creep_tolerance, not both (two step controls)");
  if (s.step_tolerance > 0.0 && s.dt_max > 0.0 && s.dt_max < s.dt)
    throw ModelError("settings.dt_max", "must be >= dt (the first step) under step_tolerance");
  if (!(s.dt_max >= 0.0 && std::isfinite(s.dt_max)))
    throw ModelError("settings.dt_max", "must be >= 0 (time; 0 = no limit)");
  if (!(s.g2 > 0.0 && std::isfinite(s.g2))) throw ModelError("settings.g2", "must be > 0");
  if (!(s.settle_until >= 0.0 && std::isfinite(s.settle_until)))
    throw ModelError("settings.settle_until", "must be >= 0 (time; 0 = no settling stage)");
  if (s.settle_until > 0.0 && !(s.settle_dt > 0.0 && std::isfinite(s.settle_dt)))
    throw ModelError("settings.settle_dt", "must be > 0 (time) with a settling stage");
  if (s.settle_until > 0.0 && !(s.settle_g2 > 0.0 && std::isfinite(s.settle_g2)))
    throw ModelError("settings.settle_g2", "must be > 0 with a settling stage");
  if (!(s.collapse_dt >= 0.0 && std::isfinite(s.collapse_dt)))
    throw ModelError("settings.collapse_dt", "must be >= 0 (time; 0 = no collapse stages)");
  if (s.collapse_dt > 0.0) {
    if (!(s.settle_until > 0.0 && s.settle_dynamic && s.dynamic_ratio == 0.0))
      throw ModelError("settings.collapse_dt",
                       "collapse stages are for a static analysis with a dynamic settling stage (their model)");
    if (!(s.collapse_dt < s.dt)) throw ModelError("settings.collapse_dt", "must be < dt");
    if (s.step_tolerance > 0.0)
      throw ModelError("settings.collapse_dt", "not with step_tolerance (step doubling takes no collapse stage)");
  }
  if (!(s.dynamic_ratio >= 0.0 && s.dynamic_ratio <= 1.0))
    throw ModelError("settings.dynamic_ratio", "must be in [0, 1]");
  if (!finite(s.gravity)) throw ModelError("settings.gravity", "must be finite");
  if (!(s.settle_gravity_ramp >= 0.0 && std::isfinite(s.settle_gravity_ramp)))
    throw ModelError("settings.settle_gravity_ramp", "must be >= 0 (time; 0 = gravity at once)");
  if (s.settle_gravity_ramp > 0.0 && !(s.settle_gravity_ramp <= s.settle_until))
    throw ModelError("settings.settle_gravity_ramp",
                     "must end within the settling stage (<= settle_until), so that the creep starts under full gravity");
  if (!(s.fixed_point_stiffness >= 0.0 && std::isfinite(s.fixed_point_stiffness)))
    throw ModelError("settings.fixed_point_stiffness", "must be >= 0 (0 = automatic)");
  if (s.max_open_close < 1) throw ModelError("settings.max_open_close", "must be >= 1");
  if (!(s.pcg_tolerance > 0.0)) throw ModelError("settings.pcg_tolerance", "must be > 0");
  if (s.pcg_max_iterations < 1) throw ModelError("settings.pcg_max_iterations", "must be >= 1");
  if (!(s.pcg_iterate_tolerance >= 0.0 && s.pcg_iterate_tolerance < 1.0))
    throw ModelError("settings.pcg_iterate_tolerance", "must be in [0, 1) (0 = every solve at pcg_tolerance)");
  if (s.time_integration == TimeIntegration::trapezoidal && s.dynamic_ratio == 0.0)
    throw ModelError("settings.time_integration",
                     "the trapezoidal rule needs a dynamic analysis (settings.dynamic_ratio > 0)");
}

void Engine::Impl::initialise() {
  const Settings& s = model.settings;
  double e_max = 0.0;
  for (const auto& mat : model.materials) {
    elastic.push_back(elastic_matrix(mat));
    e_max = std::max(e_max, mat.young_modulus);
  }
  // Fixed points: Shi's code uses a penalty of the order of 10-100 E (dda.md).
  fixed_k = s.fixed_point_stiffness > 0.0 ? s.fixed_point_stiffness : 100.0 * e_max;

  Eigen::AlignedBox2d box;
  st.blocks.resize(model.blocks.size());
  held.assign(model.blocks.size(), 0);
  {
    std::vector<int> points(model.blocks.size(), 0);
    for (const FixedPoint& fp : model.fixed_points) ++points[fp.block];
    for (std::size_t k = 0; k < points.size(); ++k) held[k] = points[k] >= 2;
  }
  for (std::size_t k = 0; k < model.blocks.size(); ++k) {
    const BlockDef& def = model.blocks[k];
    BlockState& b = st.blocks[k];
    b.vertices = def.vertices;
    b.edge_joint_set = def.edge_joint_set.empty() ? std::vector<int>(def.vertices.size(), 0)
                                                  : def.edge_joint_set;
    normalise_orientation(b.vertices, b.edge_joint_set);
    b.material = def.material;
    b.stress = def.initial_stress;
    b.velocity.setZero();
    b.velocity << def.initial_velocity.x(), def.initial_velocity.y(), def.initial_angular_velocity,
        0.0, 0.0, 0.0;
    for (const auto& v : b.vertices) box.extend(v);
  }
  w0 = 0.5 * std::max(box.sizes().x(), box.sizes().y());
  {
    // Median block size sqrt(area) [length]: the contact search never reaches
    // less than kSearchFloor of it (docs/engine.md, "Contact search reach").
    std::vector<double> sizes;
    sizes.reserve(st.blocks.size());
    for (const auto& b : st.blocks) sizes.push_back(std::sqrt(std::abs(polygon_integrals(b.vertices).S)));
    std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2), sizes.end());
    search_floor = kSearchFloor * sizes[sizes.size() / 2];
  }
  st.step = 0;
  st.time = 0.0;
  search_disp = std::min(g2_now() * w0, search_floor);
  st.next_dt = settling() ? std::min(s.dt, s.settle_dt) : s.dt;
  solver = std::make_unique<LinearSolver>(s.solver, s.pcg_tolerance, s.pcg_max_iterations);
  D = Eigen::VectorXd::Zero(6 * static_cast<Eigen::Index>(st.blocks.size()));
  refresh_geometry();
  st.energy = EnergyAccount::start(energy_inputs());
  st.measurements.assign(model.measurement_points.size(), {});
  record_measurements(-1);
}

void Engine::Impl::refresh_geometry() {
  const std::size_t n = st.blocks.size();
  moments.resize(n);
  views.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    BlockState& b = st.blocks[k];
    moments[k] = central_integrals(b.vertices, &b.centroid);
    // Mass for the contact dashpots: a block held at two or more fixed points
    // does not move with the impact (infinite).
    views[k] = contact::BlockView{b.vertices, b.centroid, b.edge_joint_set,
                                  held[k] ? std::numeric_limits<double>::infinity()
                                          : model.materials[b.material].density * moments[k].S};
  }
}

void Engine::Impl::assemble_blocks(double dt, double t_end, std::vector<Mat6>& diag,
                                   Eigen::VectorXd& rhs) const {
  const Settings& s = model.settings;
  const std::size_t n = st.blocks.size();
  diag.resize(n);
  rhs.resize(6 * static_cast<Eigen::Index>(n));
  const Newmark nm = newmark();
  for (std::size_t k = 0; k < n; ++k) {
    const BlockState& b = st.blocks[k];
    const PolygonIntegrals& g = moments[k];
    const double rho = model.materials[b.material].density;
    Mat6& K = diag[k];
    auto F = rhs.segment<6>(6 * static_cast<Eigen::Index>(k));
    // Inertia (Shi 1988; Newmark): the end-of-step acceleration is
    // a' = (D - Dp)/(beta dt^2), Dp = v dt + (1/2 - beta) dt^2 a, so
    // K += M/(beta dt^2) and F += M Dp/(beta dt^2). Shi's beta = 1/2, gamma = 1
    // gives K += 2 M/dt^2 and F += 2 M v/dt with v the carried velocity.
    const Mat6 M = rho * unit_mass_matrix(g);
    K = (1.0 / (nm.beta * dt * dt)) * M;
    // Elastic strain energy S/2 e^T E_e e: K(ex..gxy) += S E_e.
    K.block<3, 3>(3, 3) += g.S * elastic[b.material];
    // Block damping (Material::damping_ratio), implicit over the step: the
    // viscous stress E_e tau eps_dot with eps_dot = eps/dt adds (tau/dt) S E_e.
    if (const double tau = strain_damping_time(g, model.materials[b.material], elastic[b.material]);
        tau > 0.0 && dynamic_now())
      K.block<3, 3>(3, 3) += (tau / dt) * g.S * elastic[b.material];
    // Body force rho g over the area; the other rows vanish about the centroid.
    F.setZero();
    // With a gravity ramp (Settings::settle_gravity_ramp) its value at the
    // step's end, where the step's equilibrium is written.
    const Vec2 gravity = s.gravity_at(t_end);
    F(0) = rho * gravity.x() * g.S;
    F(1) = rho * gravity.y() * g.S;
    // Initial stress: potential S e^T sigma gives F(ex..gxy) -= S sigma.
    F.tail<3>() -= g.S * b.stress;
    if (dynamic_now()) F.noalias() += (1.0 / (nm.beta * dt * dt)) * M * predictor(b, dt, nm);
  }
  // Point loads: F += T(p)^T f at the current position p of the material point.
  for (const auto& l : model.point_loads) {
    const BlockState& b = st.blocks[l.block];
    const Vec2 p = b.map_A * l.point + b.map_b;
    const Vec2 f = load_at(l.history, t_end);
    rhs.segment<6>(6 * l.block) += contact::displacement_matrix(b.centroid, p).transpose() * f;
  }
  // Fixed points: spring p between the material point x and its held position x0,
  // energy p/2 |T D - (x0 - x)|^2.
  for (const auto& fp : model.fixed_points) {
    const BlockState& b = st.blocks[fp.block];
    const Vec2 x = b.map_A * fp.point + b.map_b;
    const contact::Mat26 T = contact::displacement_matrix(b.centroid, x);
    diag[fp.block].noalias() += fixed_k * T.transpose() * T;
    rhs.segment<6>(6 * fp.block).noalias() += fixed_k * T.transpose() * (fp.point - x);
  }
}

double Engine::Impl::max_vertex_displacement(const Eigen::VectorXd& d) const {
  double worst = 0.0;
  for (std::size_t k = 0; k < st.blocks.size(); ++k) {
    const BlockState& b = st.blocks[k];
    const auto Dk = d.segment<6>(6 * static_cast<Eigen::Index>(k));
    for (const auto& v : b.vertices) {
      const Vec2 u = contact::displacement_matrix(b.centroid, v) * Dk;
      worst = std::max(worst, u.squaredNorm());
    }
  }
  return std::sqrt(worst);
}

void Engine::Impl::accept(const Eigen::VectorXd& d, double dt, int step_index, double t_end) {
  search_disp = search_reach(d);  // before the blocks move: d is relative to the step start
  const double ratio = ratio_now();
  const bool dynamic = ratio > 0.0;
  const bool keep_acceleration = model.settings.time_integration == TimeIntegration::trapezoidal;
  const Newmark nm = newmark();
  energy.begin(energy_inputs(), d, dt, nm.beta, nm.gamma, t_end);
  for (std::size_t k = 0; k < st.blocks.size(); ++k) {
    BlockState& b = st.blocks[k];
    const Vec6 Dk = d.segment<6>(6 * static_cast<Eigen::Index>(k));
    // Geometry with the exact-rotation post-correction: the first-order T
    // moves a point by r0 (-dy, dx), which scales areas by (1 + r0^2); instead
    // rotate exactly: x' = c + u + R(r0) (I + eps) (x - c), where eps is the
    // small strain (ex, gxy/2; gxy/2, ey). Rigid rotation keeps the area.
    const double r0 = Dk(2);
    Mat2 R;
    R << std::cos(r0), -std::sin(r0), std::sin(r0), std::cos(r0);
    Mat2 strain;
    strain << 1.0 + Dk(3), 0.5 * Dk(5), 0.5 * Dk(5), 1.0 + Dk(4);
    const Mat2 Fm = R * strain;
    const Vec2 c = b.centroid;
    const Vec2 c_new = c + Dk.head<2>();
    for (auto& v : b.vertices) v = c_new + Fm * (v - c);
    b.map_A = Fm * b.map_A;
    b.map_b = c_new + Fm * (b.map_b - c);
    // Stress: sigma += E_e (ex, ey, gxy) (Shi 1988, stress update).
    b.stress += elastic[b.material] * Dk.tail<3>();
    // Velocity (Newmark): a' = (D - Dp)/(beta dt^2), v' = v + dt ((1 - gamma) a + gamma a')
    // with the carried v, a; for Shi's scheme this is v' = 2 D/dt - v.
    if (dynamic) {
      const Vec6 a_new = (Dk - predictor(b, dt, nm)) / (nm.beta * dt * dt);
      b.velocity = ratio * b.velocity + dt * ((1.0 - nm.gamma) * ratio * b.acceleration + nm.gamma * a_new);
      if (keep_acceleration) b.acceleration = a_new;
    } else {
      // A static step starts and ends at rest (after a dynamic settling stage
      // the velocity it left is dropped here; the energy account books it).
      b.velocity.setZero();
      b.acceleration.setZero();
    }
  }
  st.step = step_index + 1;
  st.time = t_end;
  refresh_geometry();
  energy.end(energy_inputs(), t_end, contacts->energy(), st.energy);
  record_measurements(step_index);
}

void Engine::Impl::record_measurements(int step_index) {
  for (std::size_t k = 0; k < model.measurement_points.size(); ++k) {
    const auto& mp = model.measurement_points[k];
    const BlockState& b = st.blocks[mp.block];
    const Vec2 x = b.map_A * mp.point + b.map_b;
    st.measurements[k].push_back({step_index, st.time, x, x - mp.point});
  }
}

StepReport Engine::Impl::step(double dt_cap) {
  const Settings& s = model.settings;
  // Settling stage (docs/engine.md, "Settling stage"): steps of at most
  // settle_dt with g2 = settle_g2, ending on settle_until, no adaptive control.
  bool settle = settling();
  if (settle) dt_cap = std::min(dt_cap, stage_end() - st.time);
  if (s.step_tolerance > 0.0 && !settle) return doubling_step(dt_cap);
  StepReport rep;
  rep.step = st.step;
  bool adaptive = s.creep_tolerance > 0.0 && !settle;
  double load_break = std::numeric_limits<double>::infinity();
  double failure_step = std::numeric_limits<double>::infinity();  // step that reaches a failure
  if (adaptive) {
    load_break = next_load_break();
    dt_cap = std::min(dt_cap, load_break - st.time);
    // A damage law's failure ends a step (docs/rheology-in-dda.md, "Failure"):
    // the time left before the first contact fails at its present stress, 1e-3
    // of it beyond, so that it fails in that step even when its stress moves
    // a little within it (a step right to the failure time can leave a sliver
    // of life, then a sliver of that, and so on: measured, 38 more steps on
    // the shear creep test at 1e-6 beyond).
    failure_step = contacts->time_to_failure() * (1.0 + 1e-3);
  }
  bool capped = dt_cap < st.next_dt;
  double dt = std::min(st.next_dt, dt_cap);
  // Step onto the failure rather than over it, and also when it is within
  // kFailureReach steps: the creep rate diverges there, the error control
  // would shrink the steps in proportion to the time left and never arrive,
  // and the failing step's creep is not kept (the contact becomes frictional).
  if (failure_step < dt || (failure_step <= kFailureReach * dt && failure_step <= dt_cap))
    dt = failure_step;
  double allowed = g2_now() * w0;
  const bool watch = s.collapse_dt > 0.0;  // collapse stages (docs/engine.md, "Collapse stages")
  for (;;) {
    const Trial trial = solve_trial(dt, adaptive, rep);
    if (watch && !settle && trial.singular.empty() &&
        (!trial.converged || trial.max_disp > allowed || collapses(dt))) {
      // A static step that moves as a mechanism: its path would be set by dt
      // and g2. Cut it down to collapse_dt (locating the onset); at collapse_dt,
      // take the collapse from the step's start in a dynamic stage. Beyond the
      // step limit g2 w0 counts as well: a part sliding at its friction limit
      // gives the inertia term only the unbalanced share of the work, yet
      // moves by that force times dt^2 / 2M; and so does an open-close
      // iteration that does not settle at collapse_dt, where the static steps
      // would otherwise go on cutting into a crawl of the mechanism
      // (docs/engine.md, "Collapse stages").
      contacts->abandon_step();
      if (open_collapse_stage(dt, rep)) {
        settle = true;
        adaptive = false;
        capped = true;
        allowed = g2_now() * w0;
      }
      continue;
    }
    if (trial.converged && trial.max_disp <= allowed) {
      contacts->end_step(views, D);
      double err = 0.0;
      if (adaptive) {
        // Reject and redo a step whose creep error estimate exceeds the
        // tolerance by more than kRejectFactor (docs/speed-accuracy.md, "Adaptive
        // creep stepping"), with the step the estimate asks for: dt 0.9
        // sqrt(tol / err) (local error ~ dt^2), at least dt_cut dt. Never below
        // the first step dt (the control cannot stall on an estimate that does
        // not fall with the step, e.g. at a contact state change), nor more than
        // max_cuts times in one step.
        err = contacts->creep_error_estimate();
        if (err > kRejectFactor * s.creep_tolerance && dt > s.dt &&
            rep.rejections + rep.cuts < s.max_cuts && contacts->retract_step()) {
          dt = std::max(dt * std::max(s.dt_cut, 0.9 * std::sqrt(s.creep_tolerance / err)), s.dt);
          ++rep.rejections;
          continue;
        }
      }
      rep.dt = dt;
      rep.iterations = trial.iterations;
      rep.max_displacement = trial.max_disp;
      rep.max_penetration = trial.check.max_penetration;
      accept(D, dt, st.step, st.time + dt);
      rep.time = st.time;
      if (adaptive) {
        // Step size from the creep error estimate err of this step.
        rep.creep_error = err;
        rep.creep_state_changes = contacts->creep_state_changes();
        double next = next_adaptive_dt(dt, s.creep_tolerance, err, load_break);
        // A creeping contact that locked, slid or opened moved load onto its
        // neighbours at once, as a load change does: restart from dt.
        if (s.creep_restart_on_contact_change && rep.creep_state_changes > 0)
          next = std::min(next, s.dt);
        st.next_dt = next;
      } else if (rep.cuts > 0 || !capped) {
        st.next_dt = std::min(settle ? std::min(s.dt, s.settle_dt) : s.dt, dt * s.dt_growth);
      }
      if (settle && !settling()) st.next_dt = s.dt;  // the stage is over: the analysis's dt
      return rep;
    }
    contacts->abandon_step();
    cut(dt, trial, rep);
  }
}

bool Engine::Impl::open_collapse_stage(double& dt, StepReport& rep) {
  const Settings& s = model.settings;
  if (dt > s.collapse_dt * (1.0 + 1e-9)) {  // locate the onset: retry smaller, not below collapse_dt
    if (rep.cuts >= s.max_cuts)
      throw std::runtime_error("step " + std::to_string(st.step) + " at time " + std::to_string(st.time) +
                               ": moves as a mechanism at dt = " + std::to_string(dt) + " after " +
                               std::to_string(rep.cuts) + " cuts, above collapse_dt = " +
                               std::to_string(s.collapse_dt) + " (settings.max_cuts)");
    dt = std::max(dt * s.dt_cut, s.collapse_dt);
    ++rep.cuts;
    return false;
  }
  collapse_until = st.time + s.settle_until;  // a stage as long as the settling stage
  rep.collapse_stage = true;
  dt = std::min(s.settle_dt, collapse_until - st.time);
  return true;
}

double Engine::Impl::next_load_break() const {
  // Adaptive stepping (either control): steps end on the point-load sample
  // times (where the loads change their course), and the step after one
  // restarts from dt. Sample times closer than dt/1000 after the step start (a
  // load jump given as a steep ramp) fall inside the step.
  const double eps = std::max(1e-12 * std::max(1.0, std::abs(st.time)), 1e-3 * model.settings.dt);
  double t = std::numeric_limits<double>::infinity();
  for (const auto& pl : model.point_loads)
    for (const auto& ls : pl.history)
      if (ls.time > st.time + eps) t = std::min(t, ls.time);
  return t;
}

double Engine::Impl::next_adaptive_dt(double dt, double tolerance, double err,
                                      double load_break) const {
  // Local error ~ dt^2 for both first-order estimates (the creep estimate and
  // the step-doubling difference): dt' = dt min(2, max(dt_cut, 0.9 sqrt(tol /
  // err))), capped by dt_max; dt again after a load break.
  const Settings& s = model.settings;
  const double factor =
      err > 0.0 ? std::clamp(0.9 * std::sqrt(tolerance / err), s.dt_cut, 2.0) : 2.0;
  double next = dt * factor;
  if (s.dt_max > 0.0) next = std::min(next, s.dt_max);
  if (st.time >= load_break - 1e-12 * std::max(1.0, std::abs(load_break))) next = s.dt;
  return next;
}

bool Engine::Impl::take(double dt, StepReport& rep, Trial& trial) {
  trial = solve_trial(dt, false, rep);
  if (trial.converged && trial.max_disp <= g2_now() * w0) {
    contacts->end_step(views, D);
    accept(D, dt, st.step, st.time + dt);
    return true;
  }
  contacts->abandon_step();
  return false;
}

StepReport Engine::Impl::doubling_step(double dt_cap) {
  // Step doubling with local extrapolation (docs/speed-accuracy.md, "Step
  // doubling"). The step y_c of dt and two steps y_f of dt/2 from the same
  // state: the DDA step is first order, y_c - y = C dt^2 + O(dt^3) and
  // y_f - y = C dt^2/2 + O(dt^3), so err = max |y_f - y_c| over the block
  // vertices estimates the local error of y_f, and 2 y_f - y_c (Richardson)
  // is the state with local error O(dt^3): a second-order step.
  const Settings& s = model.settings;
  StepReport rep;
  rep.step = st.step;
  const double load_break = next_load_break();
  dt_cap = std::min(dt_cap, load_break - st.time);
  double dt = std::min(st.next_dt, dt_cap);
  const std::vector<BlockState> start_blocks = st.blocks;
  const int start_step = st.step;
  const double start_time = st.time;
  const std::size_t start_samples =
      st.measurements.empty() ? 0 : st.measurements.front().size();
  const std::unique_ptr<ContactSnapshot> start_contacts = contacts->snapshot();
  const EnergyBalance start_energy = st.energy;
  if (!start_contacts)
    throw std::runtime_error(
        "settings.step_tolerance: the contact model cannot copy its state (step doubling needs "
        "ContactModel::snapshot)");
  auto restart = [&] {
    st.blocks = start_blocks;
    st.step = start_step;
    st.time = start_time;
    for (auto& m : st.measurements) m.resize(start_samples);
    refresh_geometry();
    contacts->restore(*start_contacts);
    st.energy = start_energy;
  };
  std::vector<BlockState> coarse;
  EnergyFlows coarse_energy;
  for (;;) {
    Trial trial;
    bool ok = take(dt, rep, trial);
    double coarse_disp = trial.max_disp;
    int iterations = trial.iterations;
    std::unique_ptr<ContactSnapshot> coarse_contacts;
    if (ok) {
      coarse = st.blocks;
      coarse_energy = st.energy.step;
      coarse_contacts = contacts->snapshot();
      restart();
      ok = take(0.5 * dt, rep, trial);
      iterations += trial.iterations;
      if (ok) {
        ok = take(0.5 * dt, rep, trial);
        iterations += trial.iterations;
      }
    }
    if (!ok) {
      restart();
      cut(dt, trial, rep);
      continue;
    }
    double err = 0.0;
    for (std::size_t k = 0; k < st.blocks.size(); ++k)
      for (std::size_t i = 0; i < st.blocks[k].vertices.size(); ++i)
        err = std::max(err, (st.blocks[k].vertices[i] - coarse[k].vertices[i]).squaredNorm());
    err = std::sqrt(err);
    // Reject and redo a step whose estimate exceeds the tolerance by more than
    // kRejectFactor, as the creep control does (not below dt, at most max_cuts
    // times in one step).
    if (err > kRejectFactor * s.step_tolerance && dt > s.dt &&
        rep.rejections + rep.cuts < s.max_cuts) {
      restart();
      dt = std::max(dt * std::max(s.dt_cut, 0.9 * std::sqrt(s.step_tolerance / err)), s.dt);
      ++rep.rejections;
      continue;
    }
    // Richardson: 2 y_f - y_c for the blocks and, through the contact model,
    // for every contact quantity; only when both runs end with the same
    // contacts in the same states (else y_f stands, first order).
    rep.extrapolated = s.step_extrapolation && contacts->extrapolate(*coarse_contacts);
    if (rep.extrapolated) {
      for (std::size_t k = 0; k < st.blocks.size(); ++k) {
        BlockState& b = st.blocks[k];
        const BlockState& c = coarse[k];
        for (std::size_t i = 0; i < b.vertices.size(); ++i)
          b.vertices[i] = 2.0 * b.vertices[i] - c.vertices[i];
        b.map_A = 2.0 * b.map_A - c.map_A;
        b.map_b = 2.0 * b.map_b - c.map_b;
        b.stress = 2.0 * b.stress - c.stress;
        b.velocity = 2.0 * b.velocity - c.velocity;
        b.acceleration = 2.0 * b.acceleration - c.acceleration;
      }
      refresh_geometry();
    }
    EnergyAccount::finish_doubling(energy_inputs(), start_energy, coarse_energy, rep.extrapolated,
                                   contacts->energy(), st.energy);
    // One step of dt for the outside: one report, one measurement sample.
    st.step = start_step + 1;
    st.time = start_time + dt;
    for (auto& m : st.measurements) m.resize(start_samples);
    record_measurements(start_step);
    rep.dt = dt;
    rep.time = st.time;
    rep.iterations = iterations;
    rep.max_displacement = coarse_disp;
    rep.max_penetration = trial.check.max_penetration;
    rep.step_error = err;
    // Not below dt (the first step): where the estimate does not fall with the
    // step - e.g. the quasi-static settling of a static analysis under gravity
    // applied at once, whose per-step motion is g dt^2 whatever the creep - the
    // control would follow that path in ever smaller steps.
    st.next_dt = std::max(next_adaptive_dt(dt, s.step_tolerance, err, load_break), s.dt);
    return rep;
  }
}

Engine::Impl::Trial Engine::Impl::solve_trial(double dt, bool creep_error_wanted, StepReport& rep) {
  const Settings& s = model.settings;
  StepContext ctx{st.step, st.time, dt, search_disp};
  ctx.creep_error_wanted = creep_error_wanted;
  ctx.dynamic = dynamic_now();
  ctx.inertia = 1.0 / (newmark().beta * dt * dt);  // as assemble_blocks adds M/(beta dt^2)
  contacts->begin_step(views, ctx);
  auto t0 = Clock::now();
  assemble_blocks(dt, st.time + dt, base_diag, base_rhs);
  rep.assembly_seconds += seconds_since(t0);
  Trial trial;
  const double loose_tolerance = s.pcg_iterate_tolerance;
  bool tight_next = false;
  int loose_iterates = 0;
  while (trial.iterations - loose_iterates < s.max_open_close) {
    t0 = Clock::now();
    system.reset(base_diag, base_rhs);
    system.set_centroids(views);  // the points the unknowns refer to (the amg solver's coarse spaces)
    contacts->assemble(views, system);
    system.finalize();
    rep.assembly_seconds += seconds_since(t0);
    t0 = Clock::now();
    // Inexact iterates (docs/contacts.md, "Inexact iterates"): while the
    // states still change, an iterative solve stops at a loose tolerance; a
    // trial converges only on a check of a solve at the full one.
    // At most a third of the limit's worth of iterates is solved loosely, and
    // those do not count towards the limit: an iteration that has not settled
    // by then (a wall whose contacts chatter) goes on with exact solves as
    // without the option, with the whole limit ahead of it.
    const bool loose = loose_tolerance > solver->tolerance() && !tight_next &&
                       3 * loose_iterates < s.max_open_close &&
                       solver->iterative(static_cast<int>(st.blocks.size()));
    if (loose) ++loose_iterates;
    try {
      D = loose ? solver->solve(system, loose_tolerance) : solver->solve(system);
    } catch (const SingularSystemError& e) {
      contacts->abandon_step();
      trial.singular = e.what();
      trial.singular_block = e.block;
      trial.singular_unknown = e.unknown;
      return trial;
    } catch (...) {
      contacts->abandon_step();  // leave the contacts at their step-start states
      throw;
    }
    rep.solve_seconds += seconds_since(t0);
    ++trial.iterations;
    trial.check = contacts->check(views, D);
    rep.changes += trial.check.changes;
    if (trial.check.state_changes == 0) {
      if (loose) {  // settled on an inexact solve: confirm on an exact one
        tight_next = true;
        continue;
      }
      trial.converged = true;
      break;
    }
    tight_next = false;
  }
  trial.max_disp = trial.converged ? max_vertex_displacement(D) : 0.0;
  if (trial.converged && trial.max_disp > search_disp && search_disp < g2_now() * w0) {
    // The step moved a vertex further than the contact search reached: a
    // contact beyond the search distance may have closed unseen. Redo the step
    // (same dt) with the search widened to cover the motion (docs/engine.md,
    // "Contact search reach"); beyond g2 w0 the caller cuts dt as before.
    contacts->abandon_step();
    search_disp = std::min(g2_now() * w0, 2.0 * trial.max_disp);
    ++rep.search_widenings;
    return solve_trial(dt, creep_error_wanted, rep);
  }
  return trial;
}

double Engine::Impl::search_reach(const Eigen::VectorXd& d) const {
  // After an accepted step with displacements d: twice its largest vertex
  // displacement, not below the floor, never beyond g2 w0 (Shi's reach,
  // search_factor x g2 w0).
  return std::min(g2_now() * w0, std::max(search_floor, 2.0 * max_vertex_displacement(d)));
}

void Engine::Impl::cut(double& dt, const Trial& trial, StepReport& rep) const {
  const Settings& s = model.settings;
  if (rep.cuts >= s.max_cuts && !trial.singular.empty())
    throw SingularSystemError("step " + std::to_string(st.step) + " at time " + std::to_string(st.time) + ": " +
                                  trial.singular + " after " + std::to_string(rep.cuts) +
                                  " cuts of dt (settings.max_cuts)",
                              trial.singular_block, trial.singular_unknown);
  if (rep.cuts >= s.max_cuts)
    throw std::runtime_error(
        "step " + std::to_string(st.step) + " at time " + std::to_string(st.time) + ": " +
        (trial.converged ? "displacement " + std::to_string(trial.max_disp) +
                               " exceeds g2 * w0 = " + std::to_string(g2_now() * w0)
                         : "open-close iteration did not converge" + last_changes(trial.check)) +
        " after " + std::to_string(rep.cuts) + " cuts of dt (settings.max_cuts)");
  dt *= s.dt_cut;
  ++rep.cuts;
}

Engine::Engine(Model model) : impl_(std::make_unique<Impl>()) {
  impl_->model = std::move(model);
  impl_->contacts = &impl_->null_contacts;
  impl_->validate();
  impl_->initialise();
}

Engine::Engine(Model model, ContactModel& contacts) : impl_(std::make_unique<Impl>()) {
  impl_->model = std::move(model);
  impl_->contacts = &contacts;
  impl_->validate();
  impl_->initialise();
}

Engine::~Engine() = default;

StepReport Engine::step() {
  StepReport r = impl_->step(std::numeric_limits<double>::infinity());
  r.energy = impl_->st.energy.step;
  impl_->reports.push_back(r);
  for (const auto& o : impl_->observers) o(*this, r);
  return r;
}

void Engine::run(int steps) {
  for (int k = 0; k < steps; ++k) step();
}

void Engine::run_until(double end_time) { run_until(end_time, end_time); }

void Engine::run_until(double end_time, double horizon) {
  while (impl_->st.time < end_time) {
    // A sliver below round-off of the end time is not worth a step.
    if (end_time - impl_->st.time <= 1e-12 * std::max(1.0, std::abs(end_time))) break;
    StepReport r = impl_->step(std::max(horizon, end_time) - impl_->st.time);
    r.energy = impl_->st.energy.step;
    impl_->reports.push_back(r);
    for (const auto& o : impl_->observers) o(*this, r);
  }
}

void Engine::add_observer(StepObserver observer) { impl_->observers.push_back(std::move(observer)); }

const Model& Engine::model() const { return impl_->model; }
int Engine::block_count() const { return static_cast<int>(impl_->st.blocks.size()); }
int Engine::step_count() const { return impl_->st.step; }
double Engine::time() const { return impl_->st.time; }
double Engine::half_model_size() const { return impl_->w0; }
double Engine::allowed_displacement() const { return impl_->g2_now() * impl_->w0; }
const BlockState& Engine::block(int b) const { return impl_->st.blocks.at(b); }
std::span<const Vec2> Engine::vertices(int b) const { return impl_->st.blocks.at(b).vertices; }
Vec2 Engine::centroid(int b) const { return impl_->st.blocks.at(b).centroid; }
double Engine::area(int b) const { return impl_->moments.at(b).S; }
Vec3 Engine::stress(int b) const { return impl_->st.blocks.at(b).stress; }
Vec6 Engine::velocity(int b) const { return impl_->st.blocks.at(b).velocity; }
Vec2 Engine::point_position(int b, const Vec2& p0) const {
  const BlockState& s = impl_->st.blocks.at(b);
  return s.map_A * p0 + s.map_b;
}
Vec2 Engine::point_displacement(int b, const Vec2& p0) const { return point_position(b, p0) - p0; }
std::span<const contact::BlockView> Engine::views() const { return impl_->views; }
const Eigen::VectorXd& Engine::last_displacements() const { return impl_->D; }
const std::vector<StepReport>& Engine::reports() const { return impl_->reports; }
const std::vector<std::vector<MeasurementSample>>& Engine::measurements() const {
  return impl_->st.measurements;
}
const SolverStats& Engine::solver_stats() const { return impl_->solver->stats(); }
const EnergyBalance& Engine::energy() const { return impl_->st.energy; }

EngineState Engine::save() const { return impl_->st; }

void Engine::restore(const EngineState& state) {
  if (state.blocks.size() != impl_->st.blocks.size() ||
      state.measurements.size() != impl_->st.measurements.size())
    throw std::invalid_argument("Engine::restore: the state belongs to a different model");
  for (std::size_t k = 0; k < state.blocks.size(); ++k)
    if (state.blocks[k].vertices.size() != impl_->st.blocks[k].vertices.size())
      throw std::invalid_argument("Engine::restore: the state belongs to a different model (block " +
                                  std::to_string(k) + ")");
  impl_->st = state;
  impl_->refresh_geometry();
}

}  // namespace rheodda::core
