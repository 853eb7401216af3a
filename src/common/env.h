// The one reader of the process environment: every variable the workbench reads or sets goes through here,
// so the list of them is one grep (docs/ENVIRONMENT.md documents each). A value the workbench cannot take is
// an error naming the variable, never a silent default.
#pragma once
#include <optional>
#include <string>

namespace wb::env {

// The variable's value; nullopt when it is unset or empty (a parent process hands a choice back to the
// default by setting the variable empty).
std::optional<std::string> get(const char* name);
// "1" -> true, "0" -> false; nullopt when unset or empty (the default applies). Anything else throws
// std::invalid_argument naming the variable.
std::optional<bool> choice(const char* name);
// A switch off by default: true for "1", false when unset, empty or "0"; anything else throws as choice().
bool enabled(const char* name);
// A finite decimal number (nullopt when unset or empty); anything else throws std::invalid_argument naming
// the variable.
std::optional<double> number(const char* name);
// Sets the variable for this process and the programs it starts.
void set(const char* name, const std::string& value);

// Checks every WB_* switch and number the workbench reads (the paths are checked where they are used), so
// that a bad value is refused when the process starts, before any work. Throws std::invalid_argument naming
// the variable, its value and what it takes.
void checkWorkbenchVariables();

}  // namespace wb::env
