#include "app/command.h"

#include <cstdio>
#include <stdexcept>

#include "common/numbers.h"

namespace wb::app {
namespace {

// Every numeric flag of `app` and its subcommands takes decimal numbers only: CLI11 reads integers with
// strtoull(base 0) ("0x10" is 16, "010" is 8, "-1" wraps to 2^64 - 1) and floating point with strtold ("nan",
// "inf", hexadecimal).
void requireDecimalNumbers(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    const std::string type = o->get_type_name().substr(0, o->get_type_name().find(':'));
    const bool isUnsigned = type == "UINT", isInteger = type == "INT", isFloat = type == "FLOAT";
    if (!isUnsigned && !isInteger && !isFloat) continue;
    o->transform(CLI::Validator(
        [=](std::string& text) -> std::string {
          if (isUnsigned ? parseDecimalUnsigned(text).has_value() : parseDecimal(text).has_value()) {
            if (isFloat) return "";
            if (text.find_first_of(".eE") == std::string::npos) {
              // Leading zeros go: CLI11 would read "010" as octal 8.
              const size_t sign = text[0] == '-' || text[0] == '+' ? 1 : 0;
              const size_t digits = text.find_first_not_of('0', sign);
              text.erase(sign, digits == std::string::npos ? text.size() - sign - 1 : digits - sign);
              return "";
            }
          }
          return "'" + text + "' is not a " +
                 (isUnsigned  ? "non-negative decimal integer"
                  : isInteger ? "decimal integer"
                              : "finite decimal number");
        },
        ""));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) requireDecimalNumbers(*sub);
}

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
    requireDecimalNumbers(app);
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
