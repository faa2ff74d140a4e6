// fricon check PROBLEM.toml: read and validate a problem, build its model without K and run the
// checks solve makes before it factorizes K (driver::check_model: the prescribed values at every
// step, the contact discretization), print the sizes and the effective problem; nothing is
// solved. What check accepts, solve refuses only for what the factorization or the solve finds.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "fricon/contact/friction_law.hpp"
#include "fricon/driver/floating_bodies.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/io/problem_file.hpp"

namespace fricon::app {

namespace {

// One line per contact pair: its surfaces, patches, stability and (against a body) the reach.
void print_pair(const contact::ContactDiscretization& d, std::size_t i) {
  const contact::PairInfo& pair = d.pairs[i];
  Index patches = 0, faces = 0;
  for (Index p = 0; p < d.n_patches(); ++p)
    if (d.patch_pair[static_cast<std::size_t>(p)] == static_cast<Index>(i)) {
      ++patches;
      faces += static_cast<Index>(d.patches.faces[static_cast<std::size_t>(p)].size());
    }
  const std::string against =
      pair.master.empty()
          ? std::string("the plane")
          : fmt::format(
                "'{}' ({} of the {} triangles of '{}' within {:.3g} m of it, coverage "
                "{:.6f})",
                pair.master, faces, pair.n_tag_faces, pair.boundary, pair.search_distance,
                pair.master_coverage);
  fmt::print("  {:<10} '{}' against {}: {} patches, sigma_min/sigma_max(B) = {:.3g}\n", pair.key,
             pair.boundary, against, patches, pair.stability.ratio);
}

int check(const std::string& file, const std::vector<std::string>& sets) {
  const driver::Problem problem = io::read_problem(file, sets);
  // What solve builds and checks before it factorizes K (driver/model.hpp), without K.
  PhaseTimes times;
  const driver::Model model = driver::assemble_loads(problem, times);
  const std::optional<contact::ContactDiscretization> disc = driver::check_model(problem, model);
  const mesh::TetMesh& mesh = model.mesh;
  const fe::DofMap& dofs = model.dofs;
  fmt::print("{}: valid\n", file);
  fmt::print(
      "  mesh       {} nodes, {} {}-node tetrahedra, {} regions, {} boundary triangles (tags: "
      "{})\n",
      mesh.n_nodes(), mesh.n_tets(), mesh.nodes_per_tet(), mesh.n_regions(), mesh.n_faces(),
      mesh.tag_list());
  fmt::print("  unknowns   n_primal = {}\n", dofs.n_free());
  if (!model.floating.empty() || model.bodies.n_bodies() > 1)
    for (const driver::BodyReport& body : driver::describe_bodies(model))
      fmt::print("  {:<10} {}\n", body.index == 0 ? "bodies" : "", driver::body_line(body));
  if (disc) {
    fmt::print(
        "  contact    '{}': {} surface nodes ({} contact nodes), {} patches ({}), n_dual = {}, "
        "stability sigma_min/sigma_max(B) = {:.3g}, initial gap {:.3g} to {:.3g} m\n",
        disc->surface.tag, disc->surface.n_nodes(), disc->surface.n_contact_nodes(),
        disc->n_patches(), enum_name(problem.contact.front().patches), disc->n_dual(),
        disc->stability.ratio, disc->gap.minCoeff(), disc->gap.maxCoeff());
    if (disc->pairs.size() > 1 || !disc->pairs.front().master.empty())
      for (std::size_t i = 0; i < disc->pairs.size(); ++i)
        print_pair(*disc, i);
    for (const contact::PairInfo& pair : disc->pairs)
      if (pair.obstacle)
        fmt::print("  obstacle   {}{}\n", disc->pairs.size() > 1 ? pair.key + ": " : "",
                   contact::describe(*pair.obstacle, pair.obstacle_displacement));
    if (!disc->partition_note.empty()) fmt::print("  partition  {}\n", disc->partition_note);
    for (std::size_t i = 0; i < problem.contact.size(); ++i) {
      const driver::ContactOptions& c = problem.contact[i];
      const std::string law = contact::make_friction_law(c.friction)->describe();
      if (problem.contact.size() == 1)
        fmt::print("  friction   {}\n", law);
      else
        fmt::print("  friction   {}: {} {}\n", problem.contact_key(i), enum_name(c.model), law);
    }
  }
  fmt::print("effective problem:\n{}\n", io::to_json(problem).dump(2));
  return kConverged;
}

}  // namespace

Command define_check(CLI::App& app) {
  struct Options {
    std::string file;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd =
      app.add_subcommand("check", "Validate a problem file without solving; print its sizes");
  cmd->add_option("problem", o->file, "Problem file (TOML)")->required();
  cmd->add_option("--set", o->sets, "Override a key of the file: KEY=VALUE, repeatable")
      ->allow_extra_args(false);
  return {cmd, [o] { return check(o->file, o->sets); }};
}

}  // namespace fricon::app
