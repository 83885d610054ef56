// trace exports: OBJ and PLY element counts for known branches (parsed back), SVG checked by a
// small well-formedness parser of our own and by xmllint, one <g class="branch"> per branch
// with its three view paths, special points, escaped caption, ellipsoid outlines (the sphere's
// outline in the x-y view must coincide with the equator it is tangent to), outlines of
// cylinders (cross-section circle, silhouette lines at the curve's extent), zoomed insets for
// tiny components, and rasterised by rsvg-convert into a PNG.
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/conics.hpp"
#include "surfcert/trace/export.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

using namespace surfcert;
using trace::Branch;
using trace::Point3;

namespace {

constexpr double kPi = 3.14159265358979323846;

core::QuadricMatrix q(const std::string& s) {
  return core::io::quadric_from_equation(s, {"test", 1, 1, ""});
}

Branch circle_branch(int n, double r, double z) {
  Branch b;
  b.kind = "conic";
  b.closed = true;
  for (int i = 0; i < n; ++i)
    b.points.push_back({r * std::cos(2 * kPi * i / n), r * std::sin(2 * kPi * i / n), z});
  return b;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string l;
  while (std::getline(in, l))
    out.push_back(l);
  return out;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1))
    ++n;
  return n;
}

/// Minimal XML well-formedness check: one root element, properly nested and matching tags,
/// quoted attributes without '<' and with unique names, known or numeric entities only, no
/// stray '<' or '&' in text. Returns an empty string when fine, else the problem.
std::string xml_problem(const std::string& s) {
  size_t i = 0;
  std::vector<std::string> stack;
  int roots = 0;
  auto entity_ok = [&](size_t at) {
    size_t e = s.find(';', at);
    if (e == std::string::npos || e - at > 10) return false;
    std::string name = s.substr(at + 1, e - at - 1);
    static const std::regex ent("amp|lt|gt|quot|apos|#[0-9]+|#x[0-9a-fA-F]+");
    return std::regex_match(name, ent);
  };
  auto is_name = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == ':' ||
           c == '.';
  };
  if (s.compare(0, 5, "<?xml") == 0) {
    i = s.find("?>");
    if (i == std::string::npos) return "unterminated declaration";
    i += 2;
  }
  while (i < s.size()) {
    char c = s[i];
    if (c == '&') {
      if (!entity_ok(i)) return "bad entity at " + std::to_string(i);
      ++i;
      continue;
    }
    if (c != '<') {
      if (stack.empty() && !std::isspace(static_cast<unsigned char>(c)))
        return "text outside the root";
      ++i;
      continue;
    }
    if (s.compare(i, 4, "<!--") == 0) {
      size_t e = s.find("-->", i);
      if (e == std::string::npos) return "unterminated comment";
      i = e + 3;
      continue;
    }
    bool closing = i + 1 < s.size() && s[i + 1] == '/';
    size_t j = i + (closing ? 2 : 1);
    size_t ns = j;
    while (j < s.size() && is_name(s[j]))
      ++j;
    std::string name = s.substr(ns, j - ns);
    if (name.empty()) return "bad tag at " + std::to_string(i);
    if (closing) {
      while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j])))
        ++j;
      if (j >= s.size() || s[j] != '>') return "bad closing tag " + name;
      if (stack.empty() || stack.back() != name) return "mismatched </" + name + ">";
      stack.pop_back();
      i = j + 1;
      continue;
    }
    std::vector<std::string> attrs;
    bool self_close = false;
    for (;;) {
      while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j])))
        ++j;
      if (j >= s.size()) return "unterminated tag " + name;
      if (s[j] == '>') {
        ++j;
        break;
      }
      if (s.compare(j, 2, "/>") == 0) {
        self_close = true;
        j += 2;
        break;
      }
      size_t as = j;
      while (j < s.size() && is_name(s[j]))
        ++j;
      std::string an = s.substr(as, j - as);
      if (an.empty() || j >= s.size() || s[j] != '=') return "bad attribute in " + name;
      for (const auto& x : attrs)
        if (x == an) return "duplicate attribute " + an;
      attrs.push_back(an);
      ++j;
      if (j >= s.size() || (s[j] != '"' && s[j] != '\'')) return "unquoted attribute " + an;
      char qc = s[j];
      size_t e = s.find(qc, j + 1);
      if (e == std::string::npos) return "unterminated attribute " + an;
      for (size_t k = j + 1; k < e; ++k) {
        if (s[k] == '<') return "'<' in attribute " + an;
        if (s[k] == '&' && !entity_ok(k)) return "bad entity in attribute " + an;
      }
      j = e + 1;
    }
    if (stack.empty()) {
      if (++roots > 1) return "two root elements";
    }
    if (!self_close) stack.push_back(name);
    i = j;
  }
  if (!stack.empty()) return "unclosed <" + stack.back() + ">";
  return roots == 1 ? "" : "no root element";
}

