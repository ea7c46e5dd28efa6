#include "ui/plot_draw.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace dampbound::ui::detail {

namespace {
constexpr float kSuperscriptScale = 0.72f;
/// Far-off pixel values are clamped to this distance beyond the area before going to float;
/// slopes inside the area change by well under a pixel.
constexpr double kFar = 1e6;

ImVec2 vec(double x, double y) { return ImVec2(static_cast<float>(x), static_cast<float>(y)); }

unsigned alpha_of(ImU32 c) { return (c >> IM_COL32_A_SHIFT) & 0xFFu; }
}  // namespace

ImVec2 text_size(const TextFont& f, const std::string& s) {
  return f.font->CalcTextSizeA(f.size, FLT_MAX, 0.0f, s.c_str(), s.c_str() + s.size());
}

void draw_text(ImDrawList* dl, const TextFont& f, ImVec2 pos, ImU32 col, const std::string& s) {
  dl->AddText(f.font, f.size, ImVec2(std::round(pos.x), std::round(pos.y)), col, s.c_str(),
              s.c_str() + s.size());
}

void draw_text_vertical(ImDrawList* dl, const TextFont& f, ImVec2 c, ImU32 col,
                        const std::string& s) {
  const ImVec2 sz = text_size(f, s);
  // Lay the text out horizontally in the middle of the clip rectangle (ImGui culls glyphs
  // outside it), then turn the new vertices by 90 degrees, (dx, dy) -> (dy, -dx), about that
  // middle and move them to c.
  const ImVec2 lo = dl->GetClipRectMin(), hi = dl->GetClipRectMax();
  const ImVec2 m(std::round(0.5f * (lo.x + hi.x)), std::round(0.5f * (lo.y + hi.y)));
  const ImVec2 cr(std::round(c.x), std::round(c.y));
  const int v0 = dl->VtxBuffer.Size;
  draw_text(dl, f, ImVec2(m.x - sz.x * 0.5f, m.y - sz.y * 0.5f), col, s);
  for (int i = v0; i < dl->VtxBuffer.Size; ++i) {
    ImVec2& p = dl->VtxBuffer[i].pos;
    const float dx = p.x - m.x, dy = p.y - m.y;
    p = ImVec2(cr.x + dy, cr.y - dx);
  }
}

ImVec2 tick_label_size(const TextFont& f, const Tick& t) {
  if (!t.pow10) return text_size(f, t.label);
  const ImVec2 base = text_size(f, "10");
  const ImVec2 ex = text_size({f.font, f.size * kSuperscriptScale}, std::to_string(t.exponent));
  return ImVec2(base.x + ex.x + 1.0f, base.y + std::round(0.3f * f.size));
}

void draw_tick_label(ImDrawList* dl, const TextFont& f, ImVec2 pos, ImU32 col, const Tick& t) {
  if (!t.pow10) {
    draw_text(dl, f, pos, col, t.label);
    return;
  }
  const ImVec2 base = text_size(f, "10");
  draw_text(dl, f, ImVec2(pos.x, pos.y + std::round(0.3f * f.size)), col, "10");
  draw_text(dl, {f.font, f.size * kSuperscriptScale}, ImVec2(pos.x + base.x + 1.0f, pos.y), col,
            std::to_string(t.exponent));
}

