// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_READ_SURFACE_H
#define CGAL_HEX_MESHING_3_IO_READ_SURFACE_H

// Surface readers, all our own: CGAL's OBJ and STL readers drop the OBJ groups and the STL solid
// names, which are the patch names users want to see in their solver, and CGAL 5.5's OFF and PLY
// readers overflow buffers on malformed input (found by our fuzz targets within seconds). Every format may be gzip-compressed (recognised by its magic bytes, so
// `part.stl.gz` and a compressed file named `part.stl` both work). All readers work on a buffer
// held in memory, so that the fuzz targets (test/Hex_meshing_3/fuzz) exercise exactly this code.
//
// Errors are `Input_error`s with a one-line message "<file>: <cause>"; a reader never crashes on
// malformed input (this is what the fuzz targets check).

#include <CGAL/Hex_meshing_3/Status.h>

#include <boost/iostreams/copy.hpp>
#include <boost/iostreams/device/array.hpp>
#include <boost/iostreams/device/back_inserter.hpp>
#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <unordered_map>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief a triangle soup with named parts, as read from one or several files.
 *
 * `part_of_triangle[i]` indexes `part_names`. Parts are the OBJ groups (`g`) and objects (`o`),
 * the STL solids, or, when a file has neither, the file itself (named after its base name). Parts
 * of the same name, from one file or several, are one part.
 */
template <typename Point_3>
struct Surface_soup
{
  std::vector<Point_3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<int> part_of_triangle;
  std::vector<std::string> part_names;
  std::vector<std::string> files;       ///< the files read, in order
  std::size_t polygons = 0;             ///< polygons read (before splitting into triangles)

  /// index of the part named `name`, created if needed (parts of the same name are one part)
  int part(const std::string& name)
  {
    if(m_index.size() != part_names.size()) {   // part_names was filled or changed by the caller
      m_index.clear();
      for(std::size_t i = 0; i < part_names.size(); ++i) m_index.emplace(part_names[i], int(i));
    }
    const auto it = m_index.find(name);
    if(it != m_index.end()) return it->second;
    part_names.push_back(name);
    m_index.emplace(name, int(part_names.size() - 1));
    return int(part_names.size() - 1);
  }

  /// a new part named after a file's base name: `stem`, or `stem_2`, `stem_3`, ... when a part of
  /// that name exists already (two files `a/part.stl` and `b/part.stl` stay two patches)
  int file_part(const std::string& stem)
  {
    std::string n = stem;
    for(int k = 2; std::find(part_names.begin(), part_names.end(), n) != part_names.end(); ++k)
      n = stem + "_" + std::to_string(k);
    return part(n);
  }

private:
  std::unordered_map<std::string, int> m_index;
};

