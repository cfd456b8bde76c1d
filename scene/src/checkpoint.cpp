#include "checkpoint.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "rheodda/scene/output.hpp"
#include "rheodda/version.hpp"

namespace rheodda::scene {
namespace {

using json = nlohmann::ordered_json;

/// Exact text of a double (C99 hex float): times compared bit for bit on resume.
std::string hex(double v) { return fmt::format("{:a}", v); }
double unhex(const std::string& s) { return std::strtod(s.c_str(), nullptr); }
std::string hex16(std::uint64_t h) { return fmt::format("{:016x}", h); }
std::uint64_t unhex16(const std::string& s) { return std::stoull(s, nullptr, 16); }

}  // namespace

std::string checkpoint_text(const Checkpoint& ck) {
  json j;
  j["program"] = kProgramVersion;
  j["scene_hash"] = ck.scene_hash;
  j["scene_file"] = ck.scene_file;
  j["title"] = ck.title;
  j["step"] = ck.step;
  j["time"] = hex(ck.time);
  j["state"] = {{"file", ck.state.name}, {"bytes", ck.state.bytes}, {"hash", hex16(ck.state.hash)}};
  j["frames"] = ck.frames.size();
  j["history_bytes"] = ck.history_bytes;
  j["history_hash"] = hex16(ck.history_hash);
  j["contacts_bytes"] = ck.contacts_bytes;
  j["contacts_hash"] = hex16(ck.contacts_hash);
  j["wall_seconds"] = ck.wall_seconds;
  json frames = json::array();
  for (std::size_t k = 0; k < ck.frames.size(); ++k)
    frames.push_back({hex(ck.frames[k].first), ck.frames[k].second, hex16(ck.frame_hashes[k])});
  j["pvd"] = frames;
  return j.dump(1) + "\n";
}

Checkpoint read_checkpoint(const std::string& path, const std::string& scene_file, const std::string& scene_hash,
                           std::size_t max_frames) {
  const std::string out = std::filesystem::path(path).parent_path().string();
  json j;
  try {
    j = json::parse(read_file(path));
  } catch (const std::exception& e) {
    throw std::invalid_argument(fmt::format("--resume: {} is not a readable checkpoint ({}); run without "
                                            "--resume, or into a new folder",
                                            path, e.what()));
  }
  if (j.value("scene_hash", "") != scene_hash) {
    const std::string other = j.contains("scene_file")
                                  ? fmt::format(" of {} ('{}')", j.value("scene_file", ""), j.value("title", ""))
                                  : std::string();
    throw std::invalid_argument(fmt::format(
        "--resume: {} holds a run{} whose scene text differs from {} (another scene, or the file changed "
        "since): nothing was changed; to keep those results run into a new folder (-o NEW_FOLDER), to "
        "replace them run without --resume",
        out, other, scene_file));
  }
  if (!j.contains("state"))
    throw std::invalid_argument(fmt::format(
        "--resume: {} was written by a rheodda older than {} (it resumed by running the steps again and saved no "
        "state); this one continues from the saved state: nothing was changed; run without --resume to start "
        "again, or resume with the rheodda that wrote it",
        path, kProgramVersion));
  Checkpoint ck;
  ck.scene_hash = scene_hash;
  int frames = 0;
  try {
    ck.scene_file = j.value("scene_file", "");
    ck.title = j.value("title", "");
    ck.step = j.at("step").get<int>();
    ck.time = unhex(j.at("time").get<std::string>());
    frames = j.at("frames").get<int>();
    ck.wall_seconds = j.at("wall_seconds").get<double>();
    ck.history_bytes = j.at("history_bytes").get<std::uint64_t>();
    ck.contacts_bytes = j.at("contacts_bytes").get<std::uint64_t>();
    ck.history_hash = unhex16(j.at("history_hash").get<std::string>());
    ck.contacts_hash = unhex16(j.at("contacts_hash").get<std::string>());
    ck.state.name = j.at("state").at("file").get<std::string>();
    ck.state.bytes = j.at("state").at("bytes").get<std::uint64_t>();
    ck.state.hash = unhex16(j.at("state").at("hash").get<std::string>());
    for (const auto& f : j.at("pvd")) {
      ck.frames.emplace_back(unhex(f.at(0).get<std::string>()), f.at(1).get<std::string>());
      ck.frame_hashes.push_back(unhex16(f.at(2).get<std::string>()));
    }
  } catch (const std::exception& e) {
    throw std::invalid_argument(fmt::format("--resume: {} lacks what a resume needs ({}); run without --resume, "
                                            "or into a new folder",
                                            path, e.what()));
  }
  if (frames < 1 || static_cast<std::size_t>(frames) != ck.frames.size() || ck.frames.size() > max_frames)
    throw std::invalid_argument(
        fmt::format("--resume: {} is inconsistent (frames {}, listed {}); run without --resume, or into a new folder",
                    path, frames, ck.frames.size()));
  return ck;
}

}  // namespace rheodda::scene
