#pragma once
// mesh: meshes of Gmsh, read and written through the Gmsh API of libgmsh, which is not linked but
// loaded when the first Gmsh file is read or written (gmsh_api.hpp): a run without Gmsh files does
// not pay its start-up.
//
// A Gmsh model maps onto a TetMesh as follows:
//   - the tetrahedra of all volumes are the tetrahedra: all 4-node (linear) or all 10-node
//     (quadratic, theory.md §2.12: the corners in TetMesh::tets, the edge nodes in tet_extra, in
//     Gmsh's node order, which is TetMesh's); a physical group of dimension 3 is a region (named
//     by its physical name, or "3:<tag>" when it has none);
//   - a physical group of dimension 2 is a boundary tag (its name, or "2:<tag>"); each of its
//     triangles, 3-node with 4-node tetrahedra and 6-node with 10-node ones, is one boundary face
//     with that tag (its corners; its edge nodes, face_extra, are those of its tetrahedron), and
//     the elementary surface it lies on is the face's entity (so `[contact] patches = "mesh"`
//     makes each surface one patch);
//   - but a physical group of dimension 2 none of whose triangles is a face of a tetrahedron (a
//     surface meshed alone, or the surface of a volume that is in no physical group, which Gmsh
//     leaves out of an .msh file it saves) is a rigid surface (TetMesh::rigid_surfaces), for a
//     rigid obstacle: its triangles as in the file, 3-node or 6-node, on copies of their corners.
//     The edge nodes of 6-node triangles are left out: the rigid surface is the flat triangles
//     through the corners, an approximation of a surface meshed curved at order 2;
//   - a physical group of dimension 1 or 0 (a curve, a point) is a node set (its name, or
//     "1:<tag>", "0:<tag>"): the nodes of its entities and of their elements, curves' end points
//     included, and the midpoints of 3-node lines (a quadratic mesh's curves); a [[dirichlet]]
//     boundary may name it (TetMesh::node_sets).
// Coordinates are taken as they are in the file, in metres.
//
// Gmsh keeps global state: these functions initialise and finalise it themselves. They may be
// called from several threads at once: each holds a process-wide lock from Gmsh's initialisation
// to its finalisation, so the Gmsh parts of concurrent calls run one after another (the rest of a
// run does not wait). They must not be called while the caller itself uses the same libgmsh
// outside them (e.g. Gmsh's own Python module in the same process), which the lock cannot see.

#include <filesystem>
#include <optional>

#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::mesh {

/// Reads a Gmsh mesh: an MSH file (versions 2.2 and 4.1, ASCII or binary), or a .geo file, which
/// is meshed in 3D on the fly (after setting Mesh.MeshSizeFactor to `size_factor`, if given;
/// size_factor > 0 and only for a .geo file).
///
/// `order`, if given (1 or 2), is the order of the elements wanted (theory.md §2.12). A .geo file
/// is meshed at that order whatever its own Mesh.ElementOrder (at order 2 Gmsh places the edge
/// nodes on the geometry: edges on a curved surface are curved). A linear MSH file asked for at
/// order 2 is made quadratic with straight edges (add_edge_midpoints: the new nodes come after
/// the file's); a quadratic one asked for at order 1 is refused. Without `order` the mesh is of
/// the file's order (a .geo file's Mesh.ElementOrder, 1 by default).
///
/// Returns the mesh with its nodes renumbered 0..n-1 in the order of their Gmsh tags, its
/// tetrahedra positively oriented, its tagged triangles oriented outward (the right-hand normal
/// points away from the fourth vertex of the tetrahedron they bound; a triangle between two
/// tetrahedra is oriented against the first), a triangle in several 2D physical groups listed
/// once per group, face_entity the Gmsh surface tag of each face, and the regions (tet_region,
/// region_names) of the 3D physical groups: tetrahedra in none of them form a region "body";
/// without any 3D physical group tet_region and region_names are empty (one region, "body"),
/// the node sets of the 1D and 0D physical groups, and the rigid surfaces: each 2D physical
/// group none of whose triangles is a face of a tetrahedron, with its triangles in the file's
/// vertex order and its own points (the Gmsh nodes of its triangles, in the order of their tags);
/// a node that only rigid surfaces use is not a node of the mesh. (In a .geo file every volume
/// is meshed, so the surface of a volume in no physical group is a boundary of its region
/// "body", not a rigid surface: a rigid surface there must be meshed without a volume.)
///
/// Throws InputError naming the file, and where it applies the Gmsh element or node tag, if the
/// file does not exist or Gmsh cannot read it (with Gmsh's own message), if it has no volume
/// element, a volume element other than a 4-node or 10-node tetrahedron (third order, hexahedra,
/// prisms, pyramids), both 4-node and 10-node tetrahedra (in one volume or in several), a surface
/// element of a 2D physical group other than a 3-node or 6-node triangle, a line of a 1D physical
/// group other than a 2-node or 3-node one, triangles or lines of both orders on one entity, a
/// tagged triangle not of the tetrahedra's order or whose edge nodes are not its tetrahedron's, a
/// tetrahedron with a node twice, two tetrahedra with different edge nodes on one edge, an inverted
/// or degenerate tetrahedron (by its corners), a node of no tetrahedron (nor of a rigid surface), a
/// 2D physical group with some triangles that are faces of the tetrahedra and some that are not, or
/// a face shared by three or more tetrahedra (a non-conforming mesh), a 1D or 0D physical group
/// with no node, with the name of a 2D one, or with a node only of a rigid surface; for a
/// size_factor given with an MSH file or not positive; for an order other than 1 and 2, or 1 with a
/// quadratic MSH file; and if libgmsh cannot be loaded (naming the library, its Debian package and
/// the loader's message). Finally runs check_mesh.
TetMesh read_gmsh(const std::filesystem::path& file, std::optional<Real> size_factor = {},
                  std::optional<int> order = {});

/// MSH format versions write_gmsh can write.
inline constexpr int kMsh22 = 22;
inline constexpr int kMsh41 = 41;

/// Writes `mesh` as an MSH file of version `msh_version` (kMsh41 or kMsh22), ASCII or binary. The
/// file name must end in ".msh". The elements are of the mesh's order: 4-node tetrahedra and 3-node
/// triangles, or, for a quadratic mesh, 10-node tetrahedra and 6-node triangles with their edge
/// nodes (tet_extra, face_extra; the rigid surfaces keep 3-node triangles). Each region is one
/// discrete volume and a physical group of dimension 3 (its name, or "body" for a mesh with one
/// unnamed region); each distinct face_entity value is one discrete surface, with that value as its
/// Gmsh tag where it is positive (faces with entity -1 get one new surface per tag); each boundary
/// tag with faces is a physical group of dimension 2. Node i is Gmsh node i+1, so read_gmsh gives
/// back the same nodes, tetrahedra, tags and face entities. Each rigid surface is one more discrete
/// surface with nodes of its own (numbered after the mesh's) and a 2D physical group of its name,
/// so that read_gmsh gives it back too. Empty tags are not written (Gmsh cannot store them), nor
/// are node sets (curves and points).
///
/// The file is written atomically (a temporary file in the same folder, then renamed); the
/// folder is created if needed. Throws InputError for a bad version or file name, fricon::Error
/// naming the file if libgmsh cannot be loaded (as read_gmsh says) or Gmsh or the file system
/// fails.
void write_gmsh(const std::filesystem::path& file, const TetMesh& mesh, int msh_version = kMsh41,
                bool binary = false);

}  // namespace fricon::mesh