struct TempDir {
  std::filesystem::path dir;
  TempDir() {
    dir = std::filesystem::temp_directory_path() /
          ("surfcert_export_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    auto p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
};

bool have(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

/// Pixel coordinates of a path's "M/L x,y" vertices.
std::vector<std::array<double, 2>> path_points(const std::string& d) {
  std::vector<std::array<double, 2>> out;
  static const std::regex pt("[ML]\\s*(-?[0-9.]+),(-?[0-9.]+)");
  for (std::sregex_iterator it(d.begin(), d.end(), pt), end; it != end; ++it)
    out.push_back({std::stod((*it)[1]), std::stod((*it)[2])});
  return out;
}

std::array<double, 4> bbox(const std::vector<std::array<double, 2>>& p) {
  std::array<double, 4> b{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& x : p) {
    b[0] = std::min(b[0], x[0]);
    b[1] = std::min(b[1], x[1]);
    b[2] = std::max(b[2], x[0]);
    b[3] = std::max(b[3], x[1]);
  }
  return b;
}

} // namespace

TEST(Export, ObjCounts) {
  Branch open;
  open.kind = "line";
  open.closed = false;
  for (int i = 0; i < 10; ++i)
    open.points.push_back({0.1 * i, 2.0, -1.0});
  std::vector<Branch> br = {circle_branch(100, 1, 0), open};
  std::vector<Point3> pts = {{3, 3, 3}, {-3, 0.5, 1e-7}};
  auto obj = trace::to_obj(br, pts);
  size_t v = 0, l = 0, p = 0;
  std::vector<std::vector<long>> elems;
  for (const auto& line : lines_of(obj)) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      double x, y, z;
      ASSERT_TRUE(static_cast<bool>(in >> x >> y >> z)) << line;
      ++v;
    } else if (tag == "l" || tag == "p") {
      (tag == "l" ? l : p)++;
      std::vector<long> idx;
      long k;
      while (in >> k)
        idx.push_back(k);
      elems.push_back(idx);
    } else {
      ASSERT_TRUE(tag.empty() || tag[0] == '#') << line;
    }
  }
  EXPECT_EQ(v, 112u);
  EXPECT_EQ(l, 2u);
  EXPECT_EQ(p, 2u);
  ASSERT_EQ(elems.size(), 4u);
  EXPECT_EQ(elems[0].size(), 101u); // closed: first vertex repeated
  EXPECT_EQ(elems[0].front(), 1);
  EXPECT_EQ(elems[0].back(), 1);
  EXPECT_EQ(elems[1].size(), 10u);
  EXPECT_EQ(elems[1].front(), 101);
  EXPECT_EQ(elems[2], std::vector<long>{111});
  EXPECT_EQ(elems[3], std::vector<long>{112});
  // Vertices are written exactly (round trip of %.17g).
  EXPECT_NE(obj.find("v -3 0.5 9.9999999999999995e-08"), std::string::npos);
}

