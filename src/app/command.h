// The workbench's commands share one parse: main() builds one CLI11 app, the live window's flags on it and a
// subcommand per command (`render`, `shaders`, `watch`, `converge`, `bench`), parses once, and runs the
// command given. Each command adds its flags, checks what was parsed and runs.
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace wb::app {

class Command {
 public:
  virtual ~Command() = default;
  // The subcommand's name ("render"; the live window, run without one, has none) and its help line.
  virtual const char* name() const = 0;
  virtual const char* description() const = 0;
  virtual void addFlags(CLI::App& app) = 0;
  // Checks and converts what was parsed, and that the outputs can be written; throws (std::invalid_argument,
  // std::runtime_error) with a one-line reason naming the flag.
  virtual void finish() {}
  // The command run without a subcommand sees the first argument before parsing, to tell a mistyped
  // command from a scene. Throws std::invalid_argument.
  virtual void checkFirstWord(const std::string& word) { (void)word; }
  virtual int run() = 0;

  // The arguments as typed after the command's name (reports record the command line).
  std::vector<std::string> args;
};

// Exit statuses of a command line that did not run: help was asked for (0), or the flags were wrong (2).
inline constexpr int kUsageError = 2;

// Parses `args` (everything after the program name) for `app`, whose flags belong to `commands` (the default
// command first, or nullptr, then the subcommands in the order they were added), and runs the command given.
// The one place that turns parse and validation errors into a message and an exit status.
int parseAndRun(CLI::App& app, const std::vector<std::string>& args, Command* defaultCommand,
                const std::vector<Command*>& subcommands);

// One command alone, as `workbench NAME args...` (the tests and helper binaries call commands this way).
int runCommand(Command& command, const std::vector<std::string>& args);

}  // namespace wb::app
