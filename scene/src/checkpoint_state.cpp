// The state file of a checkpoint (checkpoint_state.hpp): its header, and the
// payload written and read by one description of each structure (io() below),
// so that the two directions cannot disagree.
#include "checkpoint_state.hpp"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "rheodda/scene/output.hpp"
#include "rheodda/version.hpp"

namespace rheodda::scene {
namespace {

using json = nlohmann::ordered_json;

/// Counts the members of an aggregate (as many initialisers as it takes).
struct AnyField {
  template <class T>
  operator T() const;
};
template <class T, class... A>
constexpr std::size_t field_count() {
  if constexpr (requires { T{A{}..., AnyField{}}; })
    return field_count<T, A..., AnyField>();
  else
    return sizeof...(A);
}

// A structure that gains a member must have it written here too (and
// kStateFormat raised): these fail to compile until it is.
static_assert(field_count<core::StoredEnergy>() == 6);
static_assert(field_count<core::EnergyFlows>() == 15);
static_assert(field_count<core::EnergyBalance>() == 5);
static_assert(field_count<core::StageEvent>() == 12);
static_assert(field_count<core::StageState>() == 6);
static_assert(field_count<core::EngineState>() == 11);
static_assert(field_count<core::BoltState>() == 7);
static_assert(field_count<core::SolverState>() == 8);
static_assert(field_count<core::BlockState>() == 10);
static_assert(field_count<core::MeasurementSample>() == 4);
static_assert(field_count<contact::Contact>() == 19);
static_assert(field_count<contact::ContactKey>() == 4);
static_assert(field_count<contact::CreepCounters>() == 3);
static_assert(field_count<contact::ContactSystem::StepWork>() == 12);
static_assert(field_count<contact::ContactSystem::State>() == 14);
static_assert(field_count<laws::RheologyState>() == 2);
static_assert(field_count<core::ContactChanges>() == 7);
static_assert(field_count<RunResult::StaticMechanism>() == 7);

template <class T>
struct is_vector : std::false_type {};
template <class T>
struct is_vector<std::vector<T>> : std::true_type {};
template <class T>
struct is_pair : std::false_type {};
template <class A, class B>
struct is_pair<std::pair<A, B>> : std::true_type {};
template <class T>
struct is_array : std::false_type {};
template <class T, std::size_t N>
struct is_array<std::array<T, N>> : std::true_type {};
/// A fixed-size Eigen matrix (Vec2, Vec3, Vec6, Mat2): its doubles in storage order.
template <class T>
concept FixedMatrix = requires(T m) {
  { m.data() };
  T::SizeAtCompileTime;
} && (T::SizeAtCompileTime > 0);
template <class T>
concept Scalar = std::is_arithmetic_v<T> || std::is_enum_v<T>;
template <class T, class U>
concept Is = std::same_as<std::remove_const_t<T>, U>;

class Writer {
 public:
  static constexpr bool writing = true;
  std::string out;
  template <class... T>
  void operator()(const T&... v) {
    (put(v), ...);
  }

 private:
  template <class T>
  void put(const T& v);
};

class Reader {
 public:
  static constexpr bool writing = false;
  explicit Reader(std::string_view in) : in_(in) {}
  template <class... T>
  void operator()(T&... v) {
    (get(v), ...);
  }
  std::size_t left() const { return in_.size() - at_; }

