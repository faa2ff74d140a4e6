// fricon mesh brick | info: meshes as Gmsh files.
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/mesh/brick.hpp"
#include "fricon/mesh/gmsh_file.hpp"

namespace fricon::app {

namespace {

struct MeshFileOptions {
  std::vector<double> size{3.0, 1.0, 1.0};
  std::vector<Index> cells{12, 4, 4};
  std::string out, file;
  int msh_version = mesh::kMsh41;
  bool binary = false;
  double size_factor = 0.0;          // 0: not given
  int order = driver::kLinearOrder;  // mesh brick: the elements' order ([mesh] order)
  std::string unit = "m";            // mesh info: the unit of the file's coordinates ([mesh] unit)
};

// `fricon mesh brick`: the structured brick of the paper (theory.md §7.2) as a Gmsh file.
int mesh_brick(const MeshFileOptions& o) {
  const mesh::BrickSpec spec{Vec3(o.size[0], o.size[1], o.size[2]),
                             {o.cells[0], o.cells[1], o.cells[2]}};
  mesh::TetMesh mesh = mesh::make_brick(spec);
  if (o.order == driver::kQuadraticOrder) mesh::add_edge_midpoints(mesh);  // as [mesh] order = 2
  mesh::write_gmsh(o.out, mesh, o.msh_version, o.binary);
  fmt::print("{}: {} nodes, {} {}-node tetrahedra, {} boundary triangles (MSH {} {})\n", o.out,
             mesh.n_nodes(), mesh.n_tets(), mesh.nodes_per_tet(), mesh.n_faces(),
             o.msh_version == mesh::kMsh41 ? "4.1" : "2.2", o.binary ? "binary" : "ASCII");
  return kConverged;
}

// `fricon mesh info FILE`: the sizes of a Gmsh mesh as fricon reads it with [mesh] unit =
// o.unit: its coordinates in metres, so lengths in m, areas in m^2 and volumes in m^3.
int mesh_info(const MeshFileOptions& o) {
  const driver::LengthUnit unit = parse_enum<driver::LengthUnit>(o.unit);
  mesh::TetMesh mesh =
      o.size_factor > 0 ? mesh::read_gmsh(o.file, o.size_factor) : mesh::read_gmsh(o.file);
  mesh::scale_lengths(mesh, driver::metres_per(unit));  // as the problem reader scales it
  fmt::print("{}: {} nodes, {} {}-node tetrahedra, {} boundary triangles\n", o.file, mesh.n_nodes(),
             mesh.n_tets(), mesh.nodes_per_tet(), mesh.n_faces());
  const Vec3 extent = mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff();
  fmt::print("  coordinates  read in {} (as [mesh] unit = \"{}\"{}), in metres below\n", o.unit,
             o.unit, unit == driver::LengthUnit::Metre ? "; --unit mm for a millimetre mesh" : "");
  fmt::print("  extent       {:.6e} x {:.6e} x {:.6e} m\n", extent(0), extent(1), extent(2));
  std::vector<Index> tets_in(static_cast<size_t>(mesh.n_regions()), 0);
  std::vector<double> volume_of(tets_in.size(), 0.0);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    ++tets_in[static_cast<size_t>(mesh.region(t))];
    volume_of[static_cast<size_t>(mesh.region(t))] += mesh::tet_volume(mesh, t);
  }
  fmt::print("  regions\n");
  for (int r = 0; r < mesh.n_regions(); ++r)
    fmt::print("    {:<16} {:>10} tetrahedra, volume {:.6e} m^3\n",
               mesh.region_names.empty() ? "body" : mesh.region_names[static_cast<size_t>(r)],
               tets_in[static_cast<size_t>(r)], volume_of[static_cast<size_t>(r)]);
  fmt::print("  boundary tags\n");
  for (const auto& tag : mesh.tag_names) {
    const std::vector<Index> faces = mesh.faces_with_tag(tag);
    double area = 0.0;
    std::set<int> entities;
    for (Index f : faces) {
      area += mesh::face_area(mesh, f);
      if (!mesh.face_entity.empty()) entities.insert(mesh.face_entity[static_cast<size_t>(f)]);
    }
    fmt::print("    {:<16} {:>10} triangles, area {:.6e} m^2, {} entities\n", tag, faces.size(),
               area, entities.size());
  }
  // Curves and points: only a [[dirichlet]] boundary may name one.
  for (const mesh::NodeSet& set : mesh.node_sets)
    fmt::print("    {:<16} {:>10} node{}, a {} (for [[dirichlet]] only)\n", set.name,
               set.nodes.size(), set.nodes.size() == 1 ? "" : "s", mesh::node_set_kind(set.dim));
  // Surfaces that no tetrahedron carries: rigid obstacles only (theory.md §2.11).
  for (const mesh::RigidSurface& surface : mesh.rigid_surfaces)
    fmt::print(
        "    {:<16} {:>10} triangles, a rigid surface (for obstacle kind \"surface\" only)\n",
        surface.name, surface.triangles.cols());
  return kConverged;
}

}  // namespace

std::vector<Command> define_mesh(CLI::App& app) {
  auto o = std::make_shared<MeshFileOptions>();
  auto* mesh = app.add_subcommand("mesh", "Meshes as Gmsh files (MSH 2.2 and 4.1, .geo)");
  mesh->require_subcommand(1);
  CLI::App* brick = mesh->add_subcommand(
      "brick",
      "Write the structured brick of the paper (5 tetrahedra per cell; boundary tags x0 ... z1,\n"
      "each side's 2 x 2-cell blocks one Gmsh surface) as a Gmsh file");
  brick->add_option("--size", o->size, "Edge lengths [m]: X,Y,Z")
      ->delimiter(',')
      ->expected(3)
      ->check(CLI::PositiveNumber);
  brick->add_option("--cells", o->cells, "Cells per direction: NX,NY,NZ")
      ->delimiter(',')
      ->expected(3)
      ->check(CLI::Range(Index{1}, Index{100000}));
  brick->add_option("--out,-o", o->out, "Output file (.msh)")->required();
  brick->add_option("--msh-version", o->msh_version, "MSH format version: 41 or 22")
      ->check(CLI::IsMember({mesh::kMsh41, mesh::kMsh22}));
  brick->add_flag("--binary", o->binary, "Write a binary MSH file");
  brick
      ->add_option("--order", o->order,
                   "Element order: 1 (4-node tetrahedra) or 2 (10-node, straight edge midpoints;\n"
                   "Gmsh types 11 and 9)")
      ->check(CLI::IsMember({driver::kLinearOrder, driver::kQuadraticOrder}));
  CLI::App* info = mesh->add_subcommand(
      "info",
      "Read a Gmsh file (.msh, or .geo meshed on the fly) as fricon does and print its nodes,\n"
      "tetrahedra, extent, regions (tetrahedra, volume), boundary tags (triangles, area,\n"
      "entities) and curves and points (nodes), in metres (--unit: the unit of its coordinates)");
  info->add_option("file", o->file, "Mesh file (.msh or .geo)")->required();
  info->add_option("--unit", o->unit,
                   "The unit of the file's coordinates, as [mesh] unit: m (default), cm or mm;\n"
                   "lengths, areas and volumes are printed in m, m^2 and m^3")
      ->check(CLI::IsMember(enum_names<driver::LengthUnit>()));
  info->add_option("--size-factor", o->size_factor,
                   "Mesh.MeshSizeFactor for a .geo file (smaller: finer)")
      ->check(CLI::PositiveNumber);
  return {{brick, [o] { return mesh_brick(*o); }}, {info, [o] { return mesh_info(*o); }}};
}

}  // namespace fricon::app
