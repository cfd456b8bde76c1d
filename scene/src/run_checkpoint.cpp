// A run's checkpoint and its resume (docs/reference/outputs.md, "Interrupting and
// resuming"; the file formats are checkpoint.cpp's and checkpoint_state.cpp's):
// what a checkpoint counts is synced first, and --resume takes the state up,
// checks every file it continues, and writes lost frames again.
#include <fmt/format.h>

#include <filesystem>

#include "checkpoint.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {

namespace fs = std::filesystem;

void write_checkpoint(Run& run) {
  // What the checkpoint counts must be on disk before the checkpoint is: the
  // CSVs and the state file it names (the frames and blocks.pvd need not:
  // resume writes them again when they are lost).
  run.history.sync();
  run.contacts_csv.sync();
  const StateFile previous = run.state_file;
  run.state_file = write_state_file(run.out, {run.engine.save(), run.contacts.state(), run.run_totals}, run.scene_hash,
                                    previous.name);
  Checkpoint ck;
  ck.scene_hash = run.scene_hash;
  ck.scene_file = run.s.file;
  ck.title = run.s.title;
  ck.step = run.engine.step_count();
  ck.time = run.engine.time();
  ck.wall_seconds = run.earlier_wall + std::chrono::duration<double>(Clock::now() - run.wall_start).count();
  ck.history_bytes = run.history.bytes();
  ck.history_hash = run.history.hash();
  ck.contacts_bytes = run.contacts_csv.bytes();
  ck.contacts_hash = run.contacts_csv.hash();
  ck.frames = run.pvd;
  ck.frame_hashes = run.frame_hash;
  ck.state = run.state_file;
  write_file_atomic(run.checkpoint_path, checkpoint_text(ck), true);
  std::error_code ec;  // the state the previous checkpoint named is needed no more
  if (!previous.name.empty() && previous.name != run.state_file.name) fs::remove(fs::path(run.out) / previous.name, ec);
  run.last_checkpoint = Clock::now();
}

void resume_run(Run& run) {
  const SceneDescription& s = run.s;
  const std::string& out = run.out;
  core::Engine& engine = run.engine;
  contact::ContactSystem& contacts = run.contacts;
  auto& pvd = run.pvd;
  const Checkpoint ck = read_checkpoint(run.checkpoint_path, s.file, run.scene_hash, run.frame_times.size());
  SavedRun saved = read_state_file(out, ck.state, run.scene_hash);
  // Take the saved state up before any file is changed: one that does not fit
  // this scene's model is refused with the folder as it was.
  const core::EngineState start = engine.save();
  const contact::ContactSystem::State start_contacts = contacts.state();
  try {
    if (saved.engine.step != ck.step || saved.engine.time != ck.time)
      throw std::invalid_argument(
          fmt::format("it is of step {}, the checkpoint of step {}", saved.engine.step, ck.step));
    if (saved.totals.first_failure.size() != s.joint_sets.size())
      throw std::invalid_argument(fmt::format("its totals are of {} joint sets, the scene has {}",
                                              saved.totals.first_failure.size(), s.joint_sets.size()));
    engine.restore(saved.engine);
    contacts.restore(saved.contacts);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format(
        "--resume: {} does not fit this run ({}); nothing was changed: run without --resume to start again, or "
        "into a new folder",
        (fs::path(out) / ck.state.name).string(), e.what()));
  }
  run.state_file = ck.state;
  run.frames_done = static_cast<int>(ck.frames.size());
  pvd = ck.frames;
  run.frame_hash = ck.frame_hashes;
  run.earlier_wall = ck.wall_seconds;
  // Every file the run continues must be what the checkpoint recorded.
  run.history.resume((fs::path(out) / "history.csv").string(), ck.history_bytes, ck.history_hash);
  if (run.a.frames)  // analysis.frames: false writes no contacts.csv and no frame files
    run.contacts_csv.resume((fs::path(out) / "contacts.csv").string(), ck.contacts_bytes, ck.contacts_hash);
  std::vector<bool> frame_ok;  // false: missing or changed
  int last_lost = -1;
  for (int k = 0; k < run.frames_done && run.a.frames; ++k) {
    std::string text, layer;
    try {
      text = read_file((fs::path(out) / pvd[k].second).string());
      layer = read_file((fs::path(out) / contacts_file(pvd[k].second)).string());
    } catch (const std::exception&) {
    }
    frame_ok.push_back(!text.empty() && !layer.empty() && frame_pair_hash(text, layer) == run.frame_hash[k]);
    if (!frame_ok.back()) last_lost = k;
  }
  if (last_lost >= 0) {
    // A lost or changed frame can be written again only from the state of its
    // time: the steps up to it are run again from the start (the one case in
    // which a resume computes steps), then the saved state is taken up again.
    auto restore_frame = [&](int k) {
      if (frame_ok[k] || engine.time() != pvd[k].first) return;
      const std::string text = frame_text(run), layer = contacts_frame_text(run);
      if (frame_pair_hash(text, layer) != run.frame_hash[k])
        throw std::runtime_error(
            fmt::format("--resume: running again did not reproduce frame {} ({})", k, pvd[k].second));
      write_file_atomic((fs::path(out) / pvd[k].second).string(), text);
      write_file_atomic((fs::path(out) / contacts_file(pvd[k].second)).string(), layer);
      frame_ok[k] = true;
    };
    engine.restore(start);
    contacts.restore(start_contacts);
    run.mode = Run::Mode::replay;
    run.replay_target = ck.step;
    restore_frame(0);
    int f = 1;  // the frame the steps reach next
    try {
      for (std::size_t k = run.next_output(engine.time()); k < run.frame_times.size() && f <= last_lost;
           k = run.next_output(engine.time())) {
        engine.run_until(run.frame_times[k]);  // as run_to_end: the steps end on the output times
        restore_frame(f++);
      }
    } catch (const StopAfterStep&) {  // at the checkpoint's step: its frame, if it is one
      if (f <= last_lost) restore_frame(f);
    }
    run.mode = Run::Mode::record;
    for (int k = 0; k <= last_lost; ++k)
      if (!frame_ok[k])
        throw std::runtime_error(fmt::format("--resume: frame {} ({}) could not be written again", k, pvd[k].second));
    engine.restore(saved.engine);
    contacts.restore(saved.contacts);
  }
  if (run.a.frames) write_collections(run);
  run.run_totals = std::move(saved.totals);
  run.recorded_step = ck.step;
  run.result.resumed_from_step = ck.step;
  run.note_rows_state();  // the rows of history.csv go on from the checkpoint's step
}

}  // namespace rheodda::scene
