#include "ui/plot.hpp"

#include "ui/fonts.hpp"
#include "ui/gui_items.hpp"
#include "ui/plot_draw.hpp"
#include "ui/text_wrap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace dampbound::ui {

using detail::TextFont;

ImU32 palette_color(int i) {
  // A qualitative 10-colour palette (blue, orange, green, red, purple, brown, pink, grey,
  // olive, cyan), readable on white and on dark grey.
  static const ImU32 kColors[10] = {
      IM_COL32(31, 119, 180, 255), IM_COL32(255, 127, 14, 255), IM_COL32(44, 160, 44, 255),
      IM_COL32(214, 39, 40, 255),  IM_COL32(148, 103, 189, 255), IM_COL32(140, 86, 75, 255),
      IM_COL32(227, 119, 194, 255), IM_COL32(127, 127, 127, 255), IM_COL32(188, 189, 34, 255),
      IM_COL32(23, 190, 207, 255)};
  return kColors[((i % 10) + 10) % 10];
}

ImU32 with_alpha(ImU32 color, int alpha) {
  const ImU32 a = static_cast<ImU32>(std::clamp(alpha, 0, 255));
  return (color & ~IM_COL32_A_MASK) | (a << IM_COL32_A_SHIFT);
}

PlotStyle plot_style_light() {
  PlotStyle s;
  s.background = IM_COL32(255, 255, 255, 255);
  s.plot_background = IM_COL32(255, 255, 255, 255);
  s.frame = IM_COL32(60, 60, 60, 255);
  s.grid = IM_COL32(0, 0, 0, 38);
  s.grid_minor = IM_COL32(0, 0, 0, 16);
  s.text = IM_COL32(20, 20, 20, 255);
  s.legend_background = IM_COL32(255, 255, 255, 230);
  s.legend_border = IM_COL32(0, 0, 0, 90);
  s.crosshair = IM_COL32(0, 0, 0, 110);
  return s;
}

PlotStyle plot_style_dark() {
  PlotStyle s;
  s.background = 0;
  s.plot_background = IM_COL32(28, 30, 34, 255);
  s.frame = IM_COL32(160, 160, 165, 255);
  s.grid = IM_COL32(255, 255, 255, 36);
  s.grid_minor = IM_COL32(255, 255, 255, 14);
  s.text = IM_COL32(225, 225, 228, 255);
  s.legend_background = IM_COL32(22, 24, 28, 225);
  s.legend_border = IM_COL32(255, 255, 255, 70);
  s.crosshair = IM_COL32(255, 255, 255, 110);
  return s;
}

PlotStyle plot_style_current() {
  return current_theme_is_dark() ? plot_style_dark() : plot_style_light();
}

