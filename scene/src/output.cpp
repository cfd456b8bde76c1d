#include "rheodda/scene/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rheodda::scene {

std::string write_error(const std::string& path, int error_number) {
  std::string msg = fmt::format("cannot write {}: {}", path, std::strerror(error_number));
  if (error_number == ENOSPC || error_number == EDQUOT)
    msg += fmt::format(" (free space in {} and run again; the outputs so far are kept)",
                       std::filesystem::path(path).parent_path().string());
  return msg;
}

void sync_directory(const std::string& path) {
  const int fd = ::open(path.empty() ? "." : path.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void write_file_atomic(const std::string& path, const std::string& content, bool durable) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(write_error(path, errno));
  int error = 0;
  for (std::size_t done = 0; done < content.size() && !error;) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno != EINTR) error = errno;
    if (n > 0) done += static_cast<std::size_t>(n);
  }
  if (!error && durable && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && !error) error = errno;
  std::error_code ec;
  if (!error) {
    std::filesystem::rename(tmp, path, ec);
    if (ec) error = ec.value();
  }
  if (error) {
    std::filesystem::remove(tmp, ec);  // never leave a .tmp behind
    throw std::runtime_error(write_error(path, error));
  }
  if (durable) sync_directory(std::filesystem::path(path).parent_path().string());
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}: {}", path, std::strerror(errno)));
  std::ostringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

void remove_run_outputs(const std::string& dir) {
  namespace fs = std::filesystem;
  static const char* const kFiles[] = {"history.csv", "contacts.csv", "bolts.csv",  "events.csv",
                                       "blocks.pvd",  "contacts.pvd", "bolts.pvd",  "summary.json",
                                       "checkpoint.json"};
  auto remove = [](const fs::path& p) {
    std::error_code ec;
    fs::remove(p, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot remove {} of the earlier run: {}", p.string(), ec.message()));
  };
  auto ends_with = [](const std::string& name, const std::string& tail) {
    return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
  };
  const fs::path d(dir);
  for (const char* f : kFiles) {
    remove(d / f);
    remove(d / (std::string(f) + ".tmp"));
  }
  // The saved states (checkpoint-N.state) and the folders of frames and pictures.
  auto sweep = [&](const fs::path& folder, auto&& written) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return;
    std::vector<fs::path> doomed;
    for (const auto& e : fs::directory_iterator(folder, ec))
      if (e.is_regular_file(ec) && written(e.path().filename().string())) doomed.push_back(e.path());
    for (const auto& p : doomed) remove(p);
  };
  sweep(d, [&](const std::string& n) {
    return n.rfind("checkpoint-", 0) == 0 && (ends_with(n, ".state") || ends_with(n, ".state.tmp"));
  });
  sweep(d / "frames", [&](const std::string& n) { return ends_with(n, ".vtp") || ends_with(n, ".vtp.tmp"); });
  sweep(d / "plots", [&](const std::string& n) {
    for (const char* ext : {".png", ".svg", ".gp", ".dat"})
      if (ends_with(n, ext) || ends_with(n, std::string(ext) + ".tmp")) return true;
    return false;
  });
  std::error_code ec;
  if (fs::is_directory(d / "plots", ec) && fs::is_empty(d / "plots", ec)) fs::remove(d / "plots", ec);
}

namespace {

/// True when process `pid` runs on this machine (or cannot be told apart from one that does).
bool process_lives(long pid) {
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
}

/// The process id a lock file holds (0 when it holds none).
long lock_owner(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return 0;
  char* end = nullptr;
  const long pid = std::strtol(buf, &end, 10);
  return end != buf ? pid : 0;
}

}  // namespace

