#include "ui/plot_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbound::ui {

bool clip_segment(double& ax, double& ay, double& bx, double& by, const PixelRect& rect) {
  const double dx = bx - ax, dy = by - ay;
  double t0 = 0.0, t1 = 1.0;
  // Liang-Barsky: each edge is p * t <= q.
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {ax - rect.x0, rect.x1 - ax, ay - rect.y0, rect.y1 - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      if (t > t1) return false;
      t0 = std::max(t0, t);
    } else {
      if (t < t0) return false;
      t1 = std::min(t1, t);
    }
  }
  const double ax0 = ax, ay0 = ay;
  if (t1 < 1.0) {
    bx = ax0 + t1 * dx;
    by = ay0 + t1 * dy;
  }
  if (t0 > 0.0) {
    ax = ax0 + t0 * dx;
    ay = ay0 + t0 * dy;
  }
  return true;
}

std::vector<std::vector<ImVec2>> project_polylines(const std::vector<double>& x,
                                                   const std::vector<double>& y,
                                                   const AxisMap& mx, const AxisMap& my,
                                                   const PixelRect& clip) {
  std::vector<std::vector<ImVec2>> out;
  std::vector<ImVec2> cur;
  auto flush = [&] {
    if (!cur.empty()) out.push_back(std::move(cur));
    cur.clear();
  };
  auto vec = [](double px, double py) { return ImVec2(static_cast<float>(px), static_cast<float>(py)); };
  const size_t n = std::min(x.size(), y.size());
  bool have_prev = false;
  double qx = 0.0, qy = 0.0;  // previous point, unclipped
  for (size_t i = 0; i < n; ++i) {
    const double px = mx.to_px(x[i]);
    const double py = my.to_px(y[i]);
    if (std::isnan(px) || std::isnan(py)) {
      flush();
      have_prev = false;
      continue;
    }
    if (!have_prev) {
      have_prev = true;
      qx = px;
      qy = py;
      if (clip.contains(px, py)) cur.push_back(vec(px, py));
      continue;
    }
    double ax = qx, ay = qy, bx = px, by = py;
    if (clip_segment(ax, ay, bx, by, clip)) {
      if (cur.empty() || ax != qx || ay != qy) {
        flush();
        cur.push_back(vec(ax, ay));
      }
      cur.push_back(vec(bx, by));
      if (bx != px || by != py) flush();  // left the rectangle
    } else {
      flush();
    }
    qx = px;
    qy = py;
  }
  flush();
  return out;
}

std::vector<ImVec2> decimate_columns(const std::vector<ImVec2>& pts) {
  const size_t n = pts.size();
  if (n <= 4) return pts;
  std::vector<ImVec2> out;
  out.reserve(std::min(n, size_t{4096}));
  size_t i = 0;
  while (i < n) {
    const float col = std::floor(pts[i].x);
    size_t j = i, imin = i, imax = i;
    while (j + 1 < n && std::floor(pts[j + 1].x) == col) {
      ++j;
      if (pts[j].y < pts[imin].y) imin = j;
      if (pts[j].y > pts[imax].y) imax = j;
    }
    size_t idx[4] = {i, std::min(imin, imax), std::max(imin, imax), j};
    for (int k = 0; k < 4; ++k) {
      if (k == 0 || idx[k] != idx[k - 1]) out.push_back(pts[idx[k]]);
    }
    i = j + 1;
  }
  return out;
}

std::vector<BandSample> decimate_band_columns(const std::vector<BandSample>& samples) {
  const size_t n = samples.size();
  std::vector<BandSample> out;
  out.reserve(std::min(n, size_t{4096}));
  size_t i = 0;
  while (i < n) {
    if (std::isnan(samples[i].x)) {
      out.push_back(samples[i++]);
      continue;
    }
    const double col = std::floor(samples[i].x);
    size_t j = i;
    while (j + 1 < n && !std::isnan(samples[j + 1].x) && std::floor(samples[j + 1].x) == col) ++j;
    double top = std::numeric_limits<double>::infinity();
    double bottom = -std::numeric_limits<double>::infinity();
    for (size_t k = i; k <= j; ++k) {
      const BandSample& b = samples[k];
      if (std::isnan(b.lo) || std::isnan(b.hi) || b.lo < b.hi) continue;  // empty there
      top = std::min(top, b.hi);
      bottom = std::max(bottom, b.lo);
    }
    if (bottom >= top) {
      out.push_back({samples[i].x, bottom, top});
      if (j > i) out.push_back({samples[j].x, bottom, top});
    } else {
      out.push_back(samples[i]);
      if (j > i) out.push_back(samples[j]);
    }
    i = j + 1;
  }
  return out;
}