namespace {

/// Body and title fonts at their drawn sizes (io.FontGlobalScale included).
TextFont body_font(const PlotStyle& style) {
  const float scale = ImGui::GetIO().FontGlobalScale;
  if (style.font != nullptr) return {style.font, style.font->FontSize * scale};
  return {ImGui::GetFont(), ImGui::GetFontSize()};
}

TextFont heading_font(const PlotStyle& style) {
  ImFont* f = style.title_font != nullptr ? style.title_font : title_font();
  return {f, f->FontSize * ImGui::GetIO().FontGlobalScale};
}

float max_label_width(const TextFont& f, const std::vector<Tick>& ticks) {
  float w = 0.0f;
  for (const auto& t : ticks) {
    if (t.major) w = std::max(w, detail::tick_label_size(f, t).x);
  }
  return w;
}

/// True when neighbouring labelled x ticks leave at least `gap` pixels between labels.
bool x_labels_fit(const TextFont& f, const std::vector<Tick>& ticks, const AxisMap& mx,
                  float gap) {
  double prev_px = 0.0, prev_half = 0.0;
  bool have = false;
  for (const auto& t : ticks) {
    if (!t.major) continue;
    const double px = mx.to_px(t.value);
    const double half = 0.5 * detail::tick_label_size(f, t).x;
    if (have && px - prev_px < prev_half + half + gap) return false;
    prev_px = px;
    prev_half = half;
    have = true;
  }
  return true;
}

/// The title as drawn: in the title font where it fits the frame's width less its margins;
/// else in the title font at the body's size, broken at blanks (ui/text_wrap.hpp) where even
/// that is too wide. So none of it is cut off at a narrow --size or in a narrow panel, and a
/// tuner panel loses no more height to it than it must. One source for the layout (the
/// title's height) and the drawing.
struct TitleText {
  TextFont font;
  std::vector<std::string> lines;
  double height() const { return static_cast<double>(lines.size()) * font.size; }
};
TitleText title_text(const TextFont& heading, float body_size, const std::string& title,
                     double width) {
  TitleText t{heading, {}};
  if (title.empty()) return t;
  if (detail::text_size(heading, title).x <= width) {
    t.lines.push_back(title);
    return t;
  }
  t.font = TextFont{heading.font, std::min(heading.size, body_size)};
  const std::string wrapped =
      wrap_at_blanks(title, static_cast<float>(width), [&](std::string_view piece) {
        return detail::text_size(t.font, std::string(piece)).x;
      });
  size_t start = 0;
  for (;;) {
    const size_t end = wrapped.find('\n', start);
    t.lines.push_back(wrapped.substr(start, end == std::string::npos ? end : end - start));
    if (end == std::string::npos) return t;
    start = end + 1;
  }
}

/// The text and spacing of a plot (pixels), from the style's fonts: one source for the layout
/// and the drawing.
struct PlotMetrics {
  TextFont body, heading;
  float fs;        ///< body font size
  float pad;       ///< margin around the plot's parts
  float tick_len;  ///< length of a major tick
  explicit PlotMetrics(const PlotStyle& style)
      : body(body_font(style)),
        heading(heading_font(style)),
        fs(body.size),
        pad(std::round(0.6f * fs)),
        tick_len(std::round(0.35f * fs)) {}
};

}  // namespace

namespace {

/// The axes and data area in `fr` with `right_w` pixels kept free right of the area (an
/// outside legend) and `top_h` above it (a legend above).
PlotLayout layout_axes(const PixelRect& fr, const PlotSpec& spec, const PlotMetrics& m,
                       double right_w, double top_h) {
  const TextFont &f = m.body, &tf = m.heading;
  const float fs = m.fs, pad = m.pad, tick_len = m.tick_len;
  PlotLayout lay;
  lay.frame = fr;
  const TitleText title = title_text(tf, fs, spec.title, fr.x1 - fr.x0 - 2.0 * pad);
  const double top =
      fr.y0 + pad + (title.lines.empty() ? 0.0 : title.height() + 0.6 * pad) + top_h;
  const double x_tick_h = spec.x.log ? std::round(1.3f * fs) : fs;
  double bottom = fr.y1 - pad - (spec.x.label.empty() ? 0.0 : fs + 0.4 * pad) - x_tick_h -
                  tick_len - 0.3 * pad;
  bottom = std::max(bottom, top + 10.0);
  const Range xr = plot_x_range(spec);
  const Range yr = plot_y_range(spec, xr);

  lay.y = AxisMap{yr, spec.y.log, bottom, top};
  lay.y_ticks = axis_ticks(yr, spec.y.log, std::max(2, static_cast<int>((bottom - top) / (2.8 * fs))));
  const double ylab_w = max_label_width(f, lay.y_ticks);
  const double left = fr.x0 + pad + (spec.y.label.empty() ? 0.0 : fs + 0.6 * pad) + ylab_w +
                      tick_len + 0.3 * pad;
  // Room on the right for half of the last x tick label.
  const double right = std::max(fr.x1 - pad - right_w - 1.2 * fs, left + 10.0);

  lay.x = AxisMap{xr, spec.x.log, left, right};
  int target = std::max(2, static_cast<int>((right - left) / (5.0 * fs)));
  for (int iter = 0; iter < 8; ++iter) {
    lay.x_ticks = axis_ticks(xr, spec.x.log, target);
    if (target <= 2 || x_labels_fit(f, lay.x_ticks, lay.x, fs)) break;
    target = std::max(2, target * 2 / 3);
  }
  lay.area = {left, top, right, bottom};
  return lay;
}

double area_of(const PixelRect& r) { return (r.x1 - r.x0) * (r.y1 - r.y0); }

}  // namespace