 private:
  template <class T>
  void get(T& v);
  void raw(void* p, std::size_t n) {
    if (n > left()) throw std::runtime_error("its payload ends early");
    std::memcpy(p, in_.data() + at_, n);
    at_ += n;
  }
  std::string_view in_;
  std::size_t at_ = 0;
};

/// A tag before each part of the payload: a misplaced byte shows as the wrong part.
void section(Writer& w, const char* name) { w.out += name; }
void section(Reader& r, const char* name) {
  std::string got(std::strlen(name), '\0');
  r(got);
  if (got != name) throw std::runtime_error(fmt::format("its payload lacks the part '{}' where it should be", name));
}

// The structures, one description for both directions.
void io(auto& ar, Is<core::BlockState> auto& b) {
  ar(b.vertices, b.edge_joint_set, b.material, b.centroid, b.stress, b.velocity, b.acceleration, b.mass_scale, b.map_A, b.map_b);
}
void io(auto& ar, Is<core::MeasurementSample> auto& m) { ar(m.step, m.time, m.position, m.displacement); }
void io(auto& ar, Is<core::StoredEnergy> auto& e) {
  ar(e.kinetic, e.strain, e.fixed, e.contact_normal, e.contact_shear, e.bolt);
}
void io(auto& ar, Is<core::EnergyFlows> auto& f) {
  ar(f.work_gravity, f.work_loads, f.work_contact_restart, f.dissipation_friction, f.dissipation_creep,
     f.dissipation_integration, f.integration_inertia, f.dissipation_contact_damping, f.dissipation_block_damping,
     f.dissipation_contact_closing, f.dissipation_contact_release, f.dissipation_bolt, f.dissipation_edits, f.residual,
     f.scale);
}
void io(auto& ar, Is<core::EnergyBalance> auto& e) {
  ar(e.initial, e.stored, e.step, e.total, e.max_relative_residual);
}
void io(auto& ar, Is<core::StageEvent> auto& e) {
  ar(e.kind, e.start_time, e.end_time, e.start_step, e.steps, e.at_rest, e.blocks_involved, e.largest_displacement,
     e.kinetic_energy_peak, e.kinetic_energy_end, e.work, e.energy_dissipated);
}
void io(auto& ar, Is<core::StageState> auto& g) {
  ar(g.until, g.not_before, g.open, g.event, g.motion_kinetic, g.start_vertices);
}
void io(auto& ar, Is<core::SolverState> auto& s) {
  ar(s.amg_failed, s.amg_fallback_solve, s.warm_start, s.pattern, s.positions, s.aggregates, s.coarse_blocks, s.omega);
}
void io(auto& ar, Is<core::EngineState> auto& s) {
  ar(s.step, s.time, s.next_dt, s.blocks);
  // Of each measurement point only its last sample: nothing later depends on
  // the others (history.csv holds them), and they grow with every step.
  std::vector<core::MeasurementSample> last;
  if constexpr (std::remove_reference_t<decltype(ar)>::writing)
    for (const auto& m : s.measurements) last.push_back(m.empty() ? core::MeasurementSample{} : m.back());
  ar(last);
  if constexpr (!std::remove_reference_t<decltype(ar)>::writing) {
    s.measurements.clear();
    for (const auto& m : last) s.measurements.push_back({m});
  }
  ar(s.energy, s.stage, s.events, s.search_displacement, s.solver, s.bolts);
}
void io(auto& ar, Is<core::BoltState> auto& b) {
  ar(b.state, b.force, b.length, b.elongation, b.plastic_elongation, b.rheology, b.rupture_time);
}
void io(auto& ar, Is<contact::ContactKey> auto& k) { ar(k.vblock, k.vertex, k.eblock, k.edge); }
void io(auto& ar, Is<contact::Contact> auto& c) {
  ar(c.id, c.key, c.kind, c.state, c.joint_set, c.length, c.tributary_length, c.locking_ratio, c.slide_direction,
     c.normal_force, c.shear_force, c.shear_displacement, c.penetration, c.intact, c.rheology, c.creep_displacement,
     c.creep_state, c.has_crept, c.creep_failed);
}
void io(auto& ar, Is<laws::RheologyState> auto& r) { ar(r.q, r.damage); }
void io(auto& ar, Is<contact::CreepCounters> auto& k) { ar(k.contacts, k.contact_time, k.failures); }
void io(auto& ar, Is<contact::ContactSystem::StepWork> auto& w) {
  ar(w.pn, w.ps, w.dn0, w.dn, w.st0, w.slip, w.start_state, w.friction, w.normal_damping, w.shear_damping,
     w.solved_state, w.solved_shear_force);
}
void io(auto& ar, Is<contact::ContactSystem::State> auto& s) {
  ar(s.contacts, s.rheology, s.creep, s.work, s.counters, s.penalty, s.allowed_penetration, s.last_max_penetration,
     s.stored_before, s.next_id, s.previous_stress, s.previous_dt, s.creep_error, s.creep_changes);
}
void io(auto& ar, Is<core::ContactChanges> auto& c) {
  ar(c.closed, c.opened, c.slipped, c.stuck, c.refinements, c.cycled, c.cycled_corners);
}
void io(auto& ar, Is<RunResult::StaticMechanism> auto& m) {
  ar(m.static_analysis, m.inertia_share, m.steps, m.first_time, m.first_step, m.last_time, m.collapse_stages);
}
void io(auto& ar, Is<RunTotals> auto& t) {
  ar(t.cuts, t.redone, t.extrapolated, t.max_penetration, t.contact_changes, t.mechanism, t.first_failure, t.settled);
}

template <class T>
void Writer::put(const T& v) {
  if constexpr (Scalar<T>) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  } else if constexpr (Is<T, std::string>) {
    out += v;
  } else if constexpr (FixedMatrix<T>) {
    out.append(reinterpret_cast<const char*>(v.data()), sizeof(double) * T::SizeAtCompileTime);
  } else if constexpr (is_vector<T>::value) {
    put(static_cast<std::uint64_t>(v.size()));
    for (const auto& x : v) put(x);
  } else if constexpr (is_pair<T>::value) {
    put(v.first), put(v.second);
  } else if constexpr (is_array<T>::value) {
    for (const auto& x : v) put(x);
  } else {
    io(*this, v);
  }
}

template <class T>
void Reader::get(T& v) {
  if constexpr (Is<T, bool>) {
    // A flag is a byte of 0 or 1: any other byte copied into a bool would be undefined.
    unsigned char byte = 0;
    raw(&byte, 1);
    if (byte > 1) throw std::runtime_error("its payload holds a flag that is neither 0 nor 1");
    v = byte == 1;
  } else if constexpr (Scalar<T>) {
    raw(&v, sizeof v);
  } else if constexpr (Is<T, std::string>) {
    raw(v.data(), v.size());  // a tag: its length is the caller's
  } else if constexpr (FixedMatrix<T>) {
    raw(v.data(), sizeof(double) * T::SizeAtCompileTime);
  } else if constexpr (is_vector<T>::value) {
    std::uint64_t n = 0;
    get(n);
    // Every element takes a byte or more.
    if (n > left()) throw std::runtime_error("its payload holds a length beyond its end");
    v.resize(static_cast<std::size_t>(n));
    for (auto& x : v) get(x);
  } else if constexpr (is_pair<T>::value) {
    get(v.first), get(v.second);
  } else if constexpr (is_array<T>::value) {
    for (auto& x : v) get(x);
  } else {
    io(*this, v);
  }
}

std::string hex16(std::uint64_t h) { return fmt::format("{:016x}", h); }

/// What the engine and the contacts index by must be in range: the contacts'
/// vertices and edges, the blocks' joint sets (Engine::restore and
/// ContactSystem::restore check the rest against the model).
void check_indices(const SavedRun& run) {
  const auto& blocks = run.engine.blocks;
  auto has = [&](int b, int k) {
    return b >= 0 && b < static_cast<int>(blocks.size()) && k >= 0 &&
           k < static_cast<int>(blocks[b].vertices.size());
  };
  for (const auto& c : run.contacts.contacts)
    if (!has(c.key.vblock, c.key.vertex) || !has(c.key.eblock, c.key.edge))
      throw std::runtime_error(fmt::format("contact {} names a vertex or an edge its blocks do not have", c.id));
  const int joint_sets = static_cast<int>(run.contacts.counters.size());
  for (const auto& b : blocks)
    for (int j : b.edge_joint_set)
      if (j < 0 || j >= joint_sets) throw std::runtime_error(fmt::format("a block edge has joint set {}", j));
}

}  // namespace

