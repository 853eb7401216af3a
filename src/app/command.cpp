#include "app/command.h"

#include <cstdio>
#include <stdexcept>

namespace wb::app {
namespace {

// "workbench render" for the subcommand that was being parsed, else "workbench".
std::string label(CLI::App& app, const std::vector<Command*>& subcommands, const Command* single) {
  for (Command* c : subcommands)
    if (app.get_subcommand(c->name())->parsed()) return std::string("workbench ") + c->name();
  return single && *single->name() ? std::string("workbench ") + single->name() : "workbench";
}

}  // namespace

int parseAndRun(CLI::App& app, const std::vector<std::string>& args, Command* defaultCommand,
                const std::vector<Command*>& subcommands) {
  Command* chosen = defaultCommand;
  CLI::App* chosenApp = &app;
  try {
    if (defaultCommand && !args.empty()) defaultCommand->checkFirstWord(args.front());
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    app.parse(reversed);
    for (Command* c : subcommands) {
      if (CLI::App* sub = app.get_subcommand(c->name()); sub->parsed()) {
        chosen = c;
        chosenApp = sub;
      }
    }
    if (!chosen) throw CLI::CallForHelp();
    chosen->args.clear();
    bool inside = chosen == defaultCommand;
    for (const auto& a : args) {
      if (inside) chosen->args.push_back(a);
      if (!inside && a == chosen->name()) inside = true;
    }
    chosen->finish();
  } catch (const CLI::CallForHelp&) {
    for (const CLI::App* sub : app.get_subcommands({}))
      if (sub->parsed()) chosenApp = const_cast<CLI::App*>(sub);
    std::printf("%s", chosenApp->help().c_str());
    return 0;
  } catch (const CLI::ParseError& e) {
    const std::string l = label(app, subcommands, defaultCommand);
    std::fprintf(stderr, "%s: error: %s (see '%s --help')\n", l.c_str(), e.what(), l.c_str());
    return kUsageError;
  } catch (const std::exception& e) {  // finish(): a bad value, an output that cannot be written
    std::fprintf(stderr, "%s: error: %s\n", label(app, subcommands, defaultCommand).c_str(), e.what());
    return kUsageError;
  }
  return chosen->run();
}

int runCommand(Command& command, const std::vector<std::string>& args) {
  CLI::App app(command.description(), std::string("workbench ") + command.name());
  command.addFlags(app);
  return parseAndRun(app, args, &command, {});
}

}  // namespace wb::app
