#include "nbar/dynamics/forward_dynamics.hpp"

namespace nbar {

ResultTable simulation_table(const Mechanism& mechanism, const Simulation& simulation) {
  ResultTable table;
  KinematicRows kinematic(mechanism, 2);
  kinematic.name_columns(table.columns, table.units);
  const std::size_t kinematic_columns = kinematic.column_count();
  for (const char* name : {"kinetic", "potential", "spring", "dissipated", "work", "balance"}) {
    table.columns.push_back(std::string("energy.") + name);
    table.units.push_back("J");
  }
  table.rows.reserve(simulation.samples.size());
  for (std::size_t i = 0; i < simulation.samples.size(); ++i) {
    std::vector<double> row(table.columns.size());
    kinematic.fill(simulation.samples[i], row.data());
    const SimulationEnergy& e = simulation.energies[i];
    const double energies[] = {e.kinetic, e.gravity + e.spring, e.spring, e.dissipated, e.work_in, e.balance};
    std::copy(std::begin(energies), std::end(energies), row.begin() + static_cast<std::ptrdiff_t>(kinematic_columns));
    table.rows.push_back(std::move(row));
  }
  zero_numerical_noise(table);  // as solve's tables: 1e-27 deg/s^2 of a crank at constant speed is 0
  // The balance is the run's energy error, told as it is however small: 1e-12 J is not 0.
  const std::size_t balance = table.columns.size() - 1;
  for (std::size_t i = 0; i < table.rows.size(); ++i) table.rows[i][balance] = simulation.energies[i].balance;
  return table;
}

}  // namespace nbar