std::string encode_state(const SavedRun& run, const std::string& scene_hash) {
  Writer w;
  section(w, "engine");
  w(run.engine);
  section(w, "contacts");
  w(run.contacts);
  section(w, "totals");
  w(run.totals);
  section(w, "end");
  const json header = {{"rheodda_state", kStateFormat},
                       {"program", kProgramVersion},
                       {"scene_hash", scene_hash},
                       {"step", run.engine.step},
                       {"time", fmt::format("{:a}", run.engine.time)},
                       {"byte_order", std::endian::native == std::endian::little ? "little" : "big"},
                       {"payload_bytes", w.out.size()},
                       {"payload_fnv1a", hex16(fnv1a(w.out.data(), w.out.size()))}};
  return header.dump() + "\n" + w.out;
}

SavedRun decode_state(const std::string& bytes, const std::string& path, const std::string& scene_hash) {
  auto refuse = [&](const std::string& what) {
    return std::invalid_argument(
        fmt::format("--resume: {} {}; nothing was changed: run without --resume to start again, or into a new folder",
                    path, what));
  };
  const std::size_t eol = bytes.find('\n');
  json h;
  try {
    if (eol == std::string::npos) throw std::runtime_error("no header line");
    h = json::parse(bytes.substr(0, eol));
    if (!h.is_object() || !h.contains("rheodda_state")) throw std::runtime_error("no format version");
  } catch (const std::exception&) {
    throw refuse("is not a rheodda state file (its first line is not the header)");
  }
  const std::string payload = bytes.substr(eol + 1);
  SavedRun run;
  try {
    const int format = h.at("rheodda_state").get<int>();
    const std::string program = h.at("program").get<std::string>();
    if (format != kStateFormat)
      throw refuse(fmt::format("has state format {} (written by {}); this {} reads format {} only", format,
                               program, kProgramVersion, kStateFormat));
    if (program != kProgramVersion)
      throw refuse(fmt::format("was written by {}; this is {}, whose engine may not continue it the same way",
                               program, kProgramVersion));
    const std::string order = std::endian::native == std::endian::little ? "little" : "big";
    if (h.at("byte_order").get<std::string>() != order)
      throw refuse(fmt::format("was written on a {}-endian machine; this one is {}-endian",
                               h.at("byte_order").get<std::string>(), order));
    if (h.at("scene_hash").get<std::string>() != scene_hash)
      throw refuse(fmt::format("holds the state of another scene (scene hash {}; this scene's text hashes to {})",
                               h.at("scene_hash").get<std::string>(), scene_hash));
    if (h.at("payload_bytes").get<std::uint64_t>() != payload.size())
      throw refuse(fmt::format("is corrupt: its header counts {} bytes of state, the file holds {}",
                               h.at("payload_bytes").get<std::uint64_t>(), payload.size()));
    if (h.at("payload_fnv1a").get<std::string>() != hex16(fnv1a(payload.data(), payload.size())))
      throw refuse("is corrupt: its checksum does not match its contents");
    Reader r(payload);
    section(r, "engine");
    r(run.engine);
    section(r, "contacts");
    r(run.contacts);
    section(r, "totals");
    r(run.totals);
    section(r, "end");
    if (r.left() != 0) throw std::runtime_error(fmt::format("{} bytes follow its end", r.left()));
    check_indices(run);
    if (h.at("step").get<int>() != run.engine.step)
      throw std::runtime_error("its header and its state name other steps");
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    throw refuse(fmt::format("is corrupt: {}", e.what()));
  }
  return run;
}

