#ifndef cbc3d_RedGreenTables_h
#define cbc3d_RedGreenTables_h

#include <array>
#include <cstdint>
#include <vector>

namespace cbc3d
{
/// Red-green split patterns of one tet, in local point numbers: 0-3 are the tet's corners and
/// 4 + e is the midpoint of edge e (TetEdges order: 01 12 20 03 13 23). An edge mask has bit e
/// set when edge e is split. Children keep the parent's orientation.
using LocalTet = std::array<std::uint8_t, 4>;

/// The green closure of a mask, or null when the mask needs a red split. Closures exist for
/// no split edge (the tet itself), one split edge (2 children), two opposite split edges (4),
/// and the three edges of one face (4). The table is built once from these templates and the
/// 12 rotations of the tet, so every case is a rotated template.
const std::vector<LocalTet>* GreenClosure(std::uint8_t edgeMask);

/// The 8 children of a red split (1:8) whose inner octahedron is cut along the diagonal
/// joining the midpoints of edge `diagonal` and its opposite edge (0, 1 or 2: edges 01-23,
/// 12-03 or 20-13). Choosing the shortest diagonal makes the children of a BCC tet
/// half-size BCC tets.
const std::array<LocalTet, 8>& RedChildren(int diagonal);
} // namespace cbc3d

#endif
