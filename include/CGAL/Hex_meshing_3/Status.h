// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_STATUS_H
#define CGAL_HEX_MESHING_3_STATUS_H

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

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_STATUS_H
