#pragma once
// fe/elements: the Lagrange elements, one per file (theory.md §2.12). Only
// fe/element.cpp's lagrange_elements names them.

#include "fricon/fe/element.hpp"

namespace fricon::fe {

const Element& tet_p1();       ///< 4-node tetrahedron (Gmsh type 4)
const Element& tet_p2();       ///< 10-node tetrahedron (Gmsh type 11)
const Element& triangle_p1();  ///< 3-node triangle (Gmsh type 2)
const Element& triangle_p2();  ///< 6-node triangle (Gmsh type 9)

}  // namespace fricon::fe