FolderLock::FolderLock(const std::string& dir) {
  path_ = (std::filesystem::path(dir) / ".rheodda.lock").string();
  // A lock file is removed when its run ends (~FolderLock): a run that opened it just
  // before may then hold a file no longer in the folder, so it checks after locking that
  // the name still leads to the file it locked, and otherwise starts again.
  for (int attempt = 0;; ++attempt) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error(write_error(path_, errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      if (error == EINTR) {  // a signal came: try again
        ::close(fd_);
        fd_ = -1;
        continue;
      }
      const long owner = lock_owner(fd_);
      // A folder whose file system has no flock (some network mounts): the process id in
      // the file decides; one that no longer runs left a stale lock, taken over here.
      const bool no_flock = error != EWOULDBLOCK;
      if (!no_flock || process_lives(owner)) {
        ::close(fd_);
        fd_ = -1;
        throw std::runtime_error(fmt::format(
            "{} is in use by another rheodda run{}: wait for it to end, or give this run another folder (-o)", dir,
            owner > 0 ? fmt::format(" (process {})", owner) : std::string()));
      }
    }
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
        held.st_ino == named.st_ino)
      break;
    ::close(fd_);
    fd_ = -1;
    if (attempt == 100) throw std::runtime_error(fmt::format("cannot lock {}: it keeps being replaced", path_));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The process id is for the message of a second run and to tell a stale lock only.
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  // The run has ended (completed, stopped, failed): its lock file goes, the outputs stay.
  // Only the file this run holds: while it is held no other run can have replaced it.
  struct stat held {}, named {};
  if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
      held.st_ino == named.st_ino)
    ::unlink(path_.c_str());
  ::close(fd_);  // releases the flock
}

void CsvAppender::create(const std::string& path) {
  path_ = path;
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw std::runtime_error(write_error(path, errno));
  bytes_ = 0;
  hash_ = fnv1a(nullptr, 0);
}

void CsvAppender::resume(const std::string& path, std::uint64_t keep_bytes, std::uint64_t keep_hash) {
  path_ = path;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec)
    throw std::runtime_error(fmt::format("--resume: cannot continue {}: {}", path, ec.message()));
  if (size < keep_bytes)
    throw std::invalid_argument(fmt::format(
        "--resume: {} has {} bytes but the checkpoint counts {} (the file was cut or replaced after the "
        "checkpoint); nothing was changed: run again without --resume, or into a new folder",
        path, size, keep_bytes));
  // Hash the kept bytes, reading them in blocks.
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) throw std::runtime_error(fmt::format("--resume: cannot read {}: {}", path, std::strerror(errno)));
  std::uint64_t h = fnv1a(nullptr, 0), left = keep_bytes;
  std::vector<char> buf(1 << 20);
  while (left > 0) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(left, buf.size()));
    const std::size_t got = std::fread(buf.data(), 1, want, in);
    if (got == 0) break;
    h = fnv1a(buf.data(), got, h);
    left -= got;
  }
  std::fclose(in);
  if (left != 0 || h != keep_hash)
    throw std::invalid_argument(fmt::format(
        "--resume: the first {} bytes of {} differ from those the checkpoint recorded (the file was "
        "changed after the checkpoint); nothing was changed: run again without --resume, or into a new folder",
        keep_bytes, path));
  // Drop whatever was appended after the checkpoint: it is rewritten identically.
  std::filesystem::resize_file(path, keep_bytes, ec);
  if (ec) throw std::runtime_error(write_error(path, ec.value()));
  f_ = std::fopen(path.c_str(), "ab");
  if (!f_) throw std::runtime_error(write_error(path, errno));
  bytes_ = keep_bytes;
  hash_ = h;
}

CsvAppender::~CsvAppender() {
  if (f_) std::fclose(f_);
}

void CsvAppender::append(const std::string& line) {
  errno = 0;
  if (std::fwrite(line.data(), 1, line.size(), f_) != line.size() || std::fflush(f_) != 0)
    throw std::runtime_error(write_error(path_, errno ? errno : EIO));
  bytes_ += line.size();
  hash_ = fnv1a(line.data(), line.size(), hash_);
}

