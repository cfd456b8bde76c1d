// The DDA engine (Shi 1988; docs/reference/engine.md): its state, the step-start
// geometry, accepting a step (moving the blocks, stresses, velocities) and the
// public API. The rest of the engine is in the files engine_impl.hpp names.

#include "rheodda/core/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "block_terms.hpp"
#include "engine_impl.hpp"
#include "rheodda/core/defaults.hpp"

namespace rheodda::core {

void Engine::Impl::initialise() {
  const Settings& s = model.settings;
  for (const auto& mat : model.materials) elastic.push_back(elastic_matrix(mat));
  // Fixed points: Shi's code uses a penalty of the order of 10-100 E (dda.md; defaults.hpp).
  fixed_k = s.fixed_point_stiffness > 0.0 ? s.fixed_point_stiffness
                                          : default_fixed_point_stiffness(largest_young_modulus(model.materials));

  Eigen::AlignedBox2d box;
  st.blocks.resize(model.blocks.size());
  count_held();
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
  w0 = core::half_model_size(box.sizes().x(), box.sizes().y());
  {
    // Median block size sqrt(area) [length]: the contact search never reaches
    // less than kSearchFloor of it (docs/reference/engine.md, "Contact search reach").
    std::vector<double> sizes;
    sizes.reserve(st.blocks.size());
    for (const auto& b : st.blocks) sizes.push_back(std::sqrt(std::abs(polygon_integrals(b.vertices).S)));
    std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2), sizes.end());
    search_floor = kSearchFloor * sizes[sizes.size() / 2];
  }
  st.step = 0;
  st.time = 0.0;
  if (s.settle.until > 0.0) start_stage(StageKind::settling, s.settle.until);
  search_disp = std::min(max_displacement_ratio_now() * w0, search_floor);
  st.next_dt = settling() ? std::min(s.dt, s.settle.dt) : s.dt;
  solver = std::make_unique<LinearSolver>(s.solver, s.solver_tolerance, s.solver_max_iterations);
  contact_solve = make_contact_solve(s.contact_solver);
  D = Eigen::VectorXd::Zero(6 * static_cast<Eigen::Index>(st.blocks.size()));
  refresh_geometry();
  st.energy = EnergyAccount::start(energy_inputs());
  if (!model.bolts.empty()) {  // docs/reference/bolts.md: the pretension's energy is there at t = 0
    st.bolts = BoltSet::initial_states(model);
    st.energy.initial.bolt = st.energy.stored.bolt = BoltSet::stored_energy(model, st.bolts);
  }
  st.measurements.assign(model.measurement_points.size(), {});
  record_measurements(-1);
}