std::vector<ImVec2> clip_polygon(const std::vector<ImVec2>& poly, const PixelRect& rect) {
  std::vector<ImVec2> cur = poly, next;
  // Each edge keeps the side where inside(p) holds; cut() gives the crossing point.
  for (int edge = 0; edge < 4 && !cur.empty(); ++edge) {
    const bool is_x = edge < 2;
    const double bound = edge == 0 ? rect.x0 : edge == 1 ? rect.x1 : edge == 2 ? rect.y0 : rect.y1;
    const bool keep_greater = edge == 0 || edge == 2;
    auto coord = [&](const ImVec2& p) { return static_cast<double>(is_x ? p.x : p.y); };
    auto inside = [&](const ImVec2& p) { return keep_greater ? coord(p) >= bound : coord(p) <= bound; };
    next.clear();
    for (size_t i = 0; i < cur.size(); ++i) {
      const ImVec2& p = cur[i];
      const ImVec2& q = cur[(i + 1) % cur.size()];
      const bool pin = inside(p), qin = inside(q);
      if (pin) next.push_back(p);
      if (pin != qin) {
        const double t = (bound - coord(p)) / (coord(q) - coord(p));
        next.emplace_back(static_cast<float>(p.x + t * (q.x - p.x)),
                          static_cast<float>(p.y + t * (q.y - p.y)));
      }
    }
    std::swap(cur, next);
  }
  if (cur.size() < 3) cur.clear();
  return cur;
}

std::vector<std::vector<ImVec2>> split_sharp_turns(const std::vector<ImVec2>& pts) {
  std::vector<std::vector<ImVec2>> out;
  if (pts.empty()) return out;
  std::vector<ImVec2> cur{pts[0]};
  for (size_t i = 1; i < pts.size(); ++i) {
    cur.push_back(pts[i]);
    if (i + 1 >= pts.size()) break;
    const float dx1 = pts[i].x - pts[i - 1].x, dy1 = pts[i].y - pts[i - 1].y;
    const float dx2 = pts[i + 1].x - pts[i].x, dy2 = pts[i + 1].y - pts[i].y;
    const float dot = dx1 * dx2 + dy1 * dy2;
    const float len2 = (dx1 * dx1 + dy1 * dy1) * (dx2 * dx2 + dy2 * dy2);
    // cos(angle) < -0.5 <=> dot < 0 and dot^2 > 0.25 |d1|^2 |d2|^2
    if (dot < 0.0f && dot * dot > 0.25f * len2) {
      out.push_back(std::move(cur));
      cur = {pts[i]};
    }
  }
  if (cur.size() >= 2 || out.empty()) out.push_back(std::move(cur));
  return out;
}

std::vector<std::vector<ImVec2>> dash_polyline(const std::vector<ImVec2>& pts, float on,
                                               float off) {
  std::vector<std::vector<ImVec2>> out;
  if (pts.size() < 2 || !(on > 0.0f) || !(off > 0.0f)) {
    if (!pts.empty()) out.push_back(pts);
    return out;
  }
  bool drawing = true;
  float left = on;  // length left in the current dash or gap
  std::vector<ImVec2> cur{pts[0]};
  for (size_t i = 1; i < pts.size(); ++i) {
    ImVec2 a = pts[i - 1];
    const ImVec2 b = pts[i];
    float seg = std::hypot(b.x - a.x, b.y - a.y);
    while (seg > left) {
      const float t = left / seg;
      const ImVec2 m(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
      if (drawing) {
        cur.push_back(m);
        out.push_back(std::move(cur));
        cur.clear();
      } else {
        cur = {m};
      }
      drawing = !drawing;
      seg -= left;
      a = m;
      left = drawing ? on : off;
    }
    left -= seg;
    if (drawing) cur.push_back(b);
  }
  if (drawing && cur.size() >= 2) out.push_back(std::move(cur));
  return out;
}

}  // namespace dampbound::ui
