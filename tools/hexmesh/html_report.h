// hexmesh: a self-contained HTML report (no external resources, no JavaScript) of a meshing run:
// the JSON report rendered as tables, its histograms as SVG bar charts, and three axis-aligned
// slices of the mesh coloured by the scaled Jacobian.
//
// JSON layout read here (all optional; any other key is rendered generically as a table):
//   report["quality"]["histograms"][NAME] = {"lo": number, "hi": number, "counts": [n0, n1, ...]}
//       made by `histogram_json()` (or `histograms_json()` for all of `quality_histograms()`);
//       more generally, any object of this shape anywhere in the report is drawn as a histogram.
//   report["quality"]["worst"][MEASURE] = [{"cell"|"face": index, "value": number,
//                                           "location": [x, y, z]}, ...]     (worst first)
//       made by `worst_cells_json()`.
#ifndef HEXMESH_HTML_REPORT_H
#define HEXMESH_HTML_REPORT_H

#include <CGAL/number_utils.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/quality.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

// The public functions are in the global namespace (the tool's own header); helpers in
// `hexmesh_html_detail`.

/// {"lo": h.lo, "hi": h.hi, "counts": [...]}: the layout `html_report()` draws as a bar chart
inline nlohmann::ordered_json histogram_json(const CGAL::Hex_meshing_3::Histogram& h)
{
  nlohmann::ordered_json j;
  j["lo"] = h.lo;
  j["hi"] = h.hi;
  j["counts"] = h.counts;
  return j;
}

/// {NAME: histogram_json(h), ...}, e.g. of `CGAL::Hex_meshing_3::quality_histograms(q)`
inline nlohmann::ordered_json histograms_json(const std::vector<std::pair<std::string, CGAL::Hex_meshing_3::Histogram>>& hs)
{
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for(const auto& h : hs) j[h.first] = histogram_json(h.second);
  return j;
}

/// {"scaled_jacobian": [{"cell": i, "value": v, "location": [x, y, z]}, ...], "aspect_ratio": [...],
///  "non_orthogonality": [{"face": f, ...}, ...], "skewness": [...], "face_warpage": [...]}, worst first
/// (a NaN value is written as null)
inline nlohmann::ordered_json worst_cells_json(const CGAL::Hex_meshing_3::Worst_cells& w)
{
  auto list = [](const std::vector<CGAL::Hex_meshing_3::Worst_element>& v, const char* what) {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for(const auto& e : v) {
      nlohmann::ordered_json o;
      o[what] = e.index;
      o["value"] = e.value;
      o["location"] = {e.location[0], e.location[1], e.location[2]};
      a.push_back(o);
    }
    return a;
  };
  nlohmann::ordered_json j;
  j["scaled_jacobian"] = list(w.scaled_jacobian, "cell");
  j["aspect_ratio"] = list(w.aspect_ratio, "cell");
  j["non_orthogonality"] = list(w.non_orthogonality, "face");
  j["skewness"] = list(w.skewness, "face");
  j["face_warpage"] = list(w.face_warpage, "face");
  return j;
}

namespace hexmesh_html_detail {

typedef nlohmann::ordered_json Json;

/// text for HTML and XML (SVG): escapes & < > " ', replaces invalid UTF-8 and control characters
/// (other than tab, newline, carriage return) by U+FFFD
inline std::string escape(const std::string& s)
{
  static const char* const bad = "\xEF\xBF\xBD";
  std::string r;
  r.reserve(s.size() + 16);
  const std::size_t n = s.size();
  for(std::size_t i = 0; i < n;) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if(c < 0x80) {
      switch(c) {
        case '&': r += "&amp;"; break;
        case '<': r += "&lt;"; break;
        case '>': r += "&gt;"; break;
        case '"': r += "&quot;"; break;
        case '\'': r += "&#39;"; break;
        default:
          if(c < 0x20 && c != '\t' && c != '\n' && c != '\r') r += bad;
          else if(c == 0x7F) r += bad;
          else r += char(c);
      }
      ++i;
      continue;
    }
    // multi-byte sequence: validate (no overlong forms, no surrogates, <= U+10FFFF)
    std::size_t len = 0;
    std::uint32_t cp = 0, min = 0;
    if(c >= 0xC2 && c <= 0xDF) { len = 2; cp = c & 0x1F; min = 0x80; }
    else if(c >= 0xE0 && c <= 0xEF) { len = 3; cp = c & 0x0F; min = 0x800; }
    else if(c >= 0xF0 && c <= 0xF4) { len = 4; cp = c & 0x07; min = 0x10000; }
    bool ok = len > 0 && i + len <= n;
    for(std::size_t k = 1; ok && k < len; ++k) {
      const unsigned char d = static_cast<unsigned char>(s[i + k]);
      if((d & 0xC0) != 0x80) ok = false;
      else cp = (cp << 6) | (d & 0x3F);
    }
    if(ok && (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF) || cp == 0xFFFE || cp == 0xFFFF)) ok = false;
    if(ok) { r.append(s, i, len); i += len; }
    else { r += bad; ++i; }
  }
  return r;
}

