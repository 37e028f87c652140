// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_STATUS_H
#define CGAL_HEX_MESHING_3_STATUS_H

#include <CGAL/Bbox_3.h>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief what `make_hex_mesh_3()` returns.
 */
enum class Status
{
  SUCCESS = 0,          ///< every criterion is met; the mesh is complete
  CANCELED,             ///< the visitor asked to stop: the mesh is valid but coarser
  CELL_LIMIT_REACHED,   ///< refinement stopped before exceeding `max_cells`: valid, coarser mesh
  INVALID_INPUT         ///< the domain, criteria or options are unusable; see `Input_error`
};

/// \brief a short English name of a status (`"SUCCESS"`, `"CANCELED"`, ...).
inline const char* status_name(Status s)
{
  switch(s) {
    case Status::SUCCESS: return "SUCCESS";
    case Status::CANCELED: return "CANCELED";
    case Status::CELL_LIMIT_REACHED: return "CELL_LIMIT_REACHED";
    case Status::INVALID_INPUT: return "INVALID_INPUT";
  }
  return "UNKNOWN";
}

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief thrown for input the package cannot use: an unreadable or empty surface file, a region
 * seed outside the box or inside a body, a box that cannot hold the requested sizes.
 * `what()` is a one-line message naming the cause (and the file, when there is one).
 */
class Input_error : public std::runtime_error
{
public:
  explicit Input_error(const std::string& what) : std::runtime_error(what) {}
};

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief a leak of a seeded region: cells the flood fill from the seed reached (through a hole or
 * a crack of the surface wider than the cells) but that the winding number puts inside a body.
 *
 * The winding number decides: these cells are not meshed. `passage` bounds the grid faces across
 * which the flood entered the leak (the faces between the leak and the cells that stay), which is
 * where the hole is.
 */
struct Region_leak
{
  std::size_t cells = 0;            ///< cells of the leak
  double volume = 0;                ///< their volume
  Bbox_3 bbox;                      ///< bounding box of the leak's cells
  Bbox_3 passage;                   ///< bounding box of the faces between the leak and the region
  std::size_t passage_faces = 0;    ///< number of those faces
  double passage_area = 0;          ///< their area
  double max_winding_number = 0;    ///< the largest winding number at a leak cell's centre
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_STATUS_H
