#pragma once
// Word wrap at blanks only, for the tuner's wrapped text. ImGui's TextWrapped also breaks a
// line after '.', ',' and ';', which splits a number such as 0.019375619 over two lines
// ("0." and "019375619"). No ImGui here: the width of a piece of text comes from `measure`
// (tests/ui/text_wrap_test.cpp).
#include <functional>
#include <string>
#include <string_view>

namespace dampbound::ui {

/// `text` with the blank before each word that would cross `width` replaced by a line break
/// ('\n'; a run of blanks there is dropped). Lines break at blanks (spaces and tabs); only a
/// word wider than `width` by itself is split, after a '-' or '/' where one fits, else where
/// it must (between UTF-8 sequences). The text's own '\n' stay breaks. `measure(s)` is the
/// width of `s` on one line, additive (the width of a concatenation is the sum of the widths:
/// ImGui's fonts have no kerning), so each character is measured at most twice: linear time.
std::string wrap_at_blanks(std::string_view text, float width,
                           const std::function<float(std::string_view)>& measure);

/// `text` cut to at most `max_bytes` (between UTF-8 sequences) with "... (N bytes in all)"
/// appended when it was longer: names and descriptions of any length shown in a panel.
std::string shorten(std::string_view text, size_t max_bytes);

/// The most of a scene's name, and of any wrapped text, a panel shows (bytes).
constexpr size_t kShownName = 120;
constexpr size_t kShownDescription = 600;
constexpr size_t kShownText = 4000;

}  // namespace dampbound::ui