TEST(Export, PlyCounts) {
  Branch open;
  open.kind = "line";
  open.closed = false;
  for (int i = 0; i < 10; ++i)
    open.points.push_back({0.1 * i, 2.0, -1.0});
  std::vector<Branch> br = {circle_branch(100, 1, 0), open};
  std::vector<Point3> pts = {{3, 3, 3}};
  auto ply = trace::to_ply(br, pts);
  auto ls = lines_of(ply);
  ASSERT_GE(ls.size(), 3u);
  EXPECT_EQ(ls[0], "ply");
  EXPECT_EQ(ls[1], "format ascii 1.0");
  size_t nv = 0, ne = 0, header_end = 0;
  for (size_t i = 0; i < ls.size(); ++i) {
    if (ls[i].rfind("element vertex ", 0) == 0) nv = std::stoul(ls[i].substr(15));
    if (ls[i].rfind("element edge ", 0) == 0) ne = std::stoul(ls[i].substr(13));
    if (ls[i] == "end_header") {
      header_end = i;
      break;
    }
  }
  ASSERT_GT(header_end, 0u);
  EXPECT_EQ(nv, 111u);
  EXPECT_EQ(ne, 100u + 9u);
  ASSERT_EQ(ls.size(), header_end + 1 + nv + ne);
  for (size_t i = 0; i < nv; ++i) {
    std::istringstream in(ls[header_end + 1 + i]);
    double x, y, z;
    EXPECT_TRUE(static_cast<bool>(in >> x >> y >> z));
  }
  size_t closing = 0;
  for (size_t i = 0; i < ne; ++i) {
    std::istringstream in(ls[header_end + 1 + nv + i]);
    long a, b;
    ASSERT_TRUE(static_cast<bool>(in >> a >> b));
    EXPECT_GE(a, 0);
    EXPECT_LT(b, 110); // never an edge to the isolated point (index 110)
    EXPECT_TRUE(b == a + 1 || (a == 99 && b == 0)) << a << " " << b;
    closing += a == 99 && b == 0;
  }
  EXPECT_EQ(closing, 1u);
}

TEST(Export, XmlCheckerRejectsMalformed) {
  EXPECT_EQ(xml_problem("<a><b x=\"1\"/>t &amp; u</a>"), "");
  EXPECT_NE(xml_problem("<a><b></a></b>"), "");
  EXPECT_NE(xml_problem("<a>x < y</a>"), "");
  EXPECT_NE(xml_problem("<a>R&D</a>"), "");
  EXPECT_NE(xml_problem("<a x=1/>"), "");
  EXPECT_NE(xml_problem("<a/><b/>"), "");
}

TEST(Export, SvgCase13WithSpecialPoints) {
  auto a = q("x^2/4 + y^2 + z^2 - 1"), b = q("x^2 + y^2/4 + z^2 - 1");
  auto r = certify::classify_qsic(a, b, certify::Mode::Exact);
  certify::complete_report_data(r, a, b);
  ASSERT_EQ(r.tu_case, 13);
  trace::Picture pic;
  pic.branches = trace::conic_branches(a, b, r.facts, trace::TraceOptions{});
  ASSERT_EQ(pic.branches.size(), 2u);
  for (const auto& sp : r.special_points)
    pic.special_points.push_back(sp.approx);
  ASSERT_EQ(pic.special_points.size(), 2u);
  pic.caption = "case 13 two_conics_crossing: <two> ellipses & \"crossing\" 'twice' \x01 "
                "\xff (certified) \xc3\xa9";
  auto svg = trace::to_svg(a, b, pic);

  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "<g class=\"branch\""), 2u);
  EXPECT_EQ(count(svg, "class=\"curve\""), 6u);
  EXPECT_EQ(count(svg, "<circle class=\"special\""), 6u);
  EXPECT_EQ(count(svg, "outline-a\" d="), 3u);
  EXPECT_EQ(count(svg, "outline-b\" d="), 3u);
  EXPECT_EQ(count(svg, "<text class=\"caption\""), 1u);
  EXPECT_NE(svg.find("&lt;two&gt; ellipses &amp; &quot;crossing&quot; &apos;twice&apos;"),
            std::string::npos);
  EXPECT_NE(svg.find("(certified) \xc3\xa9"), std::string::npos); // valid UTF-8 kept
  EXPECT_EQ(svg.find('\x01'), std::string::npos);
  EXPECT_EQ(svg.find('\xff'), std::string::npos);
  EXPECT_NE(svg.find("viewBox=\"0 0 "), std::string::npos);
  // Every branch group holds exactly three view paths.
  size_t groups = 0;
  for (size_t at = svg.find("<g class=\"branch\""); at != std::string::npos;
       at = svg.find("<g class=\"branch\"", at + 1)) {
    ++groups;
    size_t end = svg.find("</g>", at);
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(count(svg.substr(at, end - at), "<path class=\"curve\""), 3u);
  }
  EXPECT_EQ(groups, 2u);

  TempDir tmp;
  std::string file = tmp.write("case13.svg", svg);
  if (have("xmllint"))
    EXPECT_EQ(std::system(("xmllint --noout '" + file + "' 2>/dev/null").c_str()), 0);
  else
    ADD_FAILURE() << "xmllint not installed (Debian package libxml2-utils)";
  if (!have("rsvg-convert")) {
    ADD_FAILURE() << "rsvg-convert not installed (Debian package librsvg2-bin)";
    return;
  }
  std::string png = (tmp.dir / "case13.png").string();
  ASSERT_EQ(std::system(("rsvg-convert -o '" + png + "' '" + file + "' 2>/dev/null").c_str()), 0);
  std::ifstream in(png, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(bytes.size(), 5000u);
  // IHDR: width and height as declared by the SVG (1280 x 520).
  ASSERT_GE(bytes.size(), 24u);
  auto be32 = [&](size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(bytes[at])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 3]));
  };
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_GT(be32(16), 600u);
  EXPECT_GT(be32(20), 200u);
}

