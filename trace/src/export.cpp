// surfcert::trace exports: OBJ, ASCII PLY and an SVG picture (see export.hpp).
//
// SVG layout: a fixed viewBox with three square panels (views along z, y and x, i.e. the
// planes x-y, x-z, y-z), all drawn at the same scale so that lengths compare across views.
// Each panel has a light grid with tick labels (from an offset named with the axis where six
// digits cannot tell the ticks apart), axis names, the silhouettes of the quadrics
// (the projection of a quadric's contour along axis k is the conic of the Schur complement of
// its 4x4 matrix with respect to k: an ellipsoid's is drawn whole as an ellipse; any other
// quadric's is traced by marching squares inside the box's projection, or its cross-section
// when it is a cylinder along k), the box dashed, then one <g class="branch"> per branch
// holding its three projected <path class="curve">, zoomed insets for branches under 6
// pixels, then one <circle class="special"> per special point and view. The caption is XML-escaped
// (control characters and invalid UTF-8 bytes are replaced) and written as <text class="caption">.
#include "surfcert/trace/export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

namespace surfcert::trace {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string num2(double v) {
  char buf[40];
  if (std::fabs(v) < 0.005) v = 0;
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

bool finite(const Point3& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// XML text content: escapes markup characters, replaces control characters and bytes that
/// are not valid UTF-8 (so that the document is always well-formed).
std::string xml_escape(const std::string& s) {
  std::string r;
  size_t i = 0;
  while (i < s.size()) {
    auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      case '\'':
        r += "&apos;";
        break;
      default:
        r += (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f ? ' '
                                                                            : static_cast<char>(c);
      }
      ++i;
      continue;
    }
    size_t len = c >= 0xf0 && c <= 0xf4 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
    bool ok = len > 0 && i + len <= s.size();
    unsigned cp = len == 2 ? c & 0x1fu : len == 3 ? c & 0x0fu : c & 0x07u;
    for (size_t k = 1; ok && k < len; ++k) {
      auto d = static_cast<unsigned char>(s[i + k]);
      ok = (d & 0xc0) == 0x80;
      cp = (cp << 6) | (d & 0x3fu);
    }
    if (ok) { // reject overlong forms, surrogates, > U+10FFFF and U+FFFE/U+FFFF
      ok = !(len == 3 && cp < 0x800) && !(len == 4 && cp < 0x10000) && cp <= 0x10ffff &&
           !(cp >= 0xd800 && cp <= 0xdfff) && cp != 0xfffe && cp != 0xffff;
    }
    if (ok) {
      r.append(s, i, len);
      i += len;
    } else {
      r += '?';
      ++i;
    }
  }
  return r;
}

using M4 = std::array<std::array<double, 4>, 4>;

/// The conic whose zero set is the outline of q seen along axis k, as a symmetric 3x3 matrix in
/// the view's (u, v, 1): the Schur complement with respect to k (the silhouette: points where
/// df/dx_k = 0 on f = 0, projected), or, when f does not depend on x_k (a cylinder along the
/// view, a plane containing it), the cross-section x_k = 0. Nullopt when q has no outline in
/// this view (a paraboloid along its axis, a plane seen face-on: they cover the view).
std::optional<std::array<std::array<double, 3>, 3>> view_conic(const core::QuadricMatrix& q,
                                                               size_t k) {
  M4 m{};
  double s = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      m[i][j] = q(static_cast<int>(i), static_cast<int>(j)).to_double_approx();
      s = std::max(s, std::fabs(m[i][j]));
    }
  if (!(s > 0) || !std::isfinite(s)) return std::nullopt;
  for (auto& r : m)
    for (double& v : r)
      v /= s;
  std::array<size_t, 3> id{};
  size_t t = 0;
  for (size_t i = 0; i < 4; ++i)
    if (i != k) id[t++] = i; // (u, v, w)
  std::array<std::array<double, 3>, 3> c{};
  const bool depends =
      std::fabs(m[k][0]) + std::fabs(m[k][1]) + std::fabs(m[k][2]) + std::fabs(m[k][3]) > 1e-12;
  if (std::fabs(m[k][k]) > 1e-12) {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        c[i][j] = m[id[i]][id[j]] - m[id[i]][k] * m[k][id[j]] / m[k][k];
  } else if (!depends) {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        c[i][j] = m[id[i]][id[j]];
  } else {
    return std::nullopt;
  }
  return c;
}

/// Outline of an ellipsoid seen along axis k, as points (u, v) in the view's coordinates
/// (the two remaining axes in increasing order); nullopt when the projection is not a real
/// ellipse (it always is for a real ellipsoid).
std::optional<std::vector<std::array<double, 2>>> silhouette(const core::QuadricMatrix& q, size_t k,
                                                             int samples) {
  const auto vc = view_conic(q, k);
  if (!vc) return std::nullopt;
  const auto& c = *vc;
  double a11 = c[0][0], a12 = c[0][1], a22 = c[1][1];
  double mean = 0.5 * (a11 + a22), diff = 0.5 * (a11 - a22), rad = std::hypot(diff, a12);
  double mu1 = mean + rad, mu2 = mean - rad;
  if (!((mu1 > 0) == (mu2 > 0)) || mu1 == 0 || mu2 == 0) return std::nullopt;
  double w1x, w1y;
  if (rad == 0) {
    w1x = 1;
    w1y = 0;
  } else if (diff >= 0) {
    double l = std::hypot(diff + rad, a12);
    w1x = (diff + rad) / l;
    w1y = a12 / l;
  } else {
    double l = std::hypot(a12, rad - diff);
    w1x = a12 / l;
    w1y = (rad - diff) / l;
  }
  double w2x = -w1y, w2y = w1x;
  double l1 = c[0][2] * w1x + c[1][2] * w1y, l2 = c[0][2] * w2x + c[1][2] * w2y;
  double s1 = -l1 / mu1, s2 = -l2 / mu2;
  double cc = c[2][2] + l1 * s1 + l2 * s2;
  if ((cc > 0) == (mu1 > 0) || cc == 0) return std::nullopt;
  double r1 = std::sqrt(-cc / mu1), r2 = std::sqrt(-cc / mu2);
  double cx = s1 * w1x + s2 * w2x, cy = s1 * w1y + s2 * w2y;
  std::vector<std::array<double, 2>> pts;
  for (int i = 0; i < samples; ++i) {
    double th = 2 * kPi * i / samples;
    double a = r1 * std::cos(th), b = r2 * std::sin(th);
    pts.push_back({cx + a * w1x + b * w2x, cy + a * w1y + b * w2y});
  }
  return pts;
}

/// The zero set of the conic c inside [u0, u1] x [v0, v1] as line segments (marching squares
/// on an n x n grid, crossings placed by linear interpolation): any conic type, degenerate
/// ones (a cone's two lines) included. Segments as (u, v, u', v').
std::vector<std::array<double, 4>> conic_segments(const std::array<std::array<double, 3>, 3>& c,
                                                  double u0, double u1, double v0, double v1,
                                                  int n) {
  auto g = [&c](double u, double v) {
    const double x[3] = {u, v, 1};
    double r = 0;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        r += x[i] * c[i][j] * x[j];
    return r;
  };
  std::vector<double> val(static_cast<size_t>((n + 1) * (n + 1)));
  auto at = [&](int i, int j) -> double& { return val[static_cast<size_t>(j * (n + 1) + i)]; };
  const double du = (u1 - u0) / n, dv = (v1 - v0) / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      at(i, j) = g(u0 + i * du, v0 + j * dv);
  std::vector<std::array<double, 4>> out;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Corners counter-clockwise: (i,j), (i+1,j), (i+1,j+1), (i,j+1).
      const double cu[4] = {u0 + i * du, u0 + (i + 1) * du, u0 + (i + 1) * du, u0 + i * du};
      const double cv[4] = {v0 + j * dv, v0 + j * dv, v0 + (j + 1) * dv, v0 + (j + 1) * dv};
      const double f[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      std::vector<std::array<double, 2>> x;
      for (int e = 0; e < 4; ++e) {
        const int e2 = (e + 1) % 4;
        if ((f[e] >= 0) == (f[e2] >= 0)) continue;
        const double lam = f[e] / (f[e] - f[e2]);
        x.push_back({cu[e] + lam * (cu[e2] - cu[e]), cv[e] + lam * (cv[e2] - cv[e])});
      }
      if (x.size() == 2) {
        out.push_back({x[0][0], x[0][1], x[1][0], x[1][1]});
      } else if (x.size() == 4) { // a saddle cell: pair the crossings by the centre's sign
        const bool centre = g(cu[0] + du / 2, cv[0] + dv / 2) >= 0;
        if (centre == (f[0] >= 0)) {
          out.push_back({x[0][0], x[0][1], x[3][0], x[3][1]});
          out.push_back({x[1][0], x[1][1], x[2][0], x[2][1]});
        } else {
          out.push_back({x[0][0], x[0][1], x[1][0], x[1][1]});
          out.push_back({x[2][0], x[2][1], x[3][0], x[3][1]});
        }
      }
    }
  return out;
}

} // namespace

