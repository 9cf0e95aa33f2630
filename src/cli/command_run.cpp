// hullmesh run JOB.json [OPTIONS...]: a meshing command from a job file. Options typed after the
// job file override its keys.
#include <filesystem>

#include "cli/commands.h"
#include "cli/execute.h"
#include "cli/job_file.h"

namespace hm::cli {

void register_run(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto job = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Run a meshing command from a JSON job file (option names as keys; options typed "
      "after the file override it)");
  cmd->add_option("job", *job, "JSON job file")->required()->check(CLI::ExistingFile);
  // Every word after the job file is an override for the job's command, even a global option.
  cmd->prefix_command();
  cmd->fallthrough(false);
  cmd->callback([cmd, job, &global, &action] {
    const std::vector<std::string> overrides = cmd->remaining();
    action = [job, overrides, &global] {
      const std::string folder = std::filesystem::path(*job).parent_path().string();
      const auto args = job_arguments(read_json_file(*job), *job, folder, overrides);
      ExecuteOptions o;
      o.force_quiet = global.quiet;
      o.write_record = !global.no_record;
      o.validate = global.validate;
      return execute_args(args, *job, o).exit_code;
    };
  });
}

}  // namespace hm::cli
