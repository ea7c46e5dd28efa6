#pragma once
// What the command line says when a flag is wrong: an unknown flag with the nearest known
// one, an empty value refused with its flag, a whole number out of its range with the range.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace dampbound::app {

/// The known name nearest to `word` by edit distance (insertions, deletions, substitutions,
/// swaps of neighbours), when it is close enough to be a misspelling (at most 2 edits, and
/// fewer than half the word); nullopt otherwise.
std::optional<std::string> nearest_name(const std::string& word,
                                        const std::vector<std::string>& names);

/// For CLI11's "arguments were not expected": one line naming the first unknown flag among
/// `args` (those after the program name) for the subcommand it follows, with the nearest
/// option of that subcommand or of the root; nullopt when no word of `args` is an unknown flag.
std::optional<std::string> unknown_flag_message(const CLI::App& root,
                                                const std::vector<std::string>& args);

/// Throws InputError naming the first option of `cmd` (or of the root `cmd` belongs to) that
/// was given an empty value: `--trace ""` would otherwise be read as no trace at all.
void refuse_empty_values(const CLI::App& cmd);

/// A whole number in [lo, hi]: "'abc' is not a whole number from 1 to 100000000" instead
/// of CLI11's "Value abc not in range".
CLI::Validator whole_range(long long lo, long long hi);
/// A finite number in [lo, hi], said in the same words.
CLI::Validator number_range(double lo, double hi);

}  // namespace dampbound::app
