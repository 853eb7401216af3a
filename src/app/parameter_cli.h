// The command-line flags of every parameter (render/parameters.h), for each command that renders: CLI11
// keeps the texts, apply() validates them through the registry after parsing.
#pragma once
#include <deque>
#include <string>

#include <CLI/CLI.hpp>

#include "render/parameters.h"

namespace wb::app {

class ParameterFlags {
 public:
  // Adds every parameter that has a flag; `defaults` fill the help's default values.
  void addTo(CLI::App& app, const render::Parameters& defaults);
  // Applies the flags given on the command line, then checks the rules between parameters. Throws
  // std::invalid_argument naming the flag.
  void apply(render::Parameters& values) const;
  bool given(const std::string& name) const;

 private:
  struct Flag {
    const render::ParameterInfo* info = nullptr;
    CLI::Option* option = nullptr;
    std::string text;
    bool present = false;  // Bool flags
  };
  std::deque<Flag> flags_;  // stable addresses: CLI11 writes into them
};

}  // namespace wb::app