namespace internal {

inline std::string lower(std::string s)
{
  for(char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// base name without directories and without every extension ("a/b/bike.obj.gz" -> "bike")
inline std::string stem_of(const std::string& filename)
{
  std::string base = filename.substr(filename.find_last_of("/\\") + 1);
  base = base.substr(0, base.find('.'));
  return base.empty() ? std::string("surface") : base;
}

/// the format named by the extension, ignoring a trailing ".gz"
inline std::string format_of(const std::string& filename)
{
  std::string f = lower(filename.substr(filename.find_last_of("/\\") + 1));
  if(f.size() > 3 && f.compare(f.size() - 3, 3, ".gz") == 0) f.resize(f.size() - 3);
  const std::string::size_type dot = f.find_last_of('.');
  return dot == std::string::npos ? std::string() : f.substr(dot + 1);
}

inline bool is_gzip(const std::string& data)
{
  return data.size() >= 2 && static_cast<unsigned char>(data[0]) == 0x1f &&
         static_cast<unsigned char>(data[1]) == 0x8b;
}

inline std::string gunzip(const std::string& data, const std::string& name)
{
  std::string out;
  try {
    namespace bio = boost::iostreams;
    bio::filtering_istream in;
    in.push(bio::gzip_decompressor());
    in.push(bio::array_source(data.data(), data.size()));
    bio::copy(in, bio::back_inserter(out));
  } catch(const std::bad_alloc&) {
    throw Input_error(name + ": the decompressed gzip stream does not fit in memory", Input_error_cause::UNREADABLE);
  } catch(const std::exception& e) {
    throw Input_error(name + ": the gzip stream is corrupt or truncated (" + e.what() + ")", Input_error_cause::TRUNCATED);
  }
  return out;
}

/// a cursor over a text buffer, reading whitespace-separated tokens line by line
struct Text_cursor
{
  const char* p;
  const char* end;
  std::size_t line = 1;

  static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_blanks() { while(p < end && blank(*p)) ++p; }
  bool at_eol() { skip_blanks(); return p >= end || *p == '\n'; }
  void next_line()
  {
    while(p < end && *p != '\n') ++p;
    if(p < end) { ++p; ++line; }
  }
  /// next token on the current line (empty at the end of the line)
  std::string_view token()
  {
    skip_blanks();
    const char* b = p;
    while(p < end && !blank(*p) && *p != '\n') ++p;
    return std::string_view(b, std::size_t(p - b));
  }
  /// skips whitespace including line ends; returns the next token (empty at the end of the buffer)
  std::string_view any_token()
  {
    while(p < end && (blank(*p) || *p == '\n')) { if(*p == '\n') ++line; ++p; }
    return token();
  }
  /// throws "name: line N: what"; at the end of the buffer the cause is `TRUNCATED` and the
  /// message says so
  [[noreturn]] void fail(const std::string& name, const std::string& what,
                         Input_error_cause cause = Input_error_cause::MALFORMED)
  {
    skip_blanks();
    const bool at_end = p >= end;
    throw Input_error(name + ": line " + std::to_string(line) + ": " + what +
                      (at_end && what.find("truncated") == std::string::npos ? " (the file ends there: truncated)" : ""),
                      at_end ? Input_error_cause::TRUNCATED : cause);
  }
  /// the rest of the line, trimmed
  std::string rest_of_line()
  {
    skip_blanks();
    const char* b = p;
    while(p < end && *p != '\n') ++p;
    const char* e = p;
    while(e > b && blank(e[-1])) --e;
    return std::string(b, std::size_t(e - b));
  }
};

/// case-insensitive keyword comparison (some exporters write STL keywords in capitals)
inline bool ieq(std::string_view a, std::string_view b)
{
  if(a.size() != b.size()) return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    if(std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

inline bool parse_double(std::string_view s, double& v)
{
  if(s.empty()) return false;
  if(s[0] == '+') s.remove_prefix(1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

template <typename Point_3>
void check_finite(const std::vector<Point_3>& pts, std::size_t from, const std::string& name)
{
  for(std::size_t i = from; i < pts.size(); ++i) {
    const Point_3& p = pts[i];
    if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
       !std::isfinite(CGAL::to_double(p.z())))
      throw Input_error(name + ": vertex " + std::to_string(i - from + 1) +
                        " has a coordinate that is not a finite number", Input_error_cause::NON_FINITE);
  }
}

/// appends polygon `poly` (indices into the soup's points) as a fan of triangles of part `part`
template <typename Soup>
void add_polygon(Soup& soup, const std::vector<std::size_t>& poly, int part)
{
  ++soup.polygons;
  for(std::size_t i = 2; i < poly.size(); ++i) {
    soup.triangles.push_back({{std::uint32_t(poly[0]), std::uint32_t(poly[i - 1]), std::uint32_t(poly[i])}});
    soup.part_of_triangle.push_back(part);
  }
}

// ---- OBJ --------------------------------------------------------------------------------------

template <typename Point_3>
void read_OBJ_buffer(const std::string& data, const std::string& name, double scale, Surface_soup<Point_3>& soup)
{
  Text_cursor c{data.data(), data.data() + data.size()};
  const std::size_t base = soup.points.size();
  int part = -1;   // created at the first face, so a file without groups is one part named after it
  std::string pending;   // empty: the part named after the file
  int stem_part = -1;
  std::vector<std::size_t> poly;
  std::vector<std::pair<std::size_t, std::size_t>> face_ranges;   // checked once all vertices are known
  std::vector<std::int64_t> raw;   // raw one-based (resolved) indices of every face corner
  std::vector<int> face_part;
  std::vector<std::size_t> face_line;
  while(c.p < c.end) {
    const std::string_view kw = c.token();
    if(kw == "v") {
      double x[3];
      for(int k = 0; k < 3; ++k)
        if(!parse_double(c.token(), x[k]))
          c.fail(name, "a vertex needs three numbers");
      soup.points.push_back(Point_3(x[0] * scale, x[1] * scale, x[2] * scale));
    } else if(kw == "f") {
      const std::size_t first = raw.size();
      for(std::string_view t = c.token(); !t.empty(); t = c.token()) {
        const std::string_view idx = t.substr(0, t.find('/'));
        long long i = 0;
        const auto r = std::from_chars(idx.data(), idx.data() + idx.size(), i);
        if(r.ec != std::errc() || r.ptr != idx.data() + idx.size() || i == 0)
          throw Input_error(name + ": line " + std::to_string(c.line) + ": '" + std::string(t) +
                            "' is not a vertex index", Input_error_cause::MALFORMED);
        const long long nv = (long long)(soup.points.size() - base);
        if(i > (long long)UINT32_MAX || i < -(long long)UINT32_MAX)
          throw Input_error(name + ": line " + std::to_string(c.line) + ": vertex index " + std::to_string(i) +
                            " is out of range", Input_error_cause::BAD_INDEX);
        if(i < 0) {   // relative to the vertices read so far
          if(i < -nv)
            throw Input_error(name + ": line " + std::to_string(c.line) + ": relative index " +
                              std::to_string(i) + " but only " + std::to_string(nv) + " vertices so far", Input_error_cause::BAD_INDEX);
          i = nv + 1 + i;
        }
        raw.push_back(i);
      }
      if(raw.size() - first < 3)
        throw Input_error(name + ": line " + std::to_string(c.line) + ": a face needs at least three vertices", Input_error_cause::MALFORMED);
      if(part < 0) {
        if(!pending.empty()) part = soup.part(pending);
        else { if(stem_part < 0) stem_part = soup.file_part(stem_of(name)); part = stem_part; }
      }
      face_ranges.push_back({first, raw.size()});
      face_part.push_back(part);
      face_line.push_back(c.line);
    } else if(kw == "g" || kw == "o") {
      std::string n = c.rest_of_line();
      if(n.empty() && kw == "g") n = "default";
      pending = n;
      part = -1;
    }   // vt, vn, usemtl, mtllib, s, l, p, comments, ...: not needed for a surface
    c.next_line();
  }
  const std::size_t nv = soup.points.size() - base;
  check_finite(soup.points, base, name);
  for(std::size_t f = 0; f < face_ranges.size(); ++f) {
    poly.clear();
    for(std::size_t k = face_ranges[f].first; k < face_ranges[f].second; ++k) {
      if(raw[k] > (long long)nv)
        throw Input_error(name + ": line " + std::to_string(face_line[f]) + ": a face refers to vertex " +
                          std::to_string(raw[k]) + " but the file has " + std::to_string(nv) + " vertices", Input_error_cause::BAD_INDEX);
      poly.push_back(base + std::size_t(raw[k] - 1));
    }
    add_polygon(soup, poly, face_part[f]);
  }
  if(face_ranges.empty())
    throw Input_error(name + ": no face (is this an OBJ file?)", Input_error_cause::NO_SURFACE);
}

// ---- STL --------------------------------------------------------------------------------------

template <typename Point_3>
void read_STL_binary(const std::string& data, const std::string& name, double scale, Surface_soup<Point_3>& soup)
{
  if(data.find_first_not_of(" \t\r\n\f\v") == std::string::npos)
    throw Input_error(name + ": the file is empty", Input_error_cause::EMPTY);
  if(data.size() < 84)
    throw Input_error(name + ": too short for a binary STL (" + std::to_string(data.size()) +
                      " bytes) and not an ASCII STL", Input_error_cause::MALFORMED);
  std::uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);   // little-endian on every platform we build for
  const std::uint64_t expected = 84 + 50 * std::uint64_t(n);
  if(expected != data.size())
    throw Input_error(name + ": binary STL declares " + std::to_string(n) + " triangles (" +
                      std::to_string(expected) + " bytes) but has " + std::to_string(data.size()) +
                      " bytes (" + (expected > data.size() ? "truncated" : "longer than declared") + ", or not an STL file)", expected > data.size() ? Input_error_cause::TRUNCATED : Input_error_cause::MALFORMED);
  if(n == 0) throw Input_error(name + ": the STL file has no triangle", Input_error_cause::NO_SURFACE);
  const std::size_t base = soup.points.size();
  const int part = soup.file_part(stem_of(name));
  soup.points.reserve(base + 3 * std::size_t(n));
  std::vector<std::size_t> poly(3);
  for(std::uint32_t t = 0; t < n; ++t) {
    const char* f = data.data() + 84 + 50 * std::size_t(t) + 12;   // skip the normal
    for(int k = 0; k < 3; ++k) {
      float x[3];
      std::memcpy(x, f + 12 * k, 12);
      soup.points.push_back(Point_3(double(x[0]) * scale, double(x[1]) * scale, double(x[2]) * scale));
      poly[std::size_t(k)] = soup.points.size() - 1;
    }
    add_polygon(soup, poly, part);
  }
  check_finite(soup.points, base, name);
}

template <typename Point_3>
void read_STL_ascii(const std::string& data, const std::string& name, double scale, Surface_soup<Point_3>& soup)
{
  Text_cursor c{data.data(), data.data() + data.size()};
  const std::size_t base = soup.points.size();
  std::size_t solids = 0, facets = 0;
  int stem_part = -1;
  auto fail = [&](const std::string& what, Input_error_cause cause = Input_error_cause::MALFORMED) {
    c.fail(name, what, cause);
  };
  std::vector<std::size_t> poly;
  for(std::string_view t = c.any_token(); !t.empty(); t = c.any_token()) {
    if(!ieq(t, "solid")) fail("expected 'solid', found '" + std::string(t.substr(0, 40)) + "'");
    std::string sname = c.rest_of_line();
    int part;
    if(!sname.empty()) part = soup.part(sname);
    else { if(stem_part < 0) stem_part = soup.file_part(stem_of(name)); part = stem_part; sname = stem_of(name); }
    ++solids;
    bool closed = false;
    for(t = c.any_token(); !t.empty(); t = c.any_token()) {
      if(ieq(t, "endsolid")) { c.rest_of_line(); closed = true; break; }
      if(!ieq(t, "facet")) fail("expected 'facet' or 'endsolid', found '" + std::string(t.substr(0, 40)) + "'");
      c.rest_of_line();   // "normal nx ny nz": recomputed from the vertices
      if(!ieq(c.any_token(), "outer") || !ieq(c.token(), "loop")) fail("expected 'outer loop'");
      poly.clear();
      for(t = c.any_token(); ieq(t, "vertex"); t = c.any_token()) {
        double x[3];
        for(int k = 0; k < 3; ++k)
          if(!parse_double(c.token(), x[k])) fail("a vertex needs three numbers");
        soup.points.push_back(Point_3(x[0] * scale, x[1] * scale, x[2] * scale));
        poly.push_back(soup.points.size() - 1);
      }
      if(t.empty()) fail("the file ends inside a facet (truncated)", Input_error_cause::TRUNCATED);
      if(!ieq(t, "endloop")) fail("expected 'vertex' or 'endloop', found '" + std::string(t.substr(0, 40)) + "'");
      if(!ieq(c.any_token(), "endfacet")) fail("expected 'endfacet'");
      if(poly.size() < 3) fail("a facet needs at least three vertices");
      add_polygon(soup, poly, part);
      ++facets;
    }
    if(!closed) fail("the file ends inside solid '" + sname + "' (truncated: no 'endsolid')", Input_error_cause::TRUNCATED);
  }
  if(solids == 0) throw Input_error(name + ": the STL file is empty", Input_error_cause::EMPTY);
  if(facets == 0) throw Input_error(name + ": the STL file has no triangle", Input_error_cause::NO_SURFACE);
  check_finite(soup.points, base, name);
}

template <typename Point_3>
void read_STL_buffer(const std::string& data, const std::string& name, double scale, Surface_soup<Point_3>& soup)
{
  // binary when the size matches the triangle count (some binary headers start with "solid")
  if(data.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    if(84 + 50 * std::uint64_t(n) == data.size()) return read_STL_binary(data, name, scale, soup);
  }
  std::size_t i = 0;
  while(i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if(i + 5 <= data.size() && ieq(std::string_view(data).substr(i, 5), "solid") && data.find('\0') == std::string::npos)
    return read_STL_ascii(data, name, scale, soup);
  read_STL_binary(data, name, scale, soup);   // throws with the size mismatch
}

// ---- OFF ---------------------------------------------------------------------------------------
// Our own line-based parser: CGAL 5.5's File_scanner_OFF and PLY reader overflow buffers on
// malformed input (found by the fuzz targets within seconds), and a reader must never crash.
// Supported: OFF with the optional prefixes ST, C, N (texture, colour, normal values after the
// coordinates are ignored), counts on the header line or the next one, '#' comments, faces with
// optional colour values after the indices. Not supported (clear error): 4OFF, nOFF, OFF BINARY.

template <typename Point_3>
void read_OFF_buffer(const std::string& data, const std::string& name, double scale, Surface_soup<Point_3>& soup)
{
  Text_cursor c{data.data(), data.data() + data.size()};
  auto fail = [&](const std::string& what, Input_error_cause cause = Input_error_cause::MALFORMED) {
    c.fail(name, what, cause);
  };
  // the next token of the data section, skipping comments and line ends
  auto next_line_start = [&]() {
    for(;;) {
      c.skip_blanks();
      if(c.p >= c.end) return false;
      if(*c.p == '\n') { c.next_line(); continue; }
      if(*c.p == '#') { c.next_line(); continue; }
      return true;
    }
  };
  if(!next_line_start()) throw Input_error(name + ": the file is empty", Input_error_cause::EMPTY);
  std::string_view kw = c.token();
  const std::size_t off = kw.find("OFF");
  if(off == std::string_view::npos || off + 3 != kw.size())
    throw Input_error(name + ": not an OFF file (no 'OFF' header)", Input_error_cause::MALFORMED);
  const std::string_view prefix = kw.substr(0, off);
  if(prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
    throw Input_error(name + ": OFF variant '" + std::string(kw) + "' is not supported (3-D OFF only)", Input_error_cause::UNSUPPORTED);
  for(char ch : prefix)
    if(ch != 'S' && ch != 'T' && ch != 'C' && ch != 'N')
      throw Input_error(name + ": not an OFF file (header '" + std::string(kw.substr(0, 40)) + "')", Input_error_cause::MALFORMED);
  long long counts[3];
  int got = 0;
  for(std::string_view t = c.token(); !t.empty() && got < 3; t = c.token()) {
    if(t == "BINARY") throw Input_error(name + ": binary OFF is not supported (convert it to ASCII OFF)", Input_error_cause::UNSUPPORTED);
    if(t[0] == '#') { c.next_line(); break; }
    const auto r = std::from_chars(t.data(), t.data() + t.size(), counts[got]);
    if(r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("bad OFF header: '" + std::string(t.substr(0, 40)) + "' is not a count");
    ++got;
  }
  while(got < 3) {
    if(got == 0 || c.at_eol()) { if(!next_line_start()) fail("truncated OFF header", Input_error_cause::TRUNCATED); }
    std::string_view t = c.token();
    if(t == "BINARY") throw Input_error(name + ": binary OFF is not supported (convert it to ASCII OFF)", Input_error_cause::UNSUPPORTED);
    const auto r = std::from_chars(t.data(), t.data() + t.size(), counts[got]);
    if(r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("bad OFF header: '" + std::string(t.substr(0, 40)) + "' is not a count");
    ++got;
  }
  if(counts[0] < 0 || counts[1] < 0 || counts[2] < 0) fail("negative count in the OFF header");
  // every vertex takes at least 6 bytes ("0 0 0\n"), every face at least 8 ("3 0 1 2\n")
  if(counts[0] > (long long)(data.size() / 6) || counts[1] > (long long)(data.size() / 8))
    throw Input_error(name + ": the OFF header announces " + std::to_string(counts[0]) + " vertices and " +
                      std::to_string(counts[1]) + " faces, more than the file can hold (truncated)", Input_error_cause::TRUNCATED);
  if(counts[0] == 0) throw Input_error(name + ": the surface has no vertex", Input_error_cause::NO_SURFACE);
  if(counts[1] == 0) throw Input_error(name + ": the surface has no face", Input_error_cause::NO_SURFACE);
  c.next_line();
  const std::size_t base = soup.points.size(), nv = std::size_t(counts[0]);
  soup.points.reserve(base + nv);
  for(std::size_t i = 0; i < nv; ++i) {
    if(!next_line_start()) throw Input_error(name + ": the file ends after " + std::to_string(i) + " of " +
                                             std::to_string(nv) + " vertices (truncated)", Input_error_cause::TRUNCATED);
    double x[3];
    for(int k = 0; k < 3; ++k)
      if(!parse_double(c.token(), x[k])) fail("a vertex needs three numbers");
    soup.points.push_back(Point_3(x[0] * scale, x[1] * scale, x[2] * scale));
    c.next_line();
  }
  check_finite(soup.points, base, name);
  const int part = soup.file_part(stem_of(name));
  std::vector<std::size_t> poly;
  for(long long f = 0; f < counts[1]; ++f) {
    if(!next_line_start()) throw Input_error(name + ": the file ends after " + std::to_string(f) + " of " +
                                             std::to_string(counts[1]) + " faces (truncated)", Input_error_cause::TRUNCATED);
    long long n = 0;
    const std::string_view t = c.token();
    const auto r = std::from_chars(t.data(), t.data() + t.size(), n);
    if(r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("'" + std::string(t.substr(0, 40)) + "' is not a vertex count");
    if(n < 3) fail("a face needs at least three vertices");
    if(n > (long long)nv) fail("a face has more corners than the file has vertices");
    poly.clear();
    for(long long k = 0; k < n; ++k) {
      const std::string_view ti = c.token();
      long long id = 0;
      const auto ri = std::from_chars(ti.data(), ti.data() + ti.size(), id);
      if(ti.empty()) fail("a face has fewer indices than it announces");
      if(ri.ec != std::errc() || ri.ptr != ti.data() + ti.size()) fail("'" + std::string(ti.substr(0, 40)) + "' is not a vertex index");
      if(id < 0 || id >= (long long)nv)
        fail("a face refers to vertex " + std::to_string(id) + " but the file has " + std::to_string(nv) + " vertices",
             Input_error_cause::BAD_INDEX);
      poly.push_back(base + std::size_t(id));
    }
    add_polygon(soup, poly, part);
    c.next_line();   // colour values, if any
  }
}

// ---- PLY ---------------------------------------------------------------------------------------
// Our own parser (see above): ASCII, binary little- and big-endian; the vertex element's x, y, z
// (any numeric type) and the face element's vertex_indices / vertex_index list; other elements
// and properties are skipped.

struct Ply_property
{
  std::string name;
  int type = 0;          // size in bytes of the value (1, 2, 4, 8); negative: float (-4) or double (-8)
  bool is_signed = false;
  bool is_list = false;
  int count_type = 0;    // for lists
  bool count_signed = false;
};
struct Ply_element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Ply_property> properties;
};

inline bool ply_type(std::string_view t, int& size, bool& is_signed)
{
  struct T { const char* n; int s; bool sg; };
  static const T types[] = {{"char", 1, true}, {"int8", 1, true}, {"uchar", 1, false}, {"uint8", 1, false},
                            {"short", 2, true}, {"int16", 2, true}, {"ushort", 2, false}, {"uint16", 2, false},
                            {"int", 4, true}, {"int32", 4, true}, {"uint", 4, false}, {"uint32", 4, false},
                            {"float", -4, true}, {"float32", -4, true}, {"double", -8, true}, {"float64", -8, true}};
  for(const T& x : types)
    if(t == x.n) { size = x.s; is_signed = x.sg; return true; }
  return false;
}

template <typename Point_3>
void read_PLY_buffer(const std::string& data, const std::string& name, double scale, Surface_soup<Point_3>& soup)
{
  Text_cursor c{data.data(), data.data() + data.size()};
  auto fail = [&](const std::string& what, Input_error_cause cause = Input_error_cause::MALFORMED) {
    throw Input_error(name + ": " + what, cause);
  };
  if(c.token() != "ply") fail("not a PLY file (no 'ply' header)");
  c.next_line();
  int format = -1;   // 0 ascii, 1 little endian, 2 big endian
  std::vector<Ply_element> elements;
  for(;;) {
    if(c.p >= c.end) fail("truncated PLY header (no 'end_header')", Input_error_cause::TRUNCATED);
    const std::string_view kw = c.token();
    if(kw == "end_header") { c.next_line(); break; }
    if(kw == "format") {
      const std::string_view f = c.token();
      if(f == "ascii") format = 0;
      else if(f == "binary_little_endian") format = 1;
      else if(f == "binary_big_endian") format = 2;
      else fail("unknown PLY format '" + std::string(f.substr(0, 40)) + "'");
    } else if(kw == "element") {
      Ply_element e;
      e.name = std::string(c.token());
      const std::string_view n = c.token();
      const auto r = std::from_chars(n.data(), n.data() + n.size(), e.count);
      if(e.name.empty() || r.ec != std::errc() || r.ptr != n.data() + n.size())
        fail("line " + std::to_string(c.line) + ": bad element declaration");
      elements.push_back(e);
    } else if(kw == "property") {
      if(elements.empty()) fail("line " + std::to_string(c.line) + ": a property before any element");
      Ply_property p;
      std::string_view t = c.token();
      if(t == "list") {
        p.is_list = true;
        if(!ply_type(c.token(), p.count_type, p.count_signed) || p.count_type < 0)
          fail("line " + std::to_string(c.line) + ": bad list count type");
        t = c.token();
      }
      if(!ply_type(t, p.type, p.is_signed)) fail("line " + std::to_string(c.line) + ": unknown property type '" + std::string(t.substr(0, 40)) + "'");
      p.name = std::string(c.token());
      elements.back().properties.push_back(p);
    } else if(kw != "comment" && kw != "obj_info" && !kw.empty()) {
      fail("line " + std::to_string(c.line) + ": unknown header keyword '" + std::string(kw.substr(0, 40)) + "'");
    }
    c.next_line();
  }
  if(format < 0) fail("the PLY header has no 'format' line");

  const char* bp = c.p;   // binary cursor
  auto read_value = [&](int type, bool is_signed, double& v) -> bool {
    if(format == 0) {
      const std::string_view t = c.any_token();
      if(t.empty()) return false;
      if(!parse_double(t, v)) fail("line " + std::to_string(c.line) + ": '" + std::string(t.substr(0, 40)) + "' is not a number");
      return true;
    }
    const int n = type < 0 ? -type : type;
    if(c.end - bp < n) return false;
    unsigned char b[8];
    std::memcpy(b, bp, std::size_t(n));
    bp += n;
    if(format == 2) std::reverse(b, b + n);
    if(type == -4) { float f; std::memcpy(&f, b, 4); v = f; }
    else if(type == -8) { std::memcpy(&v, b, 8); }
    else {
      std::uint64_t u = 0;
      for(int i = n - 1; i >= 0; --i) u = (u << 8) | b[i];
      if(is_signed && n < 8 && (u >> (8 * n - 1))) u |= ~std::uint64_t(0) << (8 * n);
      v = is_signed ? double(std::int64_t(u)) : double(u);
    }
    return true;
  };
  const std::size_t base = soup.points.size();
  std::size_t nv = 0;
  bool has_faces = false;
  const int part = soup.file_part(stem_of(name));
  std::vector<std::size_t> poly;
  std::vector<std::pair<std::vector<std::size_t>, std::size_t>> faces;   // checked once all vertices are known
  for(const Ply_element& e : elements) {
    const std::size_t remaining = std::size_t(c.end - (format == 0 ? c.p : bp));
    if(e.count > remaining)   // every record takes at least one byte
      fail("element '" + e.name + "' announces " + std::to_string(e.count) + " records, more than the file holds (truncated)", Input_error_cause::TRUNCATED);
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for(std::size_t k = 0; k < e.properties.size(); ++k) {
      const auto& p = e.properties[k];
      if(e.name == "vertex" && !p.is_list) {
        if(p.name == "x") ix = int(k); else if(p.name == "y") iy = int(k); else if(p.name == "z") iz = int(k);
      }
      if(e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) iface = int(k);
    }
    const bool is_vertex = e.name == "vertex";
    if(is_vertex && (ix < 0 || iy < 0 || iz < 0)) fail("the vertex element lacks an x, y or z property");
    if(is_vertex) { nv = std::size_t(e.count); soup.points.reserve(base + nv); }
    if(e.name == "face") has_faces = true;
    for(std::uint64_t r = 0; r < e.count; ++r) {
      double xyz[3] = {0, 0, 0};
      for(std::size_t k = 0; k < e.properties.size(); ++k) {
        const Ply_property& p = e.properties[k];
        double v = 0;
        if(!p.is_list) {
          if(!read_value(p.type, p.is_signed, v)) fail("the file ends inside element '" + e.name + "' (truncated)", Input_error_cause::TRUNCATED);
          if(int(k) == ix) xyz[0] = v; else if(int(k) == iy) xyz[1] = v; else if(int(k) == iz) xyz[2] = v;
          continue;
        }
        double nd = 0;
        if(!read_value(p.count_type, p.count_signed, nd)) fail("the file ends inside element '" + e.name + "' (truncated)", Input_error_cause::TRUNCATED);
        if(!(nd >= 0) || nd != std::floor(nd) || nd > double(data.size())) fail("bad list length in element '" + e.name + "'");
        const std::size_t n = std::size_t(nd);
        if(int(k) == iface) poly.clear();
        for(std::size_t i = 0; i < n; ++i) {
          if(!read_value(p.type, p.is_signed, v)) fail("the file ends inside element '" + e.name + "' (truncated)", Input_error_cause::TRUNCATED);
          if(int(k) == iface) {
            if(!(v >= 0) || v != std::floor(v) || v >= 4294967295.0) fail("a face has a bad vertex index");
            poly.push_back(std::size_t(v));
          }
        }
        if(int(k) == iface) {
          if(poly.size() < 3) fail("a face needs at least three vertices");
          faces.push_back({poly, r});
        }
      }
      if(is_vertex) soup.points.push_back(Point_3(xyz[0] * scale, xyz[1] * scale, xyz[2] * scale));
    }
  }
  if(nv == 0) fail("the surface has no vertex", Input_error_cause::NO_SURFACE);
  if(!has_faces || faces.empty()) fail("the surface has no face", Input_error_cause::NO_SURFACE);
  check_finite(soup.points, base, name);
  for(auto& f : faces) {
    for(std::size_t& id : f.first) {
      if(id >= nv)
        fail("face " + std::to_string(f.second) + " refers to vertex " + std::to_string(id) + " but the file has " +
             std::to_string(nv) + " vertices", Input_error_cause::BAD_INDEX);
      id += base;
    }
    add_polygon(soup, f.first, part);
  }
}

} // namespace internal

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief parses a surface held in memory and appends it to `soup`.
 *
 * `format` is `"obj"`, `"stl"`, `"off"` or `"ply"`; `data` may be gzip-compressed; `name` is used
 * in messages and names the part of a file without groups or solid names. Coordinates are
 * multiplied by `scale`.
 * \throws Input_error with a one-line message "name: cause"
 */
template <typename Point_3>
void read_surface_buffer(const std::string& data, const std::string& name, const std::string& format,
                         Surface_soup<Point_3>& soup, double scale = 1.0)
{
  if(!(std::isfinite(scale) && scale > 0))
    throw Input_error(name + ": the scale factor must be a positive number", Input_error_cause::BAD_PARAMETER);
  if(data.empty()) throw Input_error(name + ": the file is empty", Input_error_cause::EMPTY);
  if(internal::is_gzip(data))
    return read_surface_buffer(internal::gunzip(data, name), name, format, soup, scale);
  // a failed read leaves `soup` as it was
  const std::size_t np = soup.points.size(), nt = soup.triangles.size(), nn = soup.part_names.size(),
                    npoly = soup.polygons;
  try {
    if(format == "obj") internal::read_OBJ_buffer(data, name, scale, soup);
    else if(format == "stl") internal::read_STL_buffer(data, name, scale, soup);
    else if(format == "off") internal::read_OFF_buffer(data, name, scale, soup);
    else if(format == "ply") internal::read_PLY_buffer(data, name, scale, soup);
    else throw Input_error(name + ": unknown surface format '" + format + "' (expected .off, .obj, .stl or .ply, "
                           "optionally gzip-compressed)", Input_error_cause::UNSUPPORTED);
  } catch(...) {
    soup.points.resize(np); soup.triangles.resize(nt); soup.part_of_triangle.resize(nt);
    soup.part_names.resize(nn); soup.polygons = npoly;
    throw;
  }
  if(soup.points.size() > std::size_t(UINT32_MAX))
    throw Input_error(name + ": more than 2^32 points are not supported", Input_error_cause::UNSUPPORTED);
  soup.files.push_back(name);
}

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief reads a triangulated surface file (OFF, OBJ, STL ASCII or binary, PLY, by the file's
 * extension; each optionally gzip-compressed, e.g. `bike.obj.gz`) and appends it to `soup`.
 * Polygons with more than three corners are split into fans. OBJ groups and objects and STL solid
 * names become part names; other files are one part named after the file's base name.
 * \throws Input_error with a one-line message naming the file and the cause
 */
template <typename Point_3>
void read_surface(const std::string& filename, Surface_soup<Point_3>& soup, double scale = 1.0)
{
  const std::string format = internal::format_of(filename);
  if(format != "off" && format != "obj" && format != "stl" && format != "ply")
    throw Input_error(filename + ": unknown surface format '" + format + "' (expected .off, .obj, .stl or .ply, "
                      "optionally followed by .gz)", Input_error_cause::UNSUPPORTED);
  std::ifstream in(filename, std::ios::binary);
  if(!in) throw Input_error(filename + ": cannot open the file for reading", Input_error_cause::UNREADABLE);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if(in.bad()) throw Input_error(filename + ": read error", Input_error_cause::UNREADABLE);
  read_surface_buffer(data, filename, format, soup, scale);
}

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief parses feature lines held in memory as OBJ (optionally gzip-compressed): the `v` vertices and
 * the `l` polylines (one-based or negative indices, `v/vt` forms accepted); coordinates are
 * multiplied by `scale`. Appends to `polylines`.
 * \throws Input_error with a one-line message naming the file and the cause
 */
template <typename Point_3>
void read_polylines_buffer(std::string data, const std::string& filename, std::vector<std::vector<Point_3>>& polylines,
                           double scale = 1.0)
{
  if(!(std::isfinite(scale) && scale > 0))
    throw Input_error(filename + ": the scale factor must be a positive number", Input_error_cause::BAD_PARAMETER);
  if(internal::is_gzip(data)) data = internal::gunzip(data, filename);
  if(data.empty()) throw Input_error(filename + ": the file is empty", Input_error_cause::EMPTY);
  internal::Text_cursor c{data.data(), data.data() + data.size()};
  std::vector<Point_3> pts;
  std::vector<std::pair<std::vector<long long>, std::size_t>> lines;
  while(c.p < c.end) {
    const std::string_view kw = c.token();
    if(kw == "v") {
      double x[3];
      for(int k = 0; k < 3; ++k)
        if(!internal::parse_double(c.token(), x[k]))
          throw Input_error(filename + ": line " + std::to_string(c.line) + ": a vertex needs three numbers",
                            Input_error_cause::MALFORMED);
      if(!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
        throw Input_error(filename + ": line " + std::to_string(c.line) + ": a coordinate is not a finite number",
                          Input_error_cause::NON_FINITE);
      pts.push_back(Point_3(x[0] * scale, x[1] * scale, x[2] * scale));
    } else if(kw == "l") {
      std::vector<long long> ids;
      for(std::string_view t = c.token(); !t.empty(); t = c.token()) {
        const std::string_view idx = t.substr(0, t.find('/'));
        long long i = 0;
        const auto r = std::from_chars(idx.data(), idx.data() + idx.size(), i);
        if(r.ec != std::errc() || r.ptr != idx.data() + idx.size() || i == 0 || i > (long long)UINT32_MAX ||
           i < -(long long)pts.size())
          throw Input_error(filename + ": line " + std::to_string(c.line) + ": '" + std::string(t.substr(0, 40)) +
                            "' is not a vertex index", Input_error_cause::BAD_INDEX);
        ids.push_back(i < 0 ? (long long)pts.size() + 1 + i : i);
      }
      if(ids.size() < 2)
        throw Input_error(filename + ": line " + std::to_string(c.line) + ": a line needs two vertices",
                          Input_error_cause::MALFORMED);
      lines.push_back({ids, c.line});
    }
    c.next_line();
  }
  if(lines.empty()) throw Input_error(filename + ": no 'l' polyline (is this an OBJ file of lines?)", Input_error_cause::NO_SURFACE);
  for(const auto& l : lines) {
    std::vector<Point_3> pl;
    for(long long i : l.first) {
      if(i > (long long)pts.size())
        throw Input_error(filename + ": line " + std::to_string(l.second) + ": a line refers to vertex " +
                          std::to_string(i) + " but the file has " + std::to_string(pts.size()) + " vertices",
                          Input_error_cause::BAD_INDEX);
      pl.push_back(pts[std::size_t(i - 1)]);
    }
    polylines.push_back(std::move(pl));
  }
}

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief reads feature lines from an OBJ file; see `read_polylines_buffer()` for the format.
 * \throws Input_error with a one-line message naming the file and the cause
 */
template <typename Point_3>
void read_polylines(const std::string& filename, std::vector<std::vector<Point_3>>& polylines, double scale = 1.0)
{
  std::ifstream in(filename, std::ios::binary);
  if(!in) throw Input_error(filename + ": cannot open the file for reading", Input_error_cause::UNREADABLE);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if(in.bad()) throw Input_error(filename + ": read error", Input_error_cause::UNREADABLE);
  read_polylines_buffer(std::move(data), filename, polylines, scale);
}

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief reads a surface file as a plain triangle soup (parts ignored); see the other overload.
 */
template <typename Point_3>
void read_surface(const std::string& filename, std::vector<Point_3>& points,
                  std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  Surface_soup<Point_3> soup;
  read_surface(filename, soup);
  points = std::move(soup.points);
  triangles = std::move(soup.triangles);
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