PlotLayout layout_plot(ImVec2 top_left, ImVec2 size, const PlotSpec& spec,
                       const PlotStyle& style) {
  const PlotMetrics m(style);
  const PixelRect fr{top_left.x, top_left.y, top_left.x + size.x, top_left.y + size.y};
  const int n = detail::legend_count(spec);
  if (n == 0) return layout_axes(fr, spec, m, 0.0, 0.0);
  const detail::LegendMetrics lm(m.fs);
  const float label_w = detail::legend_label_width(spec, m.body);
  const ImVec2 one = lm.box(n, 1, label_w);
  const double gap = lm.pad;

  // Right of the data area, in one column.
  auto outside = [&] {
    PlotLayout lay = layout_axes(fr, spec, m, one.x + m.pad, 0.0);
    lay.legend_pos = LegendPos::Outside;
    lay.legend_label_width = label_w;
    const double x = lay.area.x1 + gap;
    lay.legend = {x, lay.area.y0, x + one.x, lay.area.y0 + one.y};
    return lay;
  };
  // Between the title and the data area, in columns: the fewest whose box takes at most 40 %
  // of the plot's height, labels shortened to fit the width, but not below kMinLabel pixels
  // (then as many columns as take them).
  auto above = [&] {
    constexpr float kMinLabel = 100.0f;
    const float avail = static_cast<float>(fr.x1 - fr.x0) - 2.0f * m.pad;
    const float cap = 0.4f * static_cast<float>(fr.y1 - fr.y0);
    const auto label_for = [&](int c) {
      return std::min(label_w, (avail - lm.pad) / static_cast<float>(c) - lm.column_width(0.0f));
    };
    int cols = 1;
    while (cols < n && lm.box(n, cols, label_for(cols)).y > cap &&
           label_for(cols + 1) >= std::min(kMinLabel, label_w))
      ++cols;
    const float w = std::max(20.0f, label_for(cols));
    const ImVec2 box = lm.box(n, cols, w);
    PlotLayout lay = layout_axes(fr, spec, m, 0.0, box.y + gap);
    lay.legend_pos = LegendPos::Above;
    lay.legend_columns = cols;
    lay.legend_label_width = w;
    const double x = std::max(fr.x0 + m.pad, std::min(lay.area.x0, fr.x1 - m.pad - box.x));
    const double y = lay.area.y0 - gap - box.y;
    lay.legend = {x, y, x + box.x, y + box.y};
    return lay;
  };
  if (spec.legend == LegendPos::Outside) return outside();
  if (spec.legend == LegendPos::Above) return above();

  // Inside a corner of the data area; a legend wider than the area has its labels shortened
  // to fit in it rather than running over the axes and out of the window.
  PlotLayout lay = layout_axes(fr, spec, m, 0.0, 0.0);
  const PixelRect& a = lay.area;
  ImVec2 box = one;
  float w = label_w;
  const float room = static_cast<float>(a.x1 - a.x0 - 2.0 * gap);
  if (box.x > room && room > lm.column_width(0.0f) + lm.pad + 20.0f) {
    w = room - lm.pad - lm.column_width(0.0f);
    box.x = room;
  }
  auto corner = [&](LegendPos c) {
    const bool r = c == LegendPos::TopRight || c == LegendPos::BottomRight;
    const bool t = c == LegendPos::TopRight || c == LegendPos::TopLeft;
    const double x = std::round(r ? a.x1 - gap - box.x : a.x0 + gap);
    const double y = std::round(t ? a.y0 + gap : a.y1 - gap - box.y);
    return PixelRect{x, y, x + box.x, y + box.y};
  };
  auto place = [&](LegendPos c) {
    lay.legend_pos = c;
    lay.legend_label_width = w;
    lay.legend = corner(c);
    return lay;
  };
  if (spec.legend != LegendPos::Auto) return place(spec.legend);
  const bool fits = box.x <= room && box.y <= a.y1 - a.y0 - 2.0 * gap;
  if (fits) {
    for (LegendPos c : {LegendPos::TopRight, LegendPos::TopLeft, LegendPos::BottomRight,
                        LegendPos::BottomLeft})
      if (curve_pixels_under(lay, spec, corner(c)) == 0) return place(c);
  }
  // Every corner would hide a curve: outside the data area, where it leaves the larger area.
  const PlotLayout o = outside(), t = above();
  const bool o_fits = o.legend.x1 <= fr.x1 && o.legend.y1 <= fr.y1;
  return o_fits && area_of(o.area) >= area_of(t.area) ? o : t;
}

