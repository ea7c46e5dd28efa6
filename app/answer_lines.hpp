#pragma once
// The answer-first block of bounds, suggest and run (core/analysis/answer.hpp builds the
// lines; this prints them and adds --brief), and the counts of a scene's line.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "dampbound/physics/model.hpp"

namespace dampbound::app {

/// "answer       line 1" then each further line under it; nothing for no line.
void print_answer(const std::vector<std::string>& lines);

/// Adds --brief (print only the answer) to `cmd`.
void add_brief_flag(CLI::App* cmd, bool& brief);

/// "2 nodes, 1 spring, 0 anchors" (`anchors` false leaves them out).
std::string scene_counts(const ModelSpec& spec, bool anchors = true);

}  // namespace dampbound::app