void draw_heatmap(ImDrawList* dl, const PlotLayout& lay, const PlotHeatmap& hm) {
  const int nx = hm.nx(), ny = hm.ny();
  if (nx == 0 || ny == 0 || hm.cell_color.size() < static_cast<size_t>(nx) * ny) return;
  // Cell edges snap to whole pixels, so each pixel belongs to exactly one cell: a map finer
  // than the screen costs at most one rectangle per pixel, and cells tile without seams.
  const PixelRect& a = lay.area;
  auto snap = [](double p, double lo, double hi) {
    return std::isnan(p) ? std::numeric_limits<float>::quiet_NaN()
                         : static_cast<float>(std::round(std::clamp(p, lo, hi)));
  };
  std::vector<float> xe(nx + 1), ye(ny + 1);
  for (int i = 0; i <= nx; ++i) xe[i] = snap(lay.x.to_px(hm.x_edges[i]), a.x0, a.x1);
  for (int j = 0; j <= ny; ++j) ye[j] = snap(lay.y.to_px(hm.y_edges[j]), a.y0, a.y1);
  for (int j = 0; j < ny; ++j) {
    const float top = std::min(ye[j], ye[j + 1]), bot = std::max(ye[j], ye[j + 1]);
    if (!(bot > top)) continue;  // also skips NaN edges
    float run_x0 = 0.0f, run_x1 = 0.0f;
    ImU32 run_col = 0;
    auto flush = [&] {
      if (run_col != 0) dl->AddRectFilled(ImVec2(run_x0, top), ImVec2(run_x1, bot), run_col);
      run_col = 0;
    };
    for (int i = 0; i < nx; ++i) {
      const float x0 = xe[i], x1 = xe[i + 1];
      if (!(x1 > x0)) continue;
      const ImU32 c = hm.cell_color[static_cast<size_t>(j) * nx + i];
      if (alpha_of(c) == 0) {
        flush();
        continue;
      }
      if (c == run_col && x0 == run_x1) {
        run_x1 = x1;
        continue;
      }
      flush();
      run_col = c;
      run_x0 = x0;
      run_x1 = x1;
    }
    flush();
  }
}

void draw_band(ImDrawList* dl, const PlotLayout& lay, const PlotBand& band) {
  const size_t n = std::min({band.x.size(), band.y_lo.size(), band.y_hi.size()});
  if (n < 2) return;
  const PixelRect& a = lay.area;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // +inf: the top edge; -inf (or <= 0 on a log axis): the bottom edge; NaN: no sample.
  auto ypix = [&](double v) {
    if (std::isnan(v)) return nan;
    if (v == std::numeric_limits<double>::infinity()) return a.y0 - 2.0;
    if (v == -std::numeric_limits<double>::infinity() || (lay.y.log && v <= 0.0)) return a.y1 + 2.0;
    return std::clamp(lay.y.to_px(v), a.y0 - kFar, a.y1 + kFar);
  };
  std::vector<BandSample> px(n);
  for (size_t i = 0; i < n; ++i) {
    const double x = lay.x.to_px(band.x[i]);
    px[i] = {std::isnan(x) ? x : std::clamp(x, a.x0 - kFar, a.x1 + kFar), ypix(band.y_lo[i]),
             ypix(band.y_hi[i])};
  }
  // Thousands of sub-pixel slivers cost a software rasteriser dearly: one column, one quad.
  if (static_cast<double>(n) > 2.0 * std::max(a.x1 - a.x0, 1.0)) px = decimate_band_columns(px);
  // Without anti-aliased fills, neighbouring quads share exact edges: no seams, no overlap.
  const ImDrawListFlags saved = dl->Flags;
  dl->Flags &= ~ImDrawListFlags_AntiAliasedFill;
  std::vector<ImVec2> poly;
  for (size_t i = 1; i < px.size(); ++i) {
    const BandSample& p = px[i - 1];
    const BandSample& q = px[i];
    if (std::isnan(p.x + p.lo + p.hi + q.x + q.lo + q.hi)) continue;
    // On screen the band is non-empty where lo is below hi: d = lo - hi >= 0.
    const double d0 = p.lo - p.hi, d1 = q.lo - q.hi;
    if (d0 >= 0.0 && d1 >= 0.0) {
      poly = {vec(p.x, p.hi), vec(q.x, q.hi), vec(q.x, q.lo), vec(p.x, p.lo)};
    } else if (d0 >= 0.0 || d1 >= 0.0) {
      const double t = d0 / (d0 - d1);  // where the curves cross
      const double xc = p.x + t * (q.x - p.x), yc = p.hi + t * (q.hi - p.hi);
      poly = d0 >= 0.0 ? std::vector<ImVec2>{vec(p.x, p.hi), vec(xc, yc), vec(p.x, p.lo)}
                       : std::vector<ImVec2>{vec(xc, yc), vec(q.x, q.hi), vec(q.x, q.lo)};
    } else {
      continue;
    }
    poly = clip_polygon(poly, a);
    if (poly.size() >= 3) {
      dl->AddConvexPolyFilled(poly.data(), static_cast<int>(poly.size()), band.color);
    }
  }
  dl->Flags = saved;
}