TEST(Export, SvgOutlineMatchesTangentEquator) {
  // Sphere and cylinder tangent along the equator: the sphere's outline seen along z is the
  // double conic itself, so both paths of the x-y view have the same pixel bounding box; the
  // cylinder's outline there is its cross-section, the same circle, and in the other views its
  // silhouette lines.
  auto a = q("x^2 + y^2 + z^2 - 1"), b = q("x^2 + y^2 - 1");
  auto r = certify::classify_qsic(a, b, certify::Mode::Exact);
  ASSERT_EQ(r.tu_case, 21);
  trace::Picture pic;
  pic.branches = trace::conic_branches(a, b, r.facts, trace::TraceOptions{});
  ASSERT_EQ(pic.branches.size(), 1u);
  pic.caption = "case 21 double_conic";
  auto svg = trace::to_svg(a, b, pic);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "outline-a\" d="), 3u);
  EXPECT_EQ(count(svg, "outline-b\" d="), 3u);
  EXPECT_EQ(count(svg, "<g class=\"branch\""), 1u);
  EXPECT_EQ(count(svg, "<circle class=\"special\""), 0u);

  auto attr_after = [&](const std::string& marker) {
    size_t at = svg.find(marker);
    EXPECT_NE(at, std::string::npos) << marker;
    if (at == std::string::npos) return std::string();
    size_t d = svg.find(" d=\"", at) + 4, e = svg.find('"', d);
    return svg.substr(d, e - d);
  };
  std::string dout = attr_after("outline outline-a"), dcurve = attr_after("<path class=\"curve\"");
  auto bo = bbox(path_points(dout)), bc = bbox(path_points(dcurve));
  for (size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(bo[k], bc[k], 0.3) << k;
  EXPECT_GT(bo[2] - bo[0], 100); // a visible circle
  EXPECT_NEAR(bo[2] - bo[0], bo[3] - bo[1], 0.3);
  // The cylinder's cross-section (marching squares on a 2.5-pixel grid) is the same circle.
  auto bb = bbox(path_points(attr_after("outline outline-b")));
  for (size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(bb[k], bc[k], 1.0) << k;
}

// Outlines of non-ellipsoids and the zoomed inset: Steinmetz (cylinders along y and x) in a box
// 100 times the curve's size. Seen along z the cylinder x^2 + z^2 = 1 is the two lines x = +-1,
// spanning the same x range as the curve there; each ellipse (2 wide: ~3 pixels) gets an inset,
// where it is drawn 0.8 of the inset's 110 pixels wide.
TEST(Export, SvgOutlinesOfCylindersAndInsets) {
  auto a = q("x^2 + z^2 - 1"), b = q("y^2 + z^2 - 1");
  trace::TraceOptions opt;
  trace::Box box;
  box.min = {-100, -100, -100};
  box.max = {100, 100, 100};
  opt.box = box;
  auto r = trace::intersect_curve(a, b, certify::Mode::Exact, opt);
  ASSERT_EQ(r.branches.size(), 2u);
  trace::Picture pic;
  pic.branches = r.branches;
  pic.caption = trace::curve_caption(r);
  pic.box = r.box;
  auto svg = trace::to_svg(a, b, pic);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "outline-a\" d="), 3u); // lines x = +-1 (z, y views), the circle (x view)
  EXPECT_EQ(count(svg, "outline-b\" d="), 3u);
  EXPECT_EQ(count(svg, "<g class=\"inset\""), 2u);
  EXPECT_EQ(count(svg, "<rect class=\"box\""), 3u);
  auto attr_after = [&](const std::string& marker, size_t from = 0) {
    size_t at = svg.find(marker, from);
    EXPECT_NE(at, std::string::npos) << marker;
    if (at == std::string::npos) return std::string();
    size_t d = svg.find(" d=\"", at) + 4, e = svg.find('"', d);
    return svg.substr(d, e - d);
  };
  // The first outline-a path is the x-y view's; the first curve path too (branch 0, view 0).
  auto bo = bbox(path_points(attr_after("outline outline-a")));
  auto bc = bbox(path_points(attr_after("<path class=\"curve\"")));
  EXPECT_NEAR(bo[0], bc[0], 0.5);
  EXPECT_NEAR(bo[2], bc[2], 0.5);
  EXPECT_GT(bo[3] - bo[1], 300); // the lines run through the box
  // The inset's curve: 0.8 * 110 pixels across (its larger extent).
  auto bi = bbox(path_points(attr_after("<path class=\"curve\"", svg.find("<g class=\"inset\""))));
  EXPECT_NEAR(std::max(bi[2] - bi[0], bi[3] - bi[1]), 88, 0.5);

  // The same curve at its own scale: no inset.
  pic.box.reset();
  EXPECT_EQ(count(trace::to_svg(a, b, pic), "<g class=\"inset\""), 0u);
}

