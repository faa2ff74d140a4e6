#pragma once
// driver: the option tables of the problem file (driver/option_table.hpp), one per section of
// Problem. The reader, the writer, validate() and docs/problem-file.md all come from these.

#include "fricon/driver/option_table.hpp"

namespace fricon::driver {

/// The top level of the problem file (the Problem itself); the sections are its nested tables.
const OptionTable& problem_table();

const OptionTable& mesh_table();            ///< [mesh] (MeshOptions)
const OptionTable& material_table();        ///< [material] (MaterialOptions)
const OptionTable& material_entry_table();  ///< one [[material]] (with its region)
const OptionTable& dirichlet_table();       ///< one [[dirichlet]] (DirichletOptions)
const OptionTable& traction_table();        ///< one [[traction]] (TractionOptions)
const OptionTable& contact_table();         ///< [contact] (ContactOptions)
const OptionTable& obstacle_table();        ///< [contact.obstacle] (ObstacleOptions)
const OptionTable& friction_table();        ///< [contact.friction] (FrictionOptions)
const OptionTable& loading_table();         ///< [loading] (LoadingOptions)
const OptionTable& solver_table();          ///< [solver] (SolverOptions)
const OptionTable& output_table();          ///< [output] (OutputOptions)

/// Every table, top level first, each once, in the order of docs/problem-file.md.
std::vector<const OptionTable*> all_option_tables();

}  // namespace fricon::driver