void CsvAppender::sync() {
  if (!f_) return;
  if (std::fflush(f_) != 0 || ::fsync(::fileno(f_)) != 0) throw std::runtime_error(write_error(path_, errno));
}

std::string vtk_polydata(const std::vector<FrameBlock>& blocks) {
  std::size_t npoints = 0;
  for (const auto& b : blocks) npoints += b.vertices.size();
  std::string s;
  s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  s += fmt::format("<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfPolys=\"{}\">\n", npoints, blocks.size());
  s += "<Points>\n<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& b : blocks)
    for (const auto& v : b.vertices) s += fmt::format("{:.17g} {:.17g} 0\n", v[0], v[1]);
  s += "</DataArray>\n</Points>\n<PointData Vectors=\"displacement\">\n";
  s += "<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& b : blocks)
    for (const auto& d : b.displacement) s += fmt::format("{:.17g} {:.17g} 0\n", d[0], d[1]);
  s += "</DataArray>\n</PointData>\n<CellData>\n";
  s += "<DataArray type=\"Int32\" Name=\"block\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < blocks.size(); ++i) s += fmt::format("{}\n", i);
  s += "</DataArray>\n<DataArray type=\"Int32\" Name=\"material\" format=\"ascii\">\n";
  for (const auto& b : blocks) s += fmt::format("{}\n", b.material);
  s += "</DataArray>\n<DataArray type=\"Int32\" Name=\"fixed\" format=\"ascii\">\n";
  for (const auto& b : blocks) s += fmt::format("{}\n", b.fixed ? 1 : 0);
  if (std::any_of(blocks.begin(), blocks.end(), [](const FrameBlock& b) { return b.removed.has_value(); })) {
    s += "</DataArray>\n<DataArray type=\"Int32\" Name=\"removed\" format=\"ascii\">\n";
    for (const auto& b : blocks) s += fmt::format("{}\n", b.removed.value_or(false) ? 1 : 0);
  }
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"stress\" NumberOfComponents=\"3\" "
       "ComponentName0=\"sigma_x\" ComponentName1=\"sigma_y\" ComponentName2=\"tau_xy\" format=\"ascii\">\n";
  for (const auto& b : blocks) s += fmt::format("{:.17g} {:.17g} {:.17g}\n", b.stress[0], b.stress[1], b.stress[2]);
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
       "ComponentName0=\"vx\" ComponentName1=\"vy\" ComponentName2=\"omega\" format=\"ascii\">\n";
  for (const auto& b : blocks)
    s += fmt::format("{:.17g} {:.17g} {:.17g}\n", b.velocity[0], b.velocity[1], b.velocity[2]);
  s += "</DataArray>\n</CellData>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  std::size_t k = 0;
  for (const auto& b : blocks) {
    for (std::size_t i = 0; i < b.vertices.size(); ++i) s += fmt::format("{}{}", i ? " " : "", k + i);
    s += '\n';
    k += b.vertices.size();
  }
  s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  k = 0;
  for (const auto& b : blocks) {
    k += b.vertices.size();
    s += fmt::format("{}\n", k);
  }
  s += "</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return s;
}