TEST(Export, EmptyPictureIsValid) {
  auto a = q("x^2 + y^2 + z^2 - 1"), b = q("x^2 + y^2 + z^2 - 4");
  trace::Picture pic;
  pic.caption = "empty";
  auto svg = trace::to_svg(a, b, pic);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "<g class=\"branch\""), 0u);
  EXPECT_EQ(count(svg, "outline-a\" d="), 3u);
  EXPECT_EQ(trace::to_obj({}, {}).find("\nv "), std::string::npos);
}

// A circle 2e-4 across, 1000 from the origin (a pipe of radius 1e-4 cut by the plane
// z = 1000): with %g's six digits every tick of the x axis read "1000". The labels are now
// taken from an offset named with the axis ("x - 1000"): in each view, the horizontal ticks
// are distinct numbers in arithmetic progression, and offset + label lies in the box.
TEST(Export, TickLabelsOfASmallCurveFarFromTheOrigin) {
  auto a = q("(x - 1000)^2 + y^2 - 1/100000000"), b = q("z - 1000");
  auto r = trace::intersect_curve(a, b, certify::Mode::Filtered, {});
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  ASSERT_TRUE(r.box.has_value());
  trace::Picture pic;
  pic.branches = r.branches;
  pic.caption = trace::curve_caption(r);
  pic.box = r.box;
  const auto svg = trace::to_svg(a, b, pic);
  EXPECT_EQ(xml_problem(svg), "");
  const std::regex tick_re("<text class=\"tick\" text-anchor=\"middle\"[^>]*>([^<]*)</text>");
  const std::regex axis_re(
      "<text class=\"axis\" text-anchor=\"end\"[^>]*>([xyz])( - ([^<]*))?</text>");
  size_t views = 0;
  for (size_t at = svg.find("<g class=\"view\""); at != std::string::npos;
       at = svg.find("<g class=\"view\"", at + 1)) {
    const size_t end = svg.find("<g class=\"view\"", at + 1);
    const std::string view =
        svg.substr(at, end == std::string::npos ? std::string::npos : end - at);
    std::vector<double> ticks;
    for (auto it = std::sregex_iterator(view.begin(), view.end(), tick_re);
         it != std::sregex_iterator(); ++it)
      ticks.push_back(std::stod((*it)[1].str()));
    std::smatch axis;
    ASSERT_TRUE(std::regex_search(view, axis, axis_re)) << view.substr(0, 200);
    const size_t k = static_cast<size_t>(axis[1].str()[0] - 'x');
    const double offset = axis[3].matched ? std::stod(axis[3].str()) : 0.0;
    ASSERT_GE(ticks.size(), 3u);
    const double step = ticks[1] - ticks[0];
    EXPECT_GT(step, 0);
    for (size_t i = 1; i < ticks.size(); ++i)
      EXPECT_NEAR(ticks[i] - ticks[i - 1], step, 1e-9 * std::fabs(step)) << "view " << views;
    for (double t : ticks) {
      EXPECT_GE(offset + t, r.box->min[k] - 2 * step) << "view " << views;
      EXPECT_LE(offset + t, r.box->max[k] + 2 * step) << "view " << views;
    }
    ++views;
  }
  EXPECT_EQ(views, 3u);
}