inline std::string num(double v)
{
  if(std::isnan(v)) return "NaN";
  if(std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

/// a pixel coordinate with one decimal, without a trailing ".0"
inline void px(std::string& out, double v)
{
  if(!std::isfinite(v)) v = 0;
  long long q = std::llround(v * 10.0);
  if(q < 0) { out += '-'; q = -q; }
  out += std::to_string(q / 10);
  if(q % 10) { out += '.'; out += char('0' + q % 10); }
}

inline std::string pretty_key(const std::string& k)
{
  std::string r = k;
  std::replace(r.begin(), r.end(), '_', ' ');
  return escape(r);
}

inline bool is_scalar(const Json& v) { return !v.is_object() && !v.is_array(); }

inline bool is_inline(const Json& v, int depth = 0)
{
  if(is_scalar(v)) return true;
  if(v.is_object() || depth >= 2) return false;
  for(const auto& e : v) if(!is_inline(e, depth + 1)) return false;
  return true;
}

inline bool is_histogram(const Json& v)
{
  if(!v.is_object() || !v.contains("lo") || !v.contains("hi") || !v.contains("counts")) return false;
  if(!v["lo"].is_number() || !v["hi"].is_number() || !v["counts"].is_array()) return false;
  for(const auto& c : v["counts"]) if(!c.is_number()) return false;
  return true;
}

/// an object of inline values (a row of a matrix table)
inline bool is_record(const Json& v)
{
  if(!v.is_object() || v.empty() || is_histogram(v)) return false;
  for(const auto& e : v) if(!is_inline(e)) return false;
  return true;
}

inline std::string scalar_text(const Json& v)
{
  switch(v.type()) {
    case Json::value_t::null: return "&#8212;";
    case Json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case Json::value_t::string: return escape(v.get<std::string>());
    case Json::value_t::number_integer: return std::to_string(v.get<std::int64_t>());
    case Json::value_t::number_unsigned: return std::to_string(v.get<std::uint64_t>());
    case Json::value_t::number_float: return num(v.get<double>());
    default: return "";
  }
}

/// any value as one line of text (objects as {k: v, ...}; long arrays shortened)
inline std::string inline_text(const Json& v, int depth = 0)
{
  const std::size_t max_items = 50;
  if(is_scalar(v)) return scalar_text(v);
  if(depth > 4) return "&#8230;";
  if(v.empty()) return depth > 0 ? (v.is_object() ? "{}" : "[]") : "(none)";
  std::string r;
  const bool obj = v.is_object();
  if(depth > 0 || obj) r += obj ? "{" : "[";
  std::size_t i = 0;
  for(auto it = v.begin(); it != v.end(); ++it, ++i) {
    if(i == max_items) { r += ", &#8230; (" + std::to_string(v.size()) + " items)"; break; }
    if(i) r += ", ";
    if(obj) r += escape(it.key()) + ": ";
    r += inline_text(it.value(), depth + 1);
  }
  if(depth > 0 || obj) r += obj ? "}" : "]";
  return r;
}

inline std::string heading(int level, const std::string& key)
{
  level = (std::min)(6, (std::max)(2, level));
  std::string t = pretty_key(key);
  if(!t.empty()) t[0] = char(std::toupper(static_cast<unsigned char>(t[0])));
  const std::string h = std::to_string(level);
  return "<h" + h + ">" + t + "</h" + h + ">\n";
}

// ------------------------------------------------------------------------------------------------
// histograms

inline std::string svg_histogram(const std::string& name, const Json& h)
{
  const double lo = h["lo"].get<double>(), hi = h["hi"].get<double>();
  std::vector<double> counts;
  for(const auto& c : h["counts"]) counts.push_back(c.get<double>());
  const std::size_t n = counts.size();
  double total = 0, top = 0;
  for(double c : counts) { total += c; top = (std::max)(top, c); }
  const double W = 600, H = 230, L = 60, R = 15, T = 28, B = 42;
  const double pw = W - L - R, ph = H - T - B;
  std::string o;
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"600\" height=\"230\" viewBox=\"0 0 600 230\" "
       "font-family=\"sans-serif\" font-size=\"11\">\n";
  o += "<rect x=\"0\" y=\"0\" width=\"600\" height=\"230\" fill=\"#ffffff\"/>\n";
  o += "<text x=\"" + num(L) + "\" y=\"17\" font-size=\"13\" font-weight=\"bold\">" + pretty_key(name) + "</text>\n";
  o += "<text x=\"" + num(W - R) + "\" y=\"17\" text-anchor=\"end\" fill=\"#555555\">" + num(total) + " values, " +
       std::to_string(n) + " bins; end bins include values outside the range</text>\n";
  // axes
  o += "<path d=\"M" + num(L) + " " + num(T) + "V" + num(T + ph) + "H" + num(L + pw) +
       "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";
  for(int k = 0; k <= 2; ++k) {
    const double y = T + ph - ph * k / 2.0;
    const double val = top * k / 2.0;
    o += "<text x=\"" + num(L - 4) + "\" y=\"" + num(y + 4) + "\" text-anchor=\"end\">" + num(val) + "</text>\n";
    if(k) o += "<path d=\"M" + num(L) + " " + num(y) + "H" + num(L + pw) + "\" stroke=\"#dddddd\" stroke-width=\"1\"/>\n";
  }
  if(n == 0) { o += "<text x=\"300\" y=\"120\" text-anchor=\"middle\">no bins</text>\n</svg>\n"; return o; }
  const double bw = pw / double(n);
  const double w = (std::max)(0.5, bw - (bw > 4 ? 1.0 : 0.0));
  const bool labels = bw >= 14;
  for(std::size_t i = 0; i < n; ++i) {
    const double c = counts[i];
    double bh = top > 0 ? c / top * ph : 0;
    if(c > 0 && bh < 1) bh = 1;
    const double x = L + bw * double(i);
    const double a = lo + (hi - lo) * double(i) / double(n), b = lo + (hi - lo) * double(i + 1) / double(n);
    o += "<rect x=\"" + num(x + (bw - w) / 2) + "\" y=\"" + num(T + ph - bh) + "\" width=\"" + num(w) +
         "\" height=\"" + num(bh) + "\" fill=\"#4e79a7\"><title>[" + num(a) + ", " + num(b) +
         (i + 1 == n ? "]" : ")") + ": " + num(c) + "</title></rect>\n";
    if(labels && c > 0) {
      const std::string t = num(c);
      const double fs = (std::min)(9.0, 1.6 * bw / double(t.size()));
      if(fs >= 6)
        o += "<text x=\"" + num(x + bw / 2) + "\" y=\"" + num(T + ph - bh - 2) + "\" text-anchor=\"middle\" font-size=\"" +
             num(fs) + "\" fill=\"#333333\">" + t + "</text>\n";
    }
  }
  // x tick labels at bin edges: every step-th edge, step the least divisor of n giving at most 10
  // intervals (else ceil(n / 8), and the last edge labelled too)
  std::size_t step = 1;
  while(step < n && (n % step != 0 || n / step > 10)) ++step;
  if(n / step > 10 || step == n) step = (n + 7) / 8;   // n > 0 here
  for(std::size_t i = 0; i <= n; i += step) {
    const double x = L + bw * double(i);
    o += "<path d=\"M" + num(x) + " " + num(T + ph) + "v4\" stroke=\"#333333\" stroke-width=\"1\"/>\n";
    o += "<text x=\"" + num(x) + "\" y=\"" + num(T + ph + 16) + "\" text-anchor=\"middle\">" +
         num(lo + (hi - lo) * double(i) / double(n)) + "</text>\n";
  }
  if(n % step != 0) {
    o += "<text x=\"" + num(L + pw) + "\" y=\"" + num(T + ph + 16) + "\" text-anchor=\"middle\">" + num(hi) + "</text>\n";
  }
  o += "<text x=\"" + num(L + pw / 2) + "\" y=\"" + num(H - 6) + "\" text-anchor=\"middle\" fill=\"#555555\">" +
       pretty_key(name) + "</text>\n";
  o += "</svg>\n";
  return o;
}

// ------------------------------------------------------------------------------------------------
// generic rendering of the JSON

inline void render_any(std::string& out, const Json& v, int level);

inline void render_array_of_objects(std::string& out, const Json& a)
{
  const std::size_t max_rows = 500;
  std::vector<std::string> cols;
  for(const auto& e : a) {
    if(!e.is_object()) continue;
    for(auto it = e.begin(); it != e.end(); ++it)
      if(std::find(cols.begin(), cols.end(), it.key()) == cols.end()) cols.push_back(it.key());
  }
  out += "<table class=\"grid\"><thead><tr><th>#</th>";
  for(const auto& c : cols) out += "<th>" + pretty_key(c) + "</th>";
  out += "</tr></thead><tbody>\n";
  std::size_t i = 0;
  for(const auto& e : a) {
    if(i == max_rows) break;
    out += "<tr><td>" + std::to_string(i) + "</td>";
    if(e.is_object()) {
      for(const auto& c : cols) out += "<td>" + (e.contains(c) ? inline_text(e[c]) : std::string()) + "</td>";
    } else {
      out += "<td colspan=\"" + std::to_string(cols.empty() ? std::size_t(1) : cols.size()) + "\">" + inline_text(e) + "</td>";
    }
    out += "</tr>\n";
    ++i;
  }
  out += "</tbody></table>\n";
  if(a.size() > max_rows)
    out += "<p class=\"note\">" + std::to_string(max_rows) + " of " + std::to_string(a.size()) + " rows shown.</p>\n";
}

inline void render_object(std::string& out, const Json& o, int level)
{
  std::vector<Json::const_iterator> kv, records, hists, others;
  for(auto it = o.begin(); it != o.end(); ++it) {
    const Json& v = it.value();
    if(is_inline(v)) kv.push_back(it);
    else if(is_histogram(v)) hists.push_back(it);
    else if(is_record(v)) records.push_back(it);
    else others.push_back(it);
  }
  if(!kv.empty()) {
    out += "<table class=\"kv\"><tbody>\n";
    for(const auto& it : kv)
      out += "<tr><th>" + pretty_key(it.key()) + "</th><td>" + inline_text(it.value()) + "</td></tr>\n";
    out += "</tbody></table>\n";
  }
  if(!records.empty()) {
    std::vector<std::string> cols;
    for(const auto& it : records)
      for(auto jt = it.value().begin(); jt != it.value().end(); ++jt)
        if(std::find(cols.begin(), cols.end(), jt.key()) == cols.end()) cols.push_back(jt.key());
    out += "<table class=\"grid\"><thead><tr><th></th>";
    for(const auto& c : cols) out += "<th>" + pretty_key(c) + "</th>";
    out += "</tr></thead><tbody>\n";
    for(const auto& it : records) {
      out += "<tr><th>" + pretty_key(it.key()) + "</th>";
      for(const auto& c : cols)
        out += "<td>" + (it.value().contains(c) ? inline_text(it.value()[c]) : std::string()) + "</td>";
      out += "</tr>\n";
    }
    out += "</tbody></table>\n";
  }
  if(!hists.empty()) {
    out += "<div class=\"figs\">\n";
    for(const auto& it : hists) out += "<figure>" + svg_histogram(it.key(), it.value()) + "</figure>\n";
    out += "</div>\n";
  }
  for(const auto& it : others) {
    out += heading(level, it.key());
    render_any(out, it.value(), level + 1);
  }
  if(o.empty()) out += "<p class=\"note\">(empty)</p>\n";
}

inline void render_any(std::string& out, const Json& v, int level)
{
  if(v.is_object()) {
    if(is_histogram(v)) out += "<div class=\"figs\"><figure>" + svg_histogram("", v) + "</figure></div>\n";
    else render_object(out, v, level);
  } else if(v.is_array()) {
    bool objects = !v.empty();
    for(const auto& e : v) if(!e.is_object()) objects = false;
    if(objects) render_array_of_objects(out, v);
    else if(is_inline(v)) out += "<p>" + inline_text(v) + "</p>\n";
    else {
      out += "<ol start=\"0\">\n";
      for(const auto& e : v) { out += "<li>"; render_any(out, e, level + 1); out += "</li>\n"; }
      out += "</ol>\n";
    }
  } else
    out += "<p>" + scalar_text(v) + "</p>\n";
}

// ------------------------------------------------------------------------------------------------
// slices

// scaled Jacobian colours: (0, 1] in `nb_levels` steps of a reversed YlOrRd (1: pale, 0: dark red),
// <= 0 (inverted or degenerate) magenta, missing grey
const int nb_levels = 32;
inline std::string colour_of_level(int level)
{
  static const unsigned char stops[9][3] = {{0x80, 0x00, 0x26}, {0xbd, 0x00, 0x26}, {0xe3, 0x1a, 0x1c},
                                            {0xfc, 0x4e, 0x2a}, {0xfd, 0x8d, 0x3c}, {0xfe, 0xb2, 0x4c},
                                            {0xfe, 0xd9, 0x76}, {0xff, 0xed, 0xa0}, {0xff, 0xff, 0xcc}};
  if(level < 0) return "#ff00ff";
  if(level >= nb_levels) return "#bbbbbb";
  const double t = (level + 0.5) / nb_levels * 8.0;
  const int k = (std::min)(7, int(t));
  const double f = t - k;
  char b[8];
  int rgb[3];
  for(int c = 0; c < 3; ++c) rgb[c] = int(std::lround(stops[k][c] * (1 - f) + stops[k + 1][c] * f));
  std::snprintf(b, sizeof b, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return b;
}
/// -1: inverted, nb_levels: missing, else 0 .. nb_levels-1
inline int level_of(double sj)
{
  if(std::isnan(sj)) return nb_levels;
  if(sj <= 0) return -1;
  return (std::min)(nb_levels - 1, int(sj * nb_levels));
}

/// patches 0..5 (the faces of the meshing box) in dark tones, the surface parts (6, 7, ...) in bright ones
inline std::string patch_colour(std::size_t p)
{
  static const char* const box[6] = {"#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173", "#525252"};
  static const char* const part[10] = {"#1f77b4", "#2ca02c", "#9467bd", "#17becf", "#e377c2",
                                       "#8c564b", "#bcbd22", "#7f7f7f", "#ff7f0e", "#d62728"};
  return p < 6 ? box[p] : part[(p - 6) % 10];
}

inline std::string svg_colour_legend(bool has_inverted, bool has_missing)
{
  std::string o;
  const double L = 10, T = 18, bw = 9, bh = 14;
  const double W = L + bw * nb_levels + 260;
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(W) + "\" height=\"52\" viewBox=\"0 0 " + num(W) +
       " 52\" font-family=\"sans-serif\" font-size=\"11\">\n";
  o += "<text x=\"" + num(L) + "\" y=\"12\">scaled Jacobian</text>\n";
  for(int i = 0; i < nb_levels; ++i)
    o += "<rect x=\"" + num(L + bw * i) + "\" y=\"" + num(T) + "\" width=\"" + num(bw + 0.3) + "\" height=\"" + num(bh) +
         "\" fill=\"" + colour_of_level(i) + "\"/>\n";
  o += "<rect x=\"" + num(L) + "\" y=\"" + num(T) + "\" width=\"" + num(bw * nb_levels) + "\" height=\"" + num(bh) +
       "\" fill=\"none\" stroke=\"#555555\" stroke-width=\"0.5\"/>\n";
  for(int k = 0; k <= 4; ++k)
    o += "<text x=\"" + num(L + bw * nb_levels * k / 4.0) + "\" y=\"" + num(T + bh + 12) + "\" text-anchor=\"middle\">" +
         num(k / 4.0) + "</text>\n";
  double x = L + bw * nb_levels + 20;
  o += "<rect x=\"" + num(x) + "\" y=\"" + num(T) + "\" width=\"14\" height=\"" + num(bh) + "\" fill=\"" +
       colour_of_level(-1) + "\" stroke=\"#555555\" stroke-width=\"0.5\"/>\n";
  o += "<text x=\"" + num(x + 18) + "\" y=\"" + num(T + 11) + "\">&#8804; 0 (inverted)" +
       std::string(has_inverted ? "" : ": none") + "</text>\n";
  if(has_missing) {
    x += 120;
    o += "<rect x=\"" + num(x) + "\" y=\"" + num(T) + "\" width=\"14\" height=\"" + num(bh) + "\" fill=\"" +
         colour_of_level(nb_levels) + "\" stroke=\"#555555\" stroke-width=\"0.5\"/>\n";
    o += "<text x=\"" + num(x + 18) + "\" y=\"" + num(T + 11) + "\">no value</text>\n";
  }
  o += "</svg>\n";
  return o;
}

typedef std::array<double, 2> P2;

inline double cross2(const P2& o, const P2& a, const P2& b)
{ return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }

/// convex hull, counter-clockwise, of at most a few points (Andrew's monotone chain); `pts` is reordered
inline std::vector<P2> convex_hull(std::vector<P2>& pts)
{
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if(pts.size() < 3) return pts;
  std::vector<P2> h(2 * pts.size());
  std::size_t k = 0;
  for(std::size_t i = 0; i < pts.size(); ++i) {
    while(k >= 2 && cross2(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for(std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while(k >= t && cross2(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

struct Slice_result
{
  std::string svg;
  std::size_t crossing_cells = 0, drawn_cells = 0, degenerate = 0, crossing_boundary_faces = 0, boundary_segments = 0;
  std::vector<std::size_t> segments_per_patch;
};

/// the slice of `mesh` by the plane {x_axis = c}, drawn in the box [lo, hi]
template <typename HexMesh>
Slice_result slice_svg(const HexMesh& mesh, const std::vector<std::array<double, 3>>& X,
                       const std::vector<double>& sj, int axis, double c,
                       const std::array<double, 3>& lo, const std::array<double, 3>& hi, std::size_t max_polygons)
{
  static const int uv[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  static const char* const names[3] = {"x", "y", "z"};
  const int U = uv[axis][0], V = uv[axis][1];
  const double du = hi[U] - lo[U], dv = hi[V] - lo[V];
  const double ext = (std::max)(du, dv);
  const double s = ext > 0 ? 600.0 / ext : 1.0;
  const double L = 80, R = 16, T = 26, B = 40;
  const double W = (std::max)(320.0, L + R + du * s), H = T + B + dv * s;   // room for the labels
  auto to_px = [&](const P2& p, std::string& out) {
    px(out, L + (p[0] - lo[U]) * s);
    out += ' ';
    px(out, T + (hi[V] - p[1]) * s);
  };

  Slice_result r;
  std::vector<std::string> fill(nb_levels + 2);   // index level + 1
  const auto& edges = CGAL::Hex_meshing_3::hex_local_edges();
  std::vector<P2> pts;
  pts.reserve(24);
  auto add_point = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    const double da = a[axis] - c, db = b[axis] - c;
    if(da == 0) pts.push_back({{a[U], a[V]}});
    if(db == 0) pts.push_back({{b[U], b[V]}});
    if((da < 0 && db > 0) || (da > 0 && db < 0)) {
      const double t = da / (da - db);
      pts.push_back({{a[U] + t * (b[U] - a[U]), a[V] + t * (b[V] - a[V])}});
    }
  };
  for(std::size_t ci = 0; ci < mesh.hexahedra.size(); ++ci) {
    const auto& h = mesh.hexahedra[ci];
    double mn = std::numeric_limits<double>::infinity(), mx = -mn;
    for(int k = 0; k < 8; ++k) { const double x = X[h[k]][axis]; mn = (std::min)(mn, x); mx = (std::max)(mx, x); }
    if(!(mn <= c && c < mx)) continue;   // half-open: a cell with a face on the plane counts once
    ++r.crossing_cells;
    if(r.drawn_cells >= max_polygons) continue;
    pts.clear();
    for(const auto& e : edges) add_point(X[h[e[0]]], X[h[e[1]]]);
    const std::vector<P2> hull = convex_hull(pts);
    if(hull.size() < 3) { ++r.degenerate; continue; }
    const int lev = level_of(ci < sj.size() ? sj[ci] : std::numeric_limits<double>::quiet_NaN());
    std::string& d = fill[std::size_t(lev + 1)];
    d += 'M';
    to_px(hull[0], d);
    d += 'L';
    for(std::size_t i = 1; i < hull.size(); ++i) { if(i > 1) d += ' '; to_px(hull[i], d); }
    d += 'Z';
    ++r.drawn_cells;
  }

  // boundary faces crossed by the plane, as segments
  const std::size_t np = mesh.patch_names.size();
  std::vector<std::string> lines;
  r.segments_per_patch.assign(np, 0);
  for(const auto& bf : mesh.boundary_faces) {
    double mn = std::numeric_limits<double>::infinity(), mx = -mn;
    for(int k = 0; k < 4; ++k) { const double x = X[bf.vertices[k]][axis]; mn = (std::min)(mn, x); mx = (std::max)(mx, x); }
    if(!(mn <= c && c < mx)) continue;
    ++r.crossing_boundary_faces;
    if(r.boundary_segments >= max_polygons) continue;
    pts.clear();
    for(int k = 0; k < 4; ++k) add_point(X[bf.vertices[k]], X[bf.vertices[(k + 1) % 4]]);
    if(pts.size() < 2) continue;
    // the two points farthest apart
    double best = -1;
    std::size_t bi = 0, bj = 0;
    for(std::size_t i = 0; i < pts.size(); ++i)
      for(std::size_t j = i + 1; j < pts.size(); ++j) {
        const double d2 = (pts[i][0] - pts[j][0]) * (pts[i][0] - pts[j][0]) + (pts[i][1] - pts[j][1]) * (pts[i][1] - pts[j][1]);
        if(d2 > best) { best = d2; bi = i; bj = j; }
      }
    if(!(best > 0)) continue;
    const std::size_t p = bf.patch >= 0 ? std::size_t(bf.patch) : np;
    if(p >= lines.size()) lines.resize(p + 1);
    if(p >= r.segments_per_patch.size()) r.segments_per_patch.resize(p + 1, 0);
    std::string& d = lines[p];
    d += 'M';
    to_px(pts[bi], d);
    d += 'L';
    to_px(pts[bj], d);
    ++r.segments_per_patch[p];
    ++r.boundary_segments;
  }

  std::string& o = r.svg;
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(std::ceil(W)) + "\" height=\"" + num(std::ceil(H)) +
       "\" viewBox=\"0 0 " + num(std::ceil(W)) + " " + num(std::ceil(H)) + "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  o += "<rect x=\"0\" y=\"0\" width=\"" + num(std::ceil(W)) + "\" height=\"" + num(std::ceil(H)) + "\" fill=\"#ffffff\"/>\n";
  o += "<text x=\"" + num(L) + "\" y=\"17\" font-size=\"13\" font-weight=\"bold\">" + std::string(names[axis]) + " = " +
       num(c) + "</text>\n";
  o += "<rect x=\"" + num(L) + "\" y=\"" + num(T) + "\" width=\"" + num(du * s) + "\" height=\"" + num(dv * s) +
       "\" fill=\"#f4f4f4\" stroke=\"#999999\" stroke-width=\"0.5\"/>\n";
  o += "<g stroke=\"#555555\" stroke-width=\"0.3\" stroke-opacity=\"0.6\" stroke-linejoin=\"round\">\n";
  for(std::size_t i = 0; i < fill.size(); ++i)
    if(!fill[i].empty())
      o += "<path fill=\"" + colour_of_level(int(i) - 1) + "\" d=\"" + fill[i] + "\"/>\n";
  o += "</g>\n";
  if(r.boundary_segments) {
    std::string all;
    for(const auto& l : lines) all += l;
    o += "<path fill=\"none\" stroke=\"#ffffff\" stroke-width=\"3.5\" stroke-linecap=\"round\" d=\"" + all + "\"/>\n";
    for(std::size_t p = 0; p < lines.size(); ++p)
      if(!lines[p].empty())
        o += "<path fill=\"none\" stroke=\"" + patch_colour(p) + "\" stroke-width=\"2\" stroke-linecap=\"round\" d=\"" +
             lines[p] + "\"/>\n";
  }
  if(r.crossing_cells == 0)
    o += "<text x=\"" + num(L + du * s / 2) + "\" y=\"" + num(T + dv * s / 2) +
         "\" text-anchor=\"middle\" fill=\"#555555\">no cell crosses this plane</text>\n";
  // axes: coordinates at the ends
  const double yb = T + dv * s;
  if(du * s >= 150) {
    o += "<text x=\"" + num(L) + "\" y=\"" + num(yb + 14) + "\" text-anchor=\"start\">" + num(lo[U]) + "</text>\n";
    o += "<text x=\"" + num(L + du * s) + "\" y=\"" + num(yb + 14) + "\" text-anchor=\"end\">" + num(hi[U]) + "</text>\n";
  } else
    o += "<text x=\"" + num(L + du * s / 2) + "\" y=\"" + num(yb + 14) + "\" text-anchor=\"middle\">" + num(lo[U]) +
         " &#8230; " + num(hi[U]) + "</text>\n";
  o += "<text x=\"" + num(L + du * s / 2) + "\" y=\"" + num(yb + 30) + "\" text-anchor=\"middle\" font-style=\"italic\">" +
       std::string(names[U]) + " &#8594;</text>\n";
  o += "<text x=\"" + num(L - 4) + "\" y=\"" + num(yb) + "\" text-anchor=\"end\">" + num(lo[V]) + "</text>\n";
  o += "<text x=\"" + num(L - 4) + "\" y=\"" + num(T + 9) + "\" text-anchor=\"end\">" + num(hi[V]) + "</text>\n";
  o += "<text x=\"" + num(L - 8) + "\" y=\"" + num(T + dv * s / 2 + 4) + "\" text-anchor=\"end\" font-style=\"italic\">" +
       std::string(names[V]) + " &#8593;</text>\n";
  o += "</svg>\n";
  return r;
}

inline const char* style()
{
  return "body{font-family:sans-serif;font-size:14px;color:#222;margin:1.5em auto;max-width:1300px;padding:0 1em}"
         "h1{font-size:1.6em;margin-bottom:0.2em}h2{border-bottom:1px solid #ccc;margin-top:1.6em}"
         "table{border-collapse:collapse;margin:0.4em 0 1em 0}"
         "th,td{border:1px solid #ddd;padding:3px 8px;text-align:left;vertical-align:top}"
         "table.kv th{background:#f6f6f6;font-weight:normal;color:#444}"
         "table.grid thead th{background:#eef2f7}table.grid td{font-variant-numeric:tabular-nums}"
         ".sub{color:#555;margin-top:0}.note{color:#a33}"
         ".figs{display:flex;flex-wrap:wrap;gap:12px}figure{margin:0 0 12px 0}"
         "figcaption{font-size:12px;color:#444;max-width:640px}"
         ".sw{display:inline-block;width:14px;height:10px;margin:0 4px 0 10px;border:1px solid #555;vertical-align:middle}";
}

} // namespace hexmesh_html_detail

/*!
 * a self-contained HTML page (inline CSS and SVG, no JavaScript, no external resource) showing
 * `report` (every key, rendered generically: scalars and short arrays in key/value tables, objects
 * of such values as a matrix table, arrays of objects as tables, histograms as bar charts, the rest
 * in nested sections) and three slices of `mesh` by the planes x, y, z = centre of its bounding box,
 * each hexahedron crossing a plane drawn as its cross-section filled by `cell_scaled_jacobian`
 * (per cell; missing values are drawn grey), the boundary faces crossed as thick lines coloured by
 * patch. At most `max_polygons_per_slice` cells are drawn per slice (the first ones by index; the
 * page says when the limit is reached).
 *
 * A cell counts as crossing the plane {x_a = c} when min_a <= c < max_a over its corners, so that a
 * plane through grid points (the centre of a box meshed by an octree often is one) shows the faces
 * of the cells just above it, each once.
 */
template <typename HexMesh>
std::string html_report(const nlohmann::ordered_json& report, const HexMesh& mesh,
                        const std::vector<double>& cell_scaled_jacobian,
                        std::size_t max_polygons_per_slice = 200000)
{
  using namespace hexmesh_html_detail;
  std::string out;
  out.reserve(1 << 16);

  // title
  std::string subject;
  if(report.is_object()) {
    for(const char* k : {"input", "inputs"}) {
      if(!report.contains(k)) continue;
      const Json& v = report[k];
      if(v.is_string()) subject = escape(v.get<std::string>());
      else if(is_inline(v)) subject = inline_text(v);
      break;
    }
  }
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<title>hexmesh report" + (subject.empty() ? std::string() : ": " + subject) + "</title>\n";
  out += "<style>" + std::string(style()) + "</style>\n</head>\n<body>\n";
  out += "<h1>hexmesh report</h1>\n";
  if(!subject.empty()) out += "<p class=\"sub\">" + subject + "</p>\n";

  // the JSON: top-level inline values first as a summary, then one section per other key
  if(report.is_object()) {
    bool any_inline = false;
    for(auto it = report.begin(); it != report.end(); ++it) any_inline = any_inline || is_inline(it.value());
    if(any_inline) {
      out += "<h2>Summary</h2>\n<table class=\"kv\"><tbody>\n";
      for(auto it = report.begin(); it != report.end(); ++it)
        if(is_inline(it.value()))
          out += "<tr><th>" + pretty_key(it.key()) + "</th><td>" + inline_text(it.value()) + "</td></tr>\n";
      out += "</tbody></table>\n";
    }
    for(auto it = report.begin(); it != report.end(); ++it) {
      if(is_inline(it.value())) continue;
      out += heading(2, it.key());
      render_any(out, it.value(), 3);
    }
  } else if(!report.is_null()) {
    out += "<h2>Report</h2>\n";
    render_any(out, report, 3);
  }

  // slices
  out += "<h2>Mesh slices</h2>\n";
  const std::size_t nv = mesh.points.size();
  std::vector<std::array<double, 3>> X(nv);
  for(std::size_t i = 0; i < nv; ++i)
    X[i] = {{CGAL::to_double(mesh.points[i].x()), CGAL::to_double(mesh.points[i].y()), CGAL::to_double(mesh.points[i].z())}};
  std::array<double, 3> lo{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity()}};
  std::array<double, 3> hi{{-lo[0], -lo[1], -lo[2]}};
  for(const auto& h : mesh.hexahedra)
    for(int k = 0; k < 8; ++k)
      for(int a = 0; a < 3; ++a) { lo[a] = (std::min)(lo[a], X[h[k]][a]); hi[a] = (std::max)(hi[a], X[h[k]][a]); }
  if(mesh.hexahedra.empty() || !(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2])) {
    out += "<p class=\"note\">The mesh has no cells.</p>\n";
  } else {
    bool has_inverted = false, has_missing = cell_scaled_jacobian.size() < mesh.hexahedra.size();
    for(double v : cell_scaled_jacobian) { if(v <= 0) has_inverted = true; if(std::isnan(v)) has_missing = true; }
    out += "<p>Cross-sections of the cells by the planes through the centre of the mesh's bounding box [" +
           num(lo[0]) + ", " + num(hi[0]) + "] &#215; [" + num(lo[1]) + ", " + num(hi[1]) + "] &#215; [" + num(lo[2]) +
           ", " + num(hi[2]) + "], filled by the cell's scaled Jacobian; thick lines: boundary faces, by patch.";
    if(cell_scaled_jacobian.size() != mesh.hexahedra.size())
      out += " <span class=\"note\">(" + std::to_string(cell_scaled_jacobian.size()) + " scaled Jacobian values for " +
             std::to_string(mesh.hexahedra.size()) + " cells: cells without a value are grey)</span>";
    out += "</p>\n" + svg_colour_legend(has_inverted, has_missing);
    out += "<div class=\"figs\">\n";
    static const char* const names[3] = {"x", "y", "z"};
    for(int a = 0; a < 3; ++a) {
      double c = 0.5 * (lo[a] + hi[a]);
      if(std::abs(c) < 1e-12 * (hi[a] - lo[a])) c = 0;   // rounding noise of a symmetric box: print 0
      const Slice_result r = slice_svg(mesh, X, cell_scaled_jacobian, a, c, lo, hi, max_polygons_per_slice);
      out += "<figure>\n" + r.svg + "<figcaption>Plane " + std::string(names[a]) + " = " + num(c) + ": " +
             std::to_string(r.crossing_cells) + " cells crossed, " + std::to_string(r.crossing_boundary_faces) +
             " boundary faces.";
      if(r.drawn_cells + r.degenerate < r.crossing_cells)
        out += " <span class=\"note\">Capped: " + std::to_string(r.drawn_cells) + " of " +
               std::to_string(r.crossing_cells) + " cells drawn (the first by index).</span>";
      if(r.boundary_segments >= max_polygons_per_slice && r.boundary_segments < r.crossing_boundary_faces)
        out += " <span class=\"note\">" + std::to_string(r.boundary_segments) + " of " +
               std::to_string(r.crossing_boundary_faces) + " boundary faces drawn.</span>";
      if(r.degenerate) out += " " + std::to_string(r.degenerate) + " degenerate cross-sections skipped.";
      out += "<br>";
      bool any = false;
      for(std::size_t p = 0; p < r.segments_per_patch.size(); ++p) {
        if(!r.segments_per_patch[p]) continue;
        any = true;
        const std::string name = p < mesh.patch_names.size() ? mesh.patch_names[p] : "patch " + std::to_string(p);
        out += "<span class=\"sw\" style=\"background:" + patch_colour(p) + "\"></span>" + escape(name) + " (" +
               std::to_string(r.segments_per_patch[p]) + ")";
      }
      if(!any) out += "No boundary face crosses this plane.";
      out += "</figcaption>\n</figure>\n";
    }
    out += "</div>\n";
  }
  out += "</body>\n</html>\n";
  return out;
}

#endif // HEXMESH_HTML_REPORT_H
