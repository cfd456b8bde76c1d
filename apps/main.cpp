// rheodda: contact rheology in Discontinuous Deformation Analysis.
// Sample runs:
//   rheodda --version
//   rheodda law list
//   rheodda check examples/goodman-toppling-creep.yaml --refine -j 2
//   rheodda generate examples/rockmass/jointed-slope.yaml -o out/jointed-slope-explicit.yaml
//   rheodda law curve burgers --param E1=26.87 --param E2=192.43 --param eta1=34807.72
//       --param eta2=2141.23 --force 0:0.232 --t-end 200 --dt 1
#include <fmt/format.h>

#include <exception>
#include <functional>
#include <new>

#include "commands.hpp"
#include "rheodda/scene/error.hpp"
#include "rheodda/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rheodda: creep of jointed rock with contact rheology laws in DDA"};
  app.require_subcommand(1);
  // The same string as summary.json's "program" (rheodda/version.hpp, from CMake's project()).
  app.set_version_flag("--version", rheodda::kProgramVersion, "Print the version (rheodda X.Y.Z) and exit");
  rheodda::apps::add_law_commands(app);
  rheodda::apps::add_check_command(app);
  rheodda::apps::add_keys_command(app);
  rheodda::apps::add_scene_commands(app);
  rheodda::apps::add_fit_command(app);
  rheodda::apps::add_study_command(app);
  rheodda::apps::add_generate_command(app);
  rheodda::apps::add_forecast_command(app);
  // The exit codes once, in `rheodda --help` (and docs/reference/cli.md); each command's
  // help refers to them in one line (a command made before app.footer() would copy it).
  app.footer(rheodda::apps::kExitCodesHelp);
  const std::function<void(CLI::App&)> refer = [&refer](CLI::App& parent) {
    for (CLI::App* command : parent.get_subcommands({})) {
      command->footer(rheodda::apps::kExitCodesLine);
      refer(*command);
    }
  };
  refer(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own exit code (e.g. 1: run failed)
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : rheodda::apps::kExitBadInput;
  } catch (const rheodda::scene::SceneError& e) {
    // A fault with no place in the file (line 0) is reported by file name alone, not as FILE:0:0.
    if (e.line() > 0)
      fmt::print(stderr, "rheodda: error: {}\n", e.what());
    else
      fmt::print(stderr, "rheodda: error: {}: {}{}\n", e.file(), e.key().empty() ? "" : e.key() + ": ", e.message());
    return rheodda::apps::kExitBadInput;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "rheodda: error: out of memory: the input asks for more memory than is available\n");
    return rheodda::apps::kExitFailure;
  } catch (const std::exception& e) {
    fmt::print(stderr, "rheodda: error: {}\n", e.what());
    return rheodda::apps::kExitBadInput;
  }
  return 0;
}
