#include "app/answer_lines.hpp"

#include <cstdio>

#include "core/io/format.hpp"

namespace dampbound::app {

void print_answer(const std::vector<std::string>& lines) {
  for (size_t k = 0; k < lines.size(); ++k)
    std::printf("%-13s%s\n", k == 0 ? "answer" : "", lines[k].c_str());
  std::fflush(stdout);  // the answer shows before the evidence's wait
}

void add_brief_flag(CLI::App* cmd, bool& brief) {
  cmd->add_flag("--brief", brief,
                "print only the answer: the verdict, the limits that matter and what to change "
                "(the first lines of the full output)");
}

std::string scene_counts(const ModelSpec& spec, bool anchors) {
  std::string out = plural(spec.node_count(), "node") + ", " + plural(spec.spring_count(), "spring");
  if (anchors) out += ", " + plural(spec.anchor_count(), "anchor");
  return out;
}

}  // namespace dampbound::app
