#include "tools/cli/every_command.h"

#include "tools/cli/continue.h"

namespace metrosync::cli {

const std::vector<std::vector<std::string>>& EveryCommand::groups() {
  static const std::vector<std::vector<std::string>> kGroups = {{"run", "compare", "scale"},
                                                                {"sweep", "merge"},
                                                                {"validate"},
                                                                {"continue"},
                                                                {"fit"},
                                                                {"measure"},
                                                                {"figures"},
                                                                {"animate"},
                                                                {"basin"},
                                                                {"sweep-point"}};
  return kGroups;
}

std::vector<Command> EveryCommand::addGroup(CLI::App& app, size_t group) {
  switch (group) {
    case 0:
      return addRigCommands(app, opt_);
    case 1: {
      const SweepCommands sweep = addSweepCommands(app, sweep_);
      return {{sweep.sweep, [this] { return sweepCommand(sweep_); }},
              {sweep.merge, [this] { return mergeCommand(sweep_); }}};
    }
    case 2:
      return {{addValidateCommand(app, validate_), [this] { return validateCommand(validate_); }}};
    case 3:
      return {{addContinueCommand(app), [] { return continueCommand(); }}};
    case 4:
      return {{addFitCommand(app, fit_), [this] { return fitCommand(fit_); }}};
    case 5:
      return {{addMeasureCommand(app, measure_), [this] { return measureCommand(measure_); }}};
    case 6:
      return {{addFiguresCommand(app, figures_), [this] { return figuresCommand(figures_); }}};
    case 7:
      return {{addAnimateCommand(app, animate_), [this] { return animateCommand(animate_); }}};
    case 8:
      return {{addBasinCommand(app, basin_), [this] { return basinCommand(basin_); }}};
    case 9:
      return {{addSweepPointCommand(app, point_), [this] { return sweepPointCommand(point_); }}};
    default:
      return {};
  }
}

std::vector<Command> EveryCommand::addAll(CLI::App& app) {
  std::vector<Command> commands;
  for (size_t g = 0; g < groups().size(); ++g)
    for (Command& c : addGroup(app, g)) commands.push_back(std::move(c));
  return commands;
}

std::vector<Command> EveryCommand::add(CLI::App& app, int argc, char** argv) {
  if (argc >= 2)
    for (size_t g = 0; g < groups().size(); ++g)
      for (const std::string& name : groups()[g])
        if (name == argv[1]) return addGroup(app, g);
  return addAll(app);
}

}  // namespace metrosync::cli