void draw_polyline(ImDrawList* dl, const std::vector<ImVec2>& pts, ImU32 col, float thickness,
                   bool dashed) {
  if (pts.size() < 2) return;
  auto stroke = [&](const std::vector<ImVec2>& piece) {
    for (const auto& run : split_sharp_turns(piece)) {
      if (run.size() >= 2) {
        dl->AddPolyline(run.data(), static_cast<int>(run.size()), col, ImDrawFlags_None,
                        thickness);
      }
    }
  };
  if (!dashed) {
    stroke(pts);
    return;
  }
  const float t = std::max(thickness, 1.0f);
  for (const auto& piece : dash_polyline(pts, 5.0f + 3.0f * t, 3.0f + 2.0f * t)) stroke(piece);
}

void draw_series(ImDrawList* dl, const PlotLayout& lay, const PlotSeries& s) {
  const PixelRect& a = lay.area;
  const double m = s.thickness + 2.0;
  const PixelRect clip{a.x0 - m, a.y0 - m, a.x1 + m, a.y1 + m};
  const double width = std::max(a.x1 - a.x0, 1.0);
  for (auto& line : project_polylines(s.x, s.y, lay.x, lay.y, clip)) {
    if (line.size() == 1) {
      dl->AddCircleFilled(line[0], std::max(s.thickness, 2.0f), s.color, 8);
      continue;
    }
    if (static_cast<double>(line.size()) > 2.0 * width) line = decimate_columns(line);
    draw_polyline(dl, line, s.color, s.thickness, s.dashed);
  }
}

namespace {

struct LegendEntry {
  std::string label;
  ImU32 color = 0;
  bool filled = false;
  bool dashed = false;
  float thickness = 2.0f;
};

std::vector<LegendEntry> legend_entries(const PlotSpec& spec) {
  std::vector<LegendEntry> e;
  for (const auto& s : spec.series) {
    if (!s.label.empty()) e.push_back({s.label, s.color, false, s.dashed, s.thickness});
  }
  for (const auto& b : spec.bands) {
    if (!b.label.empty()) e.push_back({b.label, b.color, true, false, 0.0f});
  }
  for (const LineAxis axis : {LineAxis::y, LineAxis::x})  // horizontal lines listed first
    for (const PlotRefLine& l : spec.ref_lines)
      if (l.axis == axis && !l.label.empty())
        e.push_back({l.label, l.color, false, l.dashed, l.thickness});
  for (const auto& c : spec.heatmap.legend) {
    if (!c.label.empty()) e.push_back({c.label, c.color, true, false, 0.0f});
  }
  return e;
}

/// Legend metrics from the font size: padding, row height, swatch width.
struct LegendMetrics {
  float pad, row, swatch;
  explicit LegendMetrics(float fs)
      : pad(std::round(0.5f * fs)), row(std::round(1.35f * fs)), swatch(std::round(2.2f * fs)) {}
};

/// How much data a legend box at `box` would hide: sampled series points inside it, plus a
/// penalty for each reference line crossing it.
double hidden_data(const PlotLayout& lay, const PlotSpec& spec, const PixelRect& box) {
  double score = 0.0;
  for (const auto& s : spec.series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    const size_t stride = std::max<size_t>(1, n / 1000);
    const double weight = static_cast<double>(stride);
    for (size_t i = 0; i < n; i += stride) {
      const double x = lay.x.to_px(s.x[i]), y = lay.y.to_px(s.y[i]);
      if (box.contains(x, y)) score += weight;
    }
  }
  const double line_penalty = 20.0;
  for (const PlotRefLine& l : spec.ref_lines) {
    const bool vertical = l.axis == LineAxis::x;
    const double px = (vertical ? lay.x : lay.y).to_px(l.at);
    if (px >= (vertical ? box.x0 : box.y0) && px <= (vertical ? box.x1 : box.y1))
      score += line_penalty;
  }
  return score;
}

}  // namespace

ImVec2 legend_size(const PlotSpec& spec, const TextFont& f) {
  const auto entries = legend_entries(spec);
  if (entries.empty() || spec.legend == LegendPos::Hidden) return ImVec2(0.0f, 0.0f);
  const LegendMetrics m(f.size);
  float w = 0.0f;
  for (const auto& e : entries) w = std::max(w, text_size(f, e.label).x);
  return ImVec2(m.pad * 2.5f + m.swatch + w, m.pad * 1.2f + m.row * static_cast<float>(entries.size()));
}

