// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_DEFAULT_VISITOR_H
#define CGAL_HEX_MESHING_3_DEFAULT_VISITOR_H

#include <cstddef>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief the visitor used when none is given: every hook is empty and inline, so it costs nothing.
 *
 * A model of `HexMeshingVisitor`. A user visitor provides the same three members; pass it as
 * `CGAL::parameters::visitor(std::ref(v))` to keep its state. Phases are, in order:
 * `"refine"`, `"balance"`, `"classify"`, `"extract"`. `go_further()` is polled once per phase
 * and once per batch of cells (never per cell); returning `false` stops refinement at the next
 * safe point, and the mesher still balances and extracts, so the mesh it returns is valid, only
 * coarser (status `Status::CANCELED`).
 */
struct Default_visitor
{
  /// a phase starts; `work` is an estimate of the number of cells it will visit (0 if unknown)
  void on_phase_begin(const char* /*name*/, std::size_t /*work*/) {}
  /// the phase ended
  void on_phase_end(const char* /*name*/) {}
  /// `fraction_done` in [0,1] for the current phase; return `false` to cancel
  bool go_further(double /*fraction_done*/) { return true; }
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_DEFAULT_VISITOR_H
