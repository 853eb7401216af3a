// The one reader of the process environment: every variable the workbench reads or sets goes through here,
// so the list of them is one grep (docs/ENVIRONMENT.md documents each).
#pragma once
#include <optional>
#include <string>

namespace wb::env {

// The variable's value; nullopt when it is unset or empty (a parent process hands a choice back to the
// default by setting the variable empty).
std::optional<std::string> get(const char* name);
// "1" -> true, "0" -> false; nullopt when unset, empty or anything else (the default applies).
std::optional<bool> choice(const char* name);
// On unless unset, empty or "0" (WB_VALIDATION=1 style switches).
bool enabled(const char* name);
// A number (nullopt when unset, empty or not a number).
std::optional<double> number(const char* name);
// Sets the variable for this process and the programs it starts.
void set(const char* name, const std::string& value);

}  // namespace wb::env