StateFile write_state_file(const std::string& out_dir, const SavedRun& run, const std::string& scene_hash,
                           const std::string& current) {
  StateFile f;
  f.name = current == kStateFiles[0] ? kStateFiles[1] : kStateFiles[0];
  const std::string text = encode_state(run, scene_hash);
  write_file_atomic((std::filesystem::path(out_dir) / f.name).string(), text, true);
  f.bytes = text.size();
  f.hash = fnv1a(text.data(), text.size());
  return f;
}

SavedRun read_state_file(const std::string& out_dir, const StateFile& entry, const std::string& scene_hash) {
  const std::string path = (std::filesystem::path(out_dir) / entry.name).string();
  if (entry.name != kStateFiles[0] && entry.name != kStateFiles[1])
    throw std::invalid_argument(
        fmt::format("--resume: the checkpoint in {} names '{}' as its state file, which is none of rheodda's; "
                    "nothing was changed: run without --resume to start again, or into a new folder",
                    out_dir, entry.name));
  std::string bytes;
  try {
    bytes = read_file(path);
  } catch (const std::exception& e) {
    throw std::invalid_argument(fmt::format(
        "--resume: the checkpoint's state file cannot be read ({}); nothing was changed: run without --resume to "
        "start again, or into a new folder",
        e.what()));
  }
  SavedRun run = decode_state(bytes, path, scene_hash);
  if (bytes.size() != entry.bytes || fnv1a(bytes.data(), bytes.size()) != entry.hash)
    throw std::invalid_argument(fmt::format(
        "--resume: {} is not the state file the checkpoint recorded ({} bytes, hash {}; it has {} bytes, hash {}): "
        "it was replaced or changed after the checkpoint; nothing was changed: run without --resume to start "
        "again, or into a new folder",
        path, entry.bytes, hex16(entry.hash), bytes.size(), hex16(fnv1a(bytes.data(), bytes.size()))));
  return run;
}

}  // namespace rheodda::scene
