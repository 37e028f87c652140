// Meshes the air around a body in a box (the region reached from a seed point, as OpenFOAM's
// locationInMesh), with a finer box around the body, reports progress through a visitor and
// writes an OpenFOAM case.
//   mesh_around_body [surface.off] [case directory]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/IO/write_OpenFOAM.h>
#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>
#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/make_hex_mesh_3.h>

#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
namespace HM = CGAL::Hex_meshing_3;
namespace HP = CGAL::Hex_meshing_3::parameters;

struct Progress   // a model of HexMeshingVisitor
{
  void on_phase_begin(const char* name, std::size_t cells) { std::cout << name << " (" << cells << " cells)\n"; }
  void on_phase_end(const char*) {}
  bool go_further(double) { return true; }   // return false to stop early with a valid, coarser mesh
};

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : "data/eight.off";
  const std::string case_dir = argc > 2 ? argv[2] : "eight_air_case";
  try {
    HM::Surface_domain_3<K> domain(input);
    const CGAL::Bbox_3 b = domain.bbox();
    const CGAL::Bbox_3 box(b.xmin() - 1, b.ymin() - 1, b.zmin() - 1, b.xmax() + 2, b.ymax() + 1, b.zmax() + 1);
    CGAL::Hex_mesh_criteria_3<K> criteria(0.4, 0.05);
    criteria.add_refinement_box(CGAL::Bbox_3(b.xmin() - 0.2, b.ymin() - 0.2, b.zmin() - 0.2,
                                             b.xmax() + 1, b.ymax() + 0.2, b.zmax() + 0.2), 0.1);
    HM::Hex_mesh_3<K> mesh;
    Progress progress;
    const K::Point_3 seed(box.xmin() + 0.01, box.ymin() + 0.01, box.zmin() + 0.01);
    CGAL::make_hex_mesh_3(domain, criteria, mesh,
                          HP::meshing_box(box).region_seed(seed).visitor(std::ref(progress)));
    HM::Polyhedral_mesh_3 pm;
    pm.build(mesh);
    const HM::Mesh_quality q = HM::compute_quality(mesh, pm);
    std::cout << mesh.number_of_cells() << " cells, max non-orthogonality "
              << HM::Mesh_quality::range(q.non_orthogonality).max << " deg\n";
    if(!HM::IO::write_OpenFOAM(case_dir, mesh, pm)) { std::cerr << "cannot write " << case_dir << "\n"; return EXIT_FAILURE; }
    std::cout << "wrote " << case_dir << "/constant/polyMesh\n";
    return mesh.number_of_cells() > 0 && q.number_of_inverted_cells() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch(const HM::Input_error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
}