std::string elide(const TextFont& f, const std::string& label, float width) {
  if (text_size(f, label).x <= width) return label;
  std::string s = label;
  while (!s.empty() && text_size(f, s + "...").x > width) {
    s.pop_back();
    while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80) s.pop_back();
  }
  return s + "...";
}

void draw_legend(ImDrawList* dl, const PlotLayout& lay, const PlotSpec& spec,
                 const PlotStyle& style, const TextFont& f) {
  ImVec2 size = legend_size(spec, f);
  if (size.x <= 0.0f) return;
  auto entries = legend_entries(spec);
  const LegendMetrics m(f.size);
  const PixelRect& a = lay.area;
  const float gap = m.pad;
  // A legend wider than the data area (a small window) has its labels shortened to fit in it,
  // rather than running over the axes and out of the window.
  const float room = static_cast<float>(a.x1 - a.x0) - 2 * gap;
  if (spec.legend != LegendPos::Outside && size.x > room && room > m.pad * 2.5f + m.swatch + 20) {
    const float text_w = room - m.pad * 2.5f - m.swatch;
    for (auto& e : entries) e.label = elide(f, e.label, text_w);
    size.x = room;
  }
  const float left = static_cast<float>(a.x0) + gap;
  const float right = static_cast<float>(a.x1) - gap - size.x;
  const float top = static_cast<float>(a.y0) + gap;
  const float bottom = static_cast<float>(a.y1) - gap - size.y;
  LegendPos pos = spec.legend;
  if (pos == LegendPos::Auto) {
    // The corner hiding the least data; ties keep the order top right, top left, ...
    const LegendPos corners[] = {LegendPos::TopRight, LegendPos::TopLeft, LegendPos::BottomRight,
                                 LegendPos::BottomLeft};
    double best = std::numeric_limits<double>::infinity();
    for (LegendPos c : corners) {
      const bool r = c == LegendPos::TopRight || c == LegendPos::BottomRight;
      const bool t = c == LegendPos::TopRight || c == LegendPos::TopLeft;
      const double x0 = r ? right : left, y0 = t ? top : bottom;
      const double score = hidden_data(lay, spec, PixelRect{x0, y0, x0 + size.x, y0 + size.y});
      if (score < best) {
        best = score;
        pos = c;
      }
    }
  }
  ImVec2 p;
  switch (pos) {
    case LegendPos::TopLeft: p = ImVec2(left, top); break;
    case LegendPos::BottomLeft: p = ImVec2(left, bottom); break;
    case LegendPos::BottomRight: p = ImVec2(right, bottom); break;
    case LegendPos::Outside: p = ImVec2(static_cast<float>(a.x1) + gap, static_cast<float>(a.y0)); break;
    default: p = ImVec2(right, top); break;
  }
  p = ImVec2(std::round(p.x), std::round(p.y));
  dl->AddRectFilled(p, ImVec2(p.x + size.x, p.y + size.y), style.legend_background, 3.0f);
  dl->AddRect(ImVec2(p.x + 0.5f, p.y + 0.5f), ImVec2(p.x + size.x - 0.5f, p.y + size.y - 0.5f),
              style.legend_border, 3.0f);
  float y = p.y + m.pad * 0.6f;
  for (const auto& e : entries) {
    const float mid = std::round(y + m.row * 0.5f);
    const float sx0 = p.x + m.pad, sx1 = p.x + m.pad + m.swatch;
    if (e.filled) {
      const float h = std::round(m.row * 0.32f);
      dl->AddRectFilled(ImVec2(sx0, mid - h), ImVec2(sx1, mid + h), e.color);
      if (alpha_of(e.color) < 255) {
        dl->AddRect(ImVec2(sx0, mid - h), ImVec2(sx1, mid + h), with_alpha(e.color, 200));
      }
    } else {
      draw_polyline(dl, {ImVec2(sx0, mid + 0.5f), ImVec2(sx1, mid + 0.5f)}, e.color,
                    std::min(e.thickness, 4.0f), e.dashed);
    }
    const ImVec2 ts = text_size(f, e.label);
    draw_text(dl, f, ImVec2(sx1 + m.pad * 0.8f, mid - ts.y * 0.5f), style.text, e.label);
    y += m.row;
  }
}

}  // namespace dampbound::ui::detail