std::string to_obj(const std::vector<Branch>& branches, const std::vector<Point3>& points) {
  std::ostringstream o;
  o << "# surfcert intersection curve: " << branches.size() << " branch(es), " << points.size()
    << " isolated point(s)\n";
  for (const auto& br : branches)
    for (const auto& p : br.points)
      o << "v " << num17(p[0]) << ' ' << num17(p[1]) << ' ' << num17(p[2]) << '\n';
  for (const auto& p : points)
    o << "v " << num17(p[0]) << ' ' << num17(p[1]) << ' ' << num17(p[2]) << '\n';
  size_t base = 1;
  for (const auto& br : branches) {
    size_t n = br.points.size();
    if (n == 0) continue;
    o << "# " << (br.kind.empty() ? "branch" : br.kind) << (br.closed ? " (closed)" : "") << '\n';
    if (n == 1) { // a polyline needs two vertices
      o << "p " << base << '\n';
    } else {
      o << 'l';
      for (size_t i = 0; i < n; ++i)
        o << ' ' << base + i;
      if (br.closed) o << ' ' << base;
      o << '\n';
    }
    base += n;
  }
  for (size_t i = 0; i < points.size(); ++i)
    o << "p " << base + i << '\n';
  return o.str();
}

std::string to_ply(const std::vector<Branch>& branches, const std::vector<Point3>& points) {
  size_t nv = points.size(), ne = 0;
  for (const auto& br : branches) {
    size_t n = br.points.size();
    nv += n;
    if (n >= 2) ne += br.closed && n >= 3 ? n : n - 1;
  }
  std::ostringstream o;
  o << "ply\nformat ascii 1.0\ncomment surfcert intersection curve: " << branches.size()
    << " branch(es), " << points.size() << " isolated point(s)\n"
    << "element vertex " << nv << "\nproperty double x\nproperty double y\nproperty double z\n"
    << "element edge " << ne << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (const auto& br : branches)
    for (const auto& p : br.points)
      o << num17(p[0]) << ' ' << num17(p[1]) << ' ' << num17(p[2]) << '\n';
  for (const auto& p : points)
    o << num17(p[0]) << ' ' << num17(p[1]) << ' ' << num17(p[2]) << '\n';
  size_t base = 0;
  for (const auto& br : branches) {
    size_t n = br.points.size();
    if (n >= 2) {
      for (size_t i = 0; i + 1 < n; ++i)
        o << base + i << ' ' << base + i + 1 << '\n';
      if (br.closed && n >= 3) o << base + n - 1 << ' ' << base << '\n';
    }
    base += n;
  }
  return o.str();
}

