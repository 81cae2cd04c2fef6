// SPDX-License-Identifier: MIT
// The subcommands of `pluecker`: each in its own file, each returns the exit
// status and throws InputError for bad input (main.cpp prints it).
#pragma once

#include "pluecker/app/args.hpp"

#include <string>
#include <vector>

namespace pluecker::cli {

// The applications' parser and option helpers (pluecker/app/).
using namespace pluecker::app;

int cmd_query(const std::vector<std::string>& argv);
int cmd_render(const std::vector<std::string>& argv);
int cmd_trace(const std::vector<std::string>& argv);
int cmd_plan(const std::vector<std::string>& argv);
int cmd_study(const std::vector<std::string>& argv);
int cmd_contract(const std::vector<std::string>& argv);
int cmd_cascade(const std::vector<std::string>& argv);
int cmd_accuracy(const std::vector<std::string>& argv);

}  // namespace pluecker::cli