void Engine::Impl::count_held() {
  held.assign(model.blocks.size(), 0);
  std::vector<int> points(model.blocks.size(), 0);
  std::vector<char> turn(model.blocks.size(), 0);
  for (const FixedPoint& fp : model.fixed_points) {
    if (fp.hold_x && fp.hold_y) ++points[fp.block];  // one held in x or y only leaves it a mass
    if (fp.hold_rotation) turn[fp.block] = 1;
  }
  // Two points held in both directions, or one and the rotation, hold its rigid motion.
  for (std::size_t k = 0; k < points.size(); ++k) held[k] = points[k] >= 2 || (points[k] >= 1 && turn[k]);
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

double Engine::Impl::max_vertex_displacement(const Eigen::VectorXd& d) const {
  double worst = 0.0;
  for (std::size_t k = 0; k < st.blocks.size(); ++k)
    worst = std::max(worst, largest_vertex_displacement_sq(st.blocks[k], d.segment<6>(6 * static_cast<Eigen::Index>(k))));
  return std::sqrt(worst);
}

void Engine::Impl::accept(const Eigen::VectorXd& d_solved, double dt, int step_index, double t_end) {
  // Blocks removed by an edit (model_edits.cpp) do not move: their unknowns,
  // zero to round-off in the solve, are zero exactly here.
  Eigen::VectorXd d_kept;
  if (!removed.empty()) {
    d_kept = d_solved;
    for (std::size_t k = 0; k < removed.size(); ++k)
      if (removed[k]) d_kept.segment<6>(6 * static_cast<Eigen::Index>(k)).setZero();
  }
  const Eigen::VectorXd& d = removed.empty() ? d_solved : d_kept;
  search_disp = search_reach(d);  // before the blocks move: d is relative to the step start
  const double ratio = ratio_now();
  const bool dynamic = ratio > 0.0;
  const bool keep_acceleration = model.settings.time_integration == TimeIntegration::trapezoidal;
  const Newmark nm = newmark();
  const bool cycled = explicit_now();  // the step was taken in explicit cycles (explicit_step.cpp)
  // Central difference is Newmark's beta = 0, gamma = 1/2 (energy.cpp books no integration loss).
  energy.begin(energy_inputs(), d, dt, cycled ? 0.0 : nm.beta, cycled ? 0.5 : nm.gamma, t_end);
  if (cycled) energy.add_block_damping(cycle_block_damping);  // booked cycle by cycle (explicit_step.cpp)
  step_motion_kinetic = 0.0;
  for (std::size_t k = 0; k < st.blocks.size(); ++k) {
    if (is_removed(k)) continue;  // frozen where it was removed, at rest
    BlockState& b = st.blocks[k];
    const Vec6 Dk = d.segment<6>(6 * static_cast<Eigen::Index>(k));
    // The step's motion as kinetic energy, (D/dt)^T s M (D/dt) / 2 with the step-start mass
    // and the scale the block moved with: what a dynamic stage's rest test reads
    // (dynamic_stages.cpp), not the end velocity, which in Shi's scheme also carries the
    // stiff modes the step does not resolve.
    if (dynamic || cycled) {
      const double s = cycled ? cycle_scale[k] : b.mass_scale;
      step_motion_kinetic += 0.5 * s * model.materials[b.material].density *
                             Dk.dot(unit_mass_matrix(moments[k]) * Dk) / (dt * dt);
    }
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
    if (cycled) {
      b.velocity = cycle_velocity[k];  // the cycles' end velocity, (2) of explicit_step.cpp
      b.acceleration.setZero();
      b.mass_scale = cycle_scale[k];  // density scaling, (6) of explicit_step.cpp
    } else if (dynamic) {
      const Vec6 a_new = (Dk - predictor(b, dt, nm)) / (nm.beta * dt * dt);
      b.velocity = ratio * b.velocity + dt * ((1.0 - nm.gamma) * ratio * b.acceleration + nm.gamma * a_new);
      if (keep_acceleration) b.acceleration = a_new;
    } else {
      // A static step starts and ends at rest (after a dynamic settling stage
      // the velocity it left is dropped here; the energy account books it).
      b.velocity.setZero();
      b.acceleration.setZero();
      b.mass_scale = 1.0;  // a stage's density scaling ends with its velocity
    }
  }
  st.step = step_index + 1;
  st.time = t_end;
  refresh_geometry();
  if (!model.bolts.empty()) {  // on the moved geometry (bolt_step.cpp)
    const BoltEnergy b = bolt_set.commit(model, st.blocks, t_end, st.bolts);
    energy.set_bolts(b.stored, b.dissipation);
  }
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

double Engine::Impl::search_reach(const Eigen::VectorXd& d) const {
  // After an accepted step with displacements d: twice its largest vertex
  // displacement, not below the floor, never beyond max_displacement_ratio w0 (Shi's reach,
  // search_factor x max_displacement_ratio w0).
  return std::min(max_displacement_ratio_now() * w0, std::max(search_floor, 2.0 * max_vertex_displacement(d)));
}

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
void Engine::set_stop_request(StopRequest asked) { impl_->stop_request = std::move(asked); }

const Model& Engine::model() const { return impl_->model; }
int Engine::block_count() const { return static_cast<int>(impl_->st.blocks.size()); }
int Engine::step_count() const { return impl_->st.step; }
double Engine::time() const { return impl_->st.time; }
double Engine::half_model_size() const { return impl_->w0; }
double Engine::allowed_displacement() const { return impl_->max_displacement_ratio_now() * impl_->w0; }
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
const std::vector<StageEvent>& Engine::events() const { return impl_->st.events; }
bool Engine::in_stage() const { return impl_->settling(); }
const std::vector<BoltState>& Engine::bolts() const { return impl_->st.bolts; }

Engine::StableCycle Engine::stable_cycle() { return impl_->stable_cycle(); }
std::vector<double> Engine::block_cycles() { return impl_->block_cycles(); }

EngineState Engine::save() const {
  EngineState s = impl_->st;
  s.search_displacement = impl_->search_disp;
  s.solver = impl_->solver->state();
  return s;
}

void Engine::restore(const EngineState& state) {
  if (state.blocks.size() != impl_->st.blocks.size() ||
      state.measurements.size() != impl_->st.measurements.size())
    throw std::invalid_argument("Engine::restore: the state belongs to a different model");
  for (std::size_t k = 0; k < state.blocks.size(); ++k) {
    const BlockState& b = state.blocks[k];
    const std::size_t n = impl_->st.blocks[k].vertices.size();
    const bool open_stage = state.stage.open && (state.stage.start_vertices.size() != state.blocks.size() ||
                                                 state.stage.start_vertices[k].size() != n);
    if (b.vertices.size() != n || b.edge_joint_set.size() != n || b.material < 0 ||
        b.material >= static_cast<int>(impl_->model.materials.size()) || open_stage)
      throw std::invalid_argument("Engine::restore: the state belongs to a different model (block " +
                                  std::to_string(k) + ")");
  }
  if (state.bolts.size() != impl_->model.bolts.size())
    throw std::invalid_argument("Engine::restore: the state belongs to a different model (bolts)");
  for (const auto& m : state.measurements)
    if (m.empty()) throw std::invalid_argument("Engine::restore: a measurement point has no sample");
  impl_->solver->restore(state.solver);  // first: it may refuse
  impl_->st = state;
  impl_->search_disp = state.search_displacement;
  impl_->reports.clear();
  impl_->refresh_geometry();
}

}  // namespace rheodda::core