std::string to_svg(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Picture& pic) {
  // Views: (horizontal axis, vertical axis, axis looked along).
  const size_t view_axes[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};
  const char* axis_name[3] = {"x", "y", "z"};
  const double panel = 400, gap = 20, top = 50, inner_margin = 34;
  // The caption wrapped at spaces into lines of at most ~180 characters (one line overflowed
  // the picture).
  std::vector<std::string> caption_lines;
  {
    std::string line, word;
    std::istringstream words(pic.caption);
    while (words >> word) {
      if (!line.empty() && line.size() + 1 + word.size() > 180) {
        caption_lines.push_back(line);
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    if (!line.empty() || caption_lines.empty()) caption_lines.push_back(line);
  }
  const double width = 3 * panel + 4 * gap,
               height = top + panel + 70 + 18.0 * static_cast<double>(caption_lines.size() - 1);

  // Outlines of the ellipsoids, per view, in the view's (u, v) coordinates.
  struct Outline {
    int surface;
    size_t view;
    std::vector<std::array<double, 2>> pts;
  };
  std::vector<Outline> outlines;
  const core::QuadricMatrix* quadrics[2] = {&a, &b};
  for (int s = 0; s < 2; ++s) {
    if (quadrics[s]->kind() != core::QuadricKind::Ellipsoid) continue;
    for (size_t v = 0; v < 3; ++v)
      if (auto pts = silhouette(*quadrics[s], view_axes[v][2], 180))
        outlines.push_back({s, v, std::move(*pts)});
  }

  // 3D bounding box of everything drawn.
  std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  auto grow = [&](size_t k, double x) {
    if (std::isfinite(x)) {
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  };
  for (const auto& br : pic.branches)
    for (const auto& p : br.points)
      if (finite(p))
        for (size_t k = 0; k < 3; ++k)
          grow(k, p[k]);
  for (const auto& p : pic.special_points)
    if (finite(p))
      for (size_t k = 0; k < 3; ++k)
        grow(k, p[k]);
  for (const auto& o : outlines)
    for (const auto& q : o.pts) {
      grow(view_axes[o.view][0], q[0]);
      grow(view_axes[o.view][1], q[1]);
    }
  if (pic.box)
    for (size_t k = 0; k < 3; ++k) {
      grow(k, pic.box->min[k]);
      grow(k, pic.box->max[k]);
    }
  // Halves throughout: a box from -1e308 to 1e308 is 2e308 wide, past the doubles (its
  // rectangle was drawn at x="-inf" with width="inf").
  double half = 0;
  for (size_t k = 0; k < 3; ++k) {
    if (!(lo[k] <= hi[k])) {
      lo[k] = -1;
      hi[k] = 1;
    }
    half = std::max(half, 0.5 * hi[k] - 0.5 * lo[k]);
  }
  if (!(half > 0)) half = 1;
  for (size_t k = 0; k < 3; ++k) { // at least 2 half wide, centred on the data
    double mid = 0.5 * lo[k] + 0.5 * hi[k];
    lo[k] = mid - half;
    hi[k] = mid + half;
  }
  const double scale = 0.5 * (panel - 2 * inner_margin) / half; // pixels per unit

  auto px = [&](size_t v, double u) {
    size_t k = view_axes[v][0];
    return gap + v * (panel + gap) + inner_margin + (0.5 * u - 0.5 * lo[k]) * (2 * scale);
  };
  auto py = [&](size_t v, double w) {
    size_t k = view_axes[v][1];
    return top + panel - inner_margin - (0.5 * w - 0.5 * lo[k]) * (2 * scale);
  };

  // "Nice" grid step: 1, 2 or 5 times a power of ten, about 5 cells per panel.
  double raw = 0.4 * half, p10 = std::pow(10.0, std::floor(std::log10(raw)));
  double step = raw / p10 < 1.5   ? p10
                : raw / p10 < 3.5 ? 2 * p10
                : raw / p10 < 7.5 ? 5 * p10
                                  : 10 * p10;
  // Per axis, an offset subtracted from its tick labels (and named with the axis) where %g's
  // six digits cannot tell the ticks apart: a circle 2e-4 across 1000 from the origin had
  // every tick labelled "1000". The offset is the middle rounded to 10 steps.
  std::array<double, 3> offset{0, 0, 0};
  for (size_t k = 0; k < 3; ++k) {
    const double mid = 0.5 * lo[k] + 0.5 * hi[k],
                 big = std::max(std::fabs(lo[k]), std::fabs(hi[k]));
    if (big > 1e4 * step) offset[k] = std::round(mid / (10 * step)) * (10 * step);
  }
  auto label = [&](double t, size_t k) {
    // A whole number of steps from the offset (the ticks' running sums, t - offset, drift by
    // a few ulps of t: "-1.11022e-16" for 0 beside an offset of -1).
    t = std::round((t - offset[k]) / step) * step;
    if (std::fabs(t) < 1e-9 * step) t = 0;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", t);
    return std::string(buf);
  };
  // "x", or "x - 1000.0001" with enough digits to tell the offset from its neighbours.
  auto axis_label = [&](size_t k) {
    std::string name = axis_name[k];
    if (offset[k] == 0) return name;
    const int digits =
        std::clamp(static_cast<int>(std::ceil(std::log10(std::fabs(offset[k]) / step))) + 2, 1, 17);
    char buf[48];
    std::snprintf(buf, sizeof buf, " %s %.*g", offset[k] < 0 ? "+" : "-", digits,
                  std::fabs(offset[k]));
    return name + buf;
  };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << width
    << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n"
    << "<title>surfcert: intersection curve of two quadrics</title>\n"
    << "<style>text{font-family:sans-serif} .grid{stroke:#e6e6e6;stroke-width:1} "
       ".frame{fill:none;stroke:#999;stroke-width:1} .tick{fill:#888;font-size:10px} "
       ".axis{fill:#444;font-size:13px;font-style:italic} .title{fill:#222;font-size:14px} "
       ".outline{fill:none;stroke-width:1.5} .outline-a{stroke:#1f77b4} "
       ".outline-b{stroke:#2ca02c} .curve{fill:none;stroke-width:2;stroke-linejoin:round} "
       ".special{fill:#ff8c00;stroke:#222;stroke-width:1} .caption{fill:#111;font-size:14px} "
       ".legend{font-size:12px} .box{fill:none;stroke:#bbb;stroke-dasharray:4 3} "
       ".inset-frame{fill:#fff;stroke:#555;stroke-width:1} .inset-label{fill:#555;font-size:10px} "
       ".inset-link{stroke:#555;stroke-width:0.8;fill:none}</style>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
    << "\" fill=\"#ffffff\"/>\n<defs>\n";
  for (size_t v = 0; v < 3; ++v)
    o << "<clipPath id=\"panel" << v << "\"><rect x=\"" << num2(gap + v * (panel + gap))
      << "\" y=\"" << num2(top) << "\" width=\"" << panel << "\" height=\"" << panel
      << "\"/></clipPath>\n";
  o << "</defs>\n";

  // Legend.
  o << "<g class=\"legend\"><text x=\"" << gap << "\" y=\"18\" fill=\"#1f77b4\">surface A"
    << "</text><text x=\"" << gap + 80 << "\" y=\"18\" fill=\"#2ca02c\">surface B</text>"
    << "<text x=\"" << gap + 160 << "\" y=\"18\" fill=\"#d62728\">curve</text>"
    << "<text x=\"" << gap + 210 << "\" y=\"18\" fill=\"#111111\">double curve</text>"
    << "<text x=\"" << gap + 305 << "\" y=\"18\" fill=\"#ff8c00\">special point</text></g>\n";

  for (size_t v = 0; v < 3; ++v) {
    size_t ku = view_axes[v][0], kv = view_axes[v][1], kw = view_axes[v][2];
    double x0 = gap + v * (panel + gap);
    o << "<g class=\"view\" id=\"view-" << axis_name[ku] << axis_name[kv] << "\">\n";
    o << "<text class=\"title\" x=\"" << num2(x0 + 4) << "\" y=\"" << num2(top - 8)
      << "\">view along " << axis_name[kw] << " (" << axis_name[ku] << "-" << axis_name[kv]
      << ")</text>\n";
    o << "<rect class=\"frame\" x=\"" << num2(x0) << "\" y=\"" << num2(top) << "\" width=\""
      << panel << "\" height=\"" << panel << "\"/>\n";
    // Grid and tick labels.
    o << "<g clip-path=\"url(#panel" << v << ")\">\n";
    double u_lo = lo[ku] - inner_margin / scale, u_hi = hi[ku] + inner_margin / scale;
    double v_lo = lo[kv] - inner_margin / scale, v_hi = hi[kv] + inner_margin / scale;
    for (double t = std::ceil(u_lo / step) * step; t <= u_hi; t += step)
      o << "<line class=\"grid\" x1=\"" << num2(px(v, t)) << "\" y1=\"" << num2(top) << "\" x2=\""
        << num2(px(v, t)) << "\" y2=\"" << num2(top + panel) << "\"/>\n";
    for (double t = std::ceil(v_lo / step) * step; t <= v_hi; t += step)
      o << "<line class=\"grid\" x1=\"" << num2(x0) << "\" y1=\"" << num2(py(v, t)) << "\" x2=\""
        << num2(x0 + panel) << "\" y2=\"" << num2(py(v, t)) << "\"/>\n";
    o << "</g>\n";
    for (double t = std::ceil(lo[ku] / step) * step; t <= hi[ku] + 1e-9 * step; t += step)
      o << "<text class=\"tick\" text-anchor=\"middle\" x=\"" << num2(px(v, t)) << "\" y=\""
        << num2(top + panel - 6) << "\">" << label(t, ku) << "</text>\n";
    for (double t = std::ceil(lo[kv] / step) * step; t <= hi[kv] + 1e-9 * step; t += step)
      o << "<text class=\"tick\" x=\"" << num2(x0 + 4) << "\" y=\"" << num2(py(v, t) + 3) << "\">"
        << label(t, kv) << "</text>\n";
    o << "<text class=\"axis\" text-anchor=\"end\" x=\"" << num2(x0 + panel - 6) << "\" y=\""
      << num2(top + panel - 18) << "\">" << axis_label(ku) << "</text>\n";
    o << "<text class=\"axis\" x=\"" << num2(x0 + 22) << "\" y=\"" << num2(top + 16) << "\">"
      << axis_label(kv) << "</text>\n";
    // Outlines.
    o << "<g clip-path=\"url(#panel" << v << ")\">\n";
    for (const auto& ol : outlines) {
      if (ol.view != v) continue;
      o << "<path class=\"outline " << (ol.surface == 0 ? "outline-a" : "outline-b") << "\" d=\"";
      for (size_t i = 0; i < ol.pts.size(); ++i)
        o << (i == 0 ? "M" : " L") << num2(px(v, ol.pts[i][0])) << ',' << num2(py(v, ol.pts[i][1]));
      o << " Z\"/>\n";
    }
    // Outlines of the other quadrics: their view conics traced inside the box's projection
    // (or the panel).
    for (int sf = 0; sf < 2; ++sf) {
      if (quadrics[sf]->kind() == core::QuadricKind::Ellipsoid) continue;
      const auto c = view_conic(*quadrics[sf], kw);
      if (!c) continue;
      double u0 = lo[ku] - inner_margin / scale, u1 = hi[ku] + inner_margin / scale;
      double w0 = lo[kv] - inner_margin / scale, w1 = hi[kv] + inner_margin / scale;
      if (pic.box) {
        u0 = pic.box->min[ku], u1 = pic.box->max[ku];
        w0 = pic.box->min[kv], w1 = pic.box->max[kv];
      }
      const auto segs = conic_segments(*c, u0, u1, w0, w1, 160);
      if (segs.empty()) continue;
      o << "<path class=\"outline " << (sf == 0 ? "outline-a" : "outline-b") << "\" d=\"";
      for (const auto& sg : segs)
        o << "M" << num2(px(v, sg[0])) << ',' << num2(py(v, sg[1])) << "L" << num2(px(v, sg[2]))
          << ',' << num2(py(v, sg[3]));
      o << "\"/>\n";
    }
    if (pic.box)
      o << "<rect class=\"box\" x=\"" << num2(px(v, pic.box->min[ku])) << "\" y=\""
        << num2(py(v, pic.box->max[kv])) << "\" width=\""
        << num2((0.5 * pic.box->max[ku] - 0.5 * pic.box->min[ku]) * (2 * scale)) << "\" height=\""
        << num2((0.5 * pic.box->max[kv] - 0.5 * pic.box->min[kv]) * (2 * scale)) << "\"/>\n";
    o << "</g>\n</g>\n";
  }

  // Branches: one group each, with its three projections.
  for (size_t bi = 0; bi < pic.branches.size(); ++bi) {
    const auto& br = pic.branches[bi];
    bool dbl = br.kind.rfind("double", 0) == 0;
    o << "<g class=\"branch\" id=\"branch-" << bi << "\" data-kind=\"" << xml_escape(br.kind)
      << "\" stroke=\"" << (dbl ? "#111111" : "#d62728") << "\""
      << (dbl ? " stroke-width=\"3\"" : "") << ">\n";
    for (size_t v = 0; v < 3; ++v) {
      size_t ku = view_axes[v][0], kv = view_axes[v][1];
      o << "<path class=\"curve\" clip-path=\"url(#panel" << v << ")\" d=\"";
      bool pen = false;
      double lx = 0, ly = 0;
      size_t emitted = 0;
      for (size_t i = 0; i < br.points.size(); ++i) {
        const auto& p = br.points[i];
        if (!finite(p)) {
          pen = false;
          continue;
        }
        double x = px(v, p[ku]), y = py(v, p[kv]);
        bool last = i + 1 == br.points.size();
        if (pen && !last && std::hypot(x - lx, y - ly) < 0.4) continue; // below display resolution
        o << (emitted == 0 ? "" : " ") << (pen ? "L" : "M") << num2(x) << ',' << num2(y);
        pen = true;
        lx = x;
        ly = y;
        ++emitted;
      }
      if (emitted == 1) // a single point: draw a dot
        o << " l0.01,0";
      if (br.closed && emitted > 2) o << " Z";
      if (emitted == 0) o << "M0,0";
      o << "\"" << (emitted <= 1 ? " stroke-linecap=\"round\"" : "") << "/>\n";
    }
    o << "</g>\n";
  }

  // Zoomed insets: a branch smaller than 6 pixels in every view is drawn again, magnified,
  // in a framed square at the top right of the view where it is largest, linked to where it
  // lies.
  std::array<int, 3> insets_in{0, 0, 0};
  const double inset = 110;
  for (size_t bi = 0; bi < pic.branches.size(); ++bi) {
    const auto& br = pic.branches[bi];
    std::array<double, 3> blo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, bhi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const auto& p : br.points)
      if (finite(p))
        for (size_t k = 0; k < 3; ++k)
          blo[k] = std::min(blo[k], p[k]), bhi[k] = std::max(bhi[k], p[k]);
    if (br.points.size() < 2 || !(blo[0] <= bhi[0])) continue;
    // The view where the branch shows most: the largest enclosed area of its projection
    // (a loop seen edge-on is a segment), then the larger extent.
    size_t best = 0;
    double ext = 0, best_key = -1;
    for (size_t v = 0; v < 3; ++v) {
      const size_t ku = view_axes[v][0], kv = view_axes[v][1];
      const double e = std::max(bhi[ku] - blo[ku], bhi[kv] - blo[kv]);
      double area = 0;
      for (size_t i = 0; i < br.points.size(); ++i) {
        const auto& p = br.points[i];
        const auto& q = br.points[(i + 1) % br.points.size()];
        area += p[ku] * q[kv] - q[ku] * p[kv];
      }
      const double key = std::fabs(area) + 1e-3 * e * e;
      ext = std::max(ext, e);
      if (key > best_key) best_key = key, best = v;
    }
    if (!(ext * scale < 6) || !(ext > 0) || insets_in[best] >= 3) continue;
    const size_t v = best, ku = view_axes[v][0], kv = view_axes[v][1];
    const double x0 = gap + v * (panel + gap) + panel - inset - 6,
                 y0 = top + 6 + insets_in[best]++ * (inset + 6);
    const double zoom = 0.8 * inset / ext; // world -> inset pixels
    const double cu = 0.5 * (blo[ku] + bhi[ku]), cv = 0.5 * (blo[kv] + bhi[kv]);
    auto ix = [&](double u) { return x0 + inset / 2 + (u - cu) * zoom; };
    auto iy = [&](double w) { return y0 + inset / 2 - (w - cv) * zoom; };
    o << "<g class=\"inset\" data-branch=\"" << bi << "\">\n";
    o << "<path class=\"inset-link\" d=\"M" << num2(px(v, cu)) << ',' << num2(py(v, cv)) << "L"
      << num2(x0) << ',' << num2(y0 + inset) << "\"/>\n";
    o << "<circle class=\"inset-link\" cx=\"" << num2(px(v, cu)) << "\" cy=\"" << num2(py(v, cv))
      << "\" r=\"7\"/>\n";
    o << "<rect class=\"inset-frame\" x=\"" << num2(x0) << "\" y=\"" << num2(y0) << "\" width=\""
      << inset << "\" height=\"" << inset << "\"/>\n";
    o << "<path class=\"curve\" stroke=\"#d62728\" d=\"";
    for (size_t i = 0; i < br.points.size(); ++i)
      o << (i == 0 ? "M" : " L") << num2(ix(br.points[i][ku])) << ',' << num2(iy(br.points[i][kv]));
    if (br.closed) o << " Z";
    o << "\"/>\n";
    for (const auto& p : pic.special_points)
      if (finite(p) && std::fabs(p[ku] - cu) <= ext && std::fabs(p[kv] - cv) <= ext)
        o << "<circle class=\"special\" cx=\"" << num2(ix(p[ku])) << "\" cy=\"" << num2(iy(p[kv]))
          << "\" r=\"3\"/>\n";
    char zl[48];
    std::snprintf(zl, sizeof zl, "zoom x%.3g", zoom / scale);
    o << "<text class=\"inset-label\" x=\"" << num2(x0 + 4) << "\" y=\"" << num2(y0 + inset - 4)
      << "\">" << zl << "</text>\n</g>\n";
  }

  // Special points.
  for (const auto& p : pic.special_points) {
    if (!finite(p)) continue;
    for (size_t v = 0; v < 3; ++v)
      o << "<circle class=\"special\" cx=\"" << num2(px(v, p[view_axes[v][0]])) << "\" cy=\""
        << num2(py(v, p[view_axes[v][1]])) << "\" r=\"4.5\"/>\n";
  }

  for (size_t i = 0; i < caption_lines.size(); ++i)
    o << "<text class=\"caption\" x=\"" << gap << "\" y=\""
      << num2(top + panel + 34 + 18.0 * static_cast<double>(i)) << "\">"
      << xml_escape(caption_lines[i]) << "</text>\n";
  o << "</svg>\n";
  return o.str();
}

} // namespace surfcert::trace
