// libFuzzer target for one surface reader (the format is chosen at compile time by
// HEX_MESHING_3_FUZZ_FORMAT): any byte string must either parse into a consistent soup, which the
// domain then repairs, or raise an Input_error -- never crash, hang or touch memory it does not own
// (built with AddressSanitizer and UndefinedBehaviorSanitizer).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_meshing_3/IO/read_surface.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
namespace HM = CGAL::Hex_meshing_3;

#define HM_CHECK(c) do { if(!(c)) { __builtin_trap(); } } while(0)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string buffer(reinterpret_cast<const char*>(data), size);
  const std::string format = HEX_MESHING_3_FUZZ_FORMAT;
  if(format == "lines") {   // feature lines (OBJ polylines)
    std::vector<std::vector<K::Point_3>> lines;
    try {
      HM::IO::read_polylines_buffer(buffer, "fuzz.obj", lines);
    } catch(const HM::Input_error& e) {
      HM_CHECK(std::string(e.what()).rfind("fuzz.obj: ", 0) == 0);
      return 0;
    }
    HM_CHECK(!lines.empty());
    for(const auto& l : lines) HM_CHECK(l.size() >= 2);
    return 0;
  }
  HM::IO::Surface_soup<K::Point_3> soup;
  try {
    HM::IO::read_surface_buffer(buffer, "fuzz." + format, format, soup);
  } catch(const HM::Input_error& e) {
    HM_CHECK(std::string(e.what()).rfind("fuzz." + format + ": ", 0) == 0);   // names the file
    HM_CHECK(soup.points.empty() && soup.triangles.empty());                 // left untouched
    return 0;
  }
  // a successful read is consistent
  HM_CHECK(!soup.triangles.empty());
  HM_CHECK(soup.part_of_triangle.size() == soup.triangles.size());
  for(std::size_t i = 0; i < soup.triangles.size(); ++i) {
    for(std::uint32_t v : soup.triangles[i]) HM_CHECK(v < soup.points.size());
    HM_CHECK(soup.part_of_triangle[i] >= 0 && std::size_t(soup.part_of_triangle[i]) < soup.part_names.size());
  }
  // and the domain either accepts it (repairs, inside test) or says why not
  if(soup.triangles.size() <= 2000) {
    try {
      HM::Surface_domain_3<K> domain(soup);
      HM_CHECK(domain.number_of_triangles() > 0);
      (void)domain.is_inside(K::Point_3(0.25, 0.5, 0.125));
    } catch(const HM::Input_error&) {
    }
  }
  return 0;
}