std::string vtk_contacts(const std::vector<FrameContact>& contacts) {
  const std::size_t n = contacts.size();
  std::string s;
  s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  s += fmt::format("<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\">\n", n, n);
  s += "<Points>\n<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& c : contacts) s += fmt::format("{:.17g} {:.17g} 0\n", c.point[0], c.point[1]);
  s += "</DataArray>\n</Points>\n<PointData>\n";
  auto ints = [&](const char* name, auto field) {
    s += fmt::format("<DataArray type=\"Int32\" Name=\"{}\" format=\"ascii\">\n", name);
    for (const auto& c : contacts) s += fmt::format("{}\n", field(c));
    s += "</DataArray>\n";
  };
  auto reals = [&](const char* name, auto field) {
    s += fmt::format("<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
    for (const auto& c : contacts) s += fmt::format("{:.17g}\n", field(c));
    s += "</DataArray>\n";
  };
  ints("id", [](const FrameContact& c) { return c.id; });
  ints("joint_set", [](const FrameContact& c) { return c.joint_set; });
  ints("state", [](const FrameContact& c) { return c.state; });
  ints("kind", [](const FrameContact& c) { return c.kind; });
  reals("normal_force", [](const FrameContact& c) { return c.normal_force; });
  reals("shear_force", [](const FrameContact& c) { return c.shear_force; });
  reals("shear_strength", [](const FrameContact& c) { return c.shear_strength; });
  reals("shear_displacement", [](const FrameContact& c) { return c.shear_displacement; });
  reals("creep_displacement", [](const FrameContact& c) { return c.creep_displacement; });
  reals("penetration", [](const FrameContact& c) { return c.penetration; });
  reals("length", [](const FrameContact& c) { return c.length; });
  reals("tributary_length", [](const FrameContact& c) { return c.tributary_length; });
  if (!contacts.empty() && contacts.front().water_pressure)  // scenes with water (docs/reference/water.md)
    reals("water_pressure", [](const FrameContact& c) { return c.water_pressure.value_or(0.0); });
  s += "</PointData>\n<Verts>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) s += fmt::format("{}\n", i);
  s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) s += fmt::format("{}\n", i + 1);
  s += "</DataArray>\n</Verts>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return s;
}

std::string vtk_collection(const std::vector<std::pair<double, std::string>>& frames) {
  std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, file] : frames)
    s += fmt::format("<DataSet timestep=\"{:.17g}\" part=\"0\" file=\"{}\"/>\n", t, file);
  s += "</Collection>\n</VTKFile>\n";
  return s;
}

namespace {
/// The numbers of the DataArray named `name` in `text`.
std::vector<double> data_array(const std::string& text, const std::string& name, const std::string& path) {
  const std::size_t at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) throw std::runtime_error(fmt::format("{}: no DataArray '{}'", path, name));
  const std::size_t start = text.find('>', at);
  const std::size_t end = text.find("</DataArray>", start);
  std::istringstream in(text.substr(start + 1, end - start - 1));
  std::vector<double> out;
  double v;
  while (in >> v) out.push_back(v);
  return out;
}
}  // namespace

std::vector<FrameBlock> read_vtk_polydata(const std::string& path) {
  const std::string text = read_file(path);
  const auto pts = data_array(text, "Points", path);
  const auto disp = data_array(text, "displacement", path);
  const auto offsets = data_array(text, "offsets", path);
  const auto conn = data_array(text, "connectivity", path);
  const auto fixed = data_array(text, "fixed", path);
  // A scene with stages flags its removed blocks (docs/reference/stages.md); the others have no such array.
  const bool staged = text.find("Name=\"removed\"") != std::string::npos;
  const auto removed = staged ? data_array(text, "removed", path) : std::vector<double>{};
  std::vector<FrameBlock> out;
  std::size_t begin = 0;
  for (std::size_t b = 0; b < offsets.size(); ++b) {
    FrameBlock fb;
    const auto end = static_cast<std::size_t>(offsets[b]);
    for (std::size_t k = begin; k < end && k < conn.size(); ++k) {
      const auto p = static_cast<std::size_t>(conn[k]);
      if (3 * p + 1 >= pts.size() || 3 * p + 1 >= disp.size())
        throw std::runtime_error(fmt::format("{}: point index out of range", path));
      fb.vertices.push_back({pts[3 * p], pts[3 * p + 1]});
      fb.displacement.push_back({disp[3 * p], disp[3 * p + 1]});
    }
    fb.fixed = b < fixed.size() && fixed[b] != 0.0;
    if (staged) fb.removed = b < removed.size() && removed[b] != 0.0;
    out.push_back(std::move(fb));
    begin = end;
  }
  return out;
}

std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace rheodda::scene