PlotLayout draw_plot(ImDrawList* dl, ImVec2 top_left, ImVec2 size, const PlotSpec& spec,
                     const PlotStyle& style) {
  const PlotLayout lay = layout_plot(top_left, size, spec, style);
  const PlotMetrics m(style);
  const TextFont &f = m.body, &tf = m.heading;
  const float fs = m.fs, pad = m.pad, tick_len = m.tick_len;
  const PixelRect& a = lay.area;
  const PixelRect& fr = lay.frame;
  const ImVec2 amin(static_cast<float>(a.x0), static_cast<float>(a.y0));
  const ImVec2 amax(static_cast<float>(a.x1), static_cast<float>(a.y1));
  auto fl = [](double v) { return static_cast<float>(v); };
  auto crisp = [](double v) { return static_cast<float>(std::floor(v) + 0.5); };

  dl->PushClipRect(ImVec2(fl(fr.x0), fl(fr.y0)), ImVec2(fl(fr.x1), fl(fr.y1)), true);
  if (style.background != 0) {
    dl->AddRectFilled(ImVec2(fl(fr.x0), fl(fr.y0)), ImVec2(fl(fr.x1), fl(fr.y1)), style.background);
  }
  dl->AddRectFilled(amin, amax, style.plot_background);

  // Data layers, clipped to the data area.
  dl->PushClipRect(amin, amax, true);
  detail::draw_heatmap(dl, lay, spec.heatmap);
  for (const auto& b : spec.bands) detail::draw_band(dl, lay, b);
  for (const auto& t : lay.x_ticks) {
    const float x = crisp(lay.x.to_px(t.value));
    dl->AddLine(ImVec2(x, amin.y), ImVec2(x, amax.y), t.major ? style.grid : style.grid_minor);
  }
  for (const auto& t : lay.y_ticks) {
    const float y = crisp(lay.y.to_px(t.value));
    dl->AddLine(ImVec2(amin.x, y), ImVec2(amax.x, y), t.major ? style.grid : style.grid_minor);
  }
  for (const LineAxis axis : {LineAxis::x, LineAxis::y})  // vertical lines under horizontal
    for (const PlotRefLine& l : spec.ref_lines) {
      if (l.axis != axis || !style.draw_curves) continue;
      const bool vertical = axis == LineAxis::x;
      const double px = (vertical ? lay.x : lay.y).to_px(l.at);
      if (std::isnan(px)) continue;
      const ImVec2 from = vertical ? ImVec2(fl(px), amin.y) : ImVec2(amin.x, fl(px));
      const ImVec2 to = vertical ? ImVec2(fl(px), amax.y) : ImVec2(amax.x, fl(px));
      detail::draw_polyline(dl, {from, to}, l.color, l.thickness, l.dashed);
    }
  if (style.draw_curves)
    for (const auto& s : spec.series) detail::draw_series(dl, lay, s);
  dl->PopClipRect();

  dl->AddRect(ImVec2(amin.x - 0.5f, amin.y - 0.5f), ImVec2(amax.x + 0.5f, amax.y + 0.5f),
              style.frame);
  // Ticks and their labels.
  for (const auto& t : lay.x_ticks) {
    const double px = lay.x.to_px(t.value);
    if (px < a.x0 - 0.5 || px > a.x1 + 0.5) continue;
    const float x = crisp(px);
    const float len = t.major ? tick_len : std::round(0.6f * tick_len);
    dl->AddLine(ImVec2(x, amax.y), ImVec2(x, amax.y + len), style.frame);
    if (!t.major) continue;
    const ImVec2 ts = detail::tick_label_size(f, t);
    detail::draw_tick_label(dl, f, ImVec2(x - ts.x * 0.5f, amax.y + tick_len + 0.3f * pad),
                            style.text, t);
  }
  for (const auto& t : lay.y_ticks) {
    const double py = lay.y.to_px(t.value);
    if (py < a.y0 - 0.5 || py > a.y1 + 0.5) continue;
    const float y = crisp(py);
    const float len = t.major ? tick_len : std::round(0.6f * tick_len);
    dl->AddLine(ImVec2(amin.x - len, y), ImVec2(amin.x, y), style.frame);
    if (!t.major) continue;
    const ImVec2 ts = detail::tick_label_size(f, t);
    detail::draw_tick_label(dl, f, ImVec2(amin.x - tick_len - 0.3f * pad - ts.x, y - ts.y * 0.5f),
                            style.text, t);
  }
  // Axis labels and title, centred on the data area.
  const float cx = 0.5f * (amin.x + amax.x);
  if (!spec.x.label.empty()) {
    const ImVec2 ts = detail::text_size(f, spec.x.label);
    detail::draw_text(dl, f, ImVec2(cx - ts.x * 0.5f, fl(fr.y1) - pad - ts.y), style.text,
                      spec.x.label);
  }
  if (!spec.y.label.empty()) {
    // A label longer than the plot is tall is shortened with "..." rather than cut off.
    detail::draw_text_vertical(dl, f, ImVec2(fl(fr.x0) + pad + 0.5f * fs, 0.5f * (amin.y + amax.y)),
                               style.text, detail::elide(f, spec.y.label, amax.y - amin.y + 2 * fs));
  }
  // Each line of the title centred on the data area, moved in where that would cross the
  // frame's margin.
  const TitleText title = title_text(tf, fs, spec.title, fr.x1 - fr.x0 - 2.0 * pad);
  for (size_t i = 0; i < title.lines.size(); ++i) {
    const ImVec2 ts = detail::text_size(title.font, title.lines[i]);
    const float x = std::max(fl(fr.x0) + pad, std::min(cx - ts.x * 0.5f, fl(fr.x1) - pad - ts.x));
    detail::draw_text(dl, title.font,
                      ImVec2(x, fl(fr.y0) + pad + static_cast<float>(i) * title.font.size),
                      style.text, title.lines[i]);
  }
  if (style.draw_legend) detail::draw_legend(dl, lay, spec, style, f);
  dl->PopClipRect();
  return lay;
}

