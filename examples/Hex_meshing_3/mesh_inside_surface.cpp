// Meshes the inside of a closed surface with hexahedra and writes a VTU file for ParaView.
//   mesh_inside_surface [surface.off] [cell size] [surface size] [out.vtu]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/IO/write_VTU.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>
#include <CGAL/make_hex_mesh_3.h>

#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
namespace HM = CGAL::Hex_meshing_3;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : "data/eight.off";
  const double size = argc > 2 ? std::atof(argv[2]) : 0.1;
  const double surface_size = argc > 3 ? std::atof(argv[3]) : 0.025;
  const std::string output = argc > 4 ? argv[4] : "eight_hex.vtu";
  try {
    HM::Surface_domain_3<K> domain(input);                         // reads, welds, builds the inside test
    CGAL::Hex_mesh_criteria_3<K> criteria(size, surface_size);     // cell size, size at the surface
    HM::Hex_mesh_3<K> mesh;
    // (with TBB, a retry of the boundary capture may run ahead on another thread: same mesh)
    const HM::Status status = CGAL::make_hex_mesh_3<CGAL::Parallel_if_available_tag>(domain, criteria, mesh);
    std::cout << HM::status_name(status) << ": " << mesh.number_of_cells() << " hexahedra, "
              << mesh.number_of_vertices() << " vertices, " << mesh.hanging_nodes.size() << " hanging nodes\n";
    if(!HM::IO::write_VTU(output, mesh)) { std::cerr << "cannot write " << output << "\n"; return EXIT_FAILURE; }
    std::cout << "wrote " << output << "\n";
    return status == HM::Status::SUCCESS && mesh.number_of_cells() > 0 ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch(const HM::Input_error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
}