PlotLayout plot_widget(const char* id, const PlotSpec& spec, ImVec2 size, const PlotStyle& style) {
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  if (size.x <= 0.0f) size.x = avail.x;
  if (size.y <= 0.0f) size.y = avail.y;
  size = ImVec2(std::max(size.x, 50.0f), std::max(size.y, 50.0f));
  const ImVec2 tl = ImGui::GetCursorScreenPos();
  item::invisible_button(id, size);
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const PlotLayout lay = draw_plot(dl, tl, size, spec, style);
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (hovered && lay.area.contains(mouse.x, mouse.y)) {
    const PixelRect& a = lay.area;
    const ImVec2 amin(static_cast<float>(a.x0), static_cast<float>(a.y0));
    const ImVec2 amax(static_cast<float>(a.x1), static_cast<float>(a.y1));
    dl->PushClipRect(amin, amax, true);
    const float cx = std::floor(mouse.x) + 0.5f, cy = std::floor(mouse.y) + 0.5f;  // crisp 1 px
    dl->AddLine(ImVec2(cx, amin.y), ImVec2(cx, amax.y), style.crosshair);
    dl->AddLine(ImVec2(amin.x, cy), ImVec2(amax.x, cy), style.crosshair);
    dl->PopClipRect();
    ImGui::BeginTooltip();
    ImGui::Text("x = %.6g\ny = %.6g", lay.x.from_px(mouse.x), lay.y.from_px(mouse.y));
    ImGui::EndTooltip();
  }
  return lay;
}

}  // namespace dampbound::ui
