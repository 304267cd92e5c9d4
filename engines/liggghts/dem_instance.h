// A LIGGGHTS instance run in-process by the coupler, with TFDEM's fixes registered.
// Exposes plain arrays only, so callers need no LIGGGHTS headers (and OpenFOAM code can use
// it without name clashes). File names in the script resolve against the working directory,
// which the coupler sets to the case.
#ifndef TFDEM_DEM_INSTANCE_H
#define TFDEM_DEM_INSTANCE_H

#include <mpi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dem_script.h"
#include "tfdem/particle_engine.h"

namespace LAMMPS_NS {
class LAMMPS;
class FixTfdemCoupling;
}  // namespace LAMMPS_NS

namespace tfdem {

class DemConsole;

// LIGGGHTS as the coupler's particle engine (soft spheres; contacts, walls and integration
// are the DEM script's own).
class DemInstance : public ParticleEngine {
 public:
  // Start LIGGGHTS on `comm`, log to log_file (screen output to log_file + ".screen"; its
  // ERROR lines also go to each rank's stderr), register our fixes and run `script` (with
  // what it includes), which must pass dem_script::coupled_script_problems() (one `fix
  // tfdem/coupling`, no `run`). A fresh start writes the logs anew. Resumed (`resume`), the
  // script runs flattened with read_restart for its read_data (dem_script::resumed_script());
  // an emptied bed runs the script and deletes its particles; the logs continue, and every
  // output file continues from its size at the checkpoint (what the stopped run wrote after
  // it is dropped: the resumed run writes it again), so each ends as a straight run's would.
  // Throws std::runtime_error naming the script and every problem found.
  DemInstance(MPI_Comm comm, const std::string &script, const std::string &log_file,
              const DemResume *resume = nullptr);
  ~DemInstance() override;
  DemInstance(const DemInstance &) = delete;
  DemInstance &operator=(const DemInstance &) = delete;

  std::string name() const override { return "LIGGGHTS"; }
  std::string key() const override { return "liggghts"; }
  // Gravity against constant/g, each contact's time against the DEM step, the gas step a
  // whole number of DEM steps, the scene check, the processor grid's balance (start_checks.cpp)
  StartReport check_start(const CaseAtStart &context) const override;
  double overlap_energy(int a, int b, double ra, double rb, double depth) const override;
  std::string lost_particles_hint() const override;
  // Advance `seconds` as a whole number of DEM steps (the coupler checks at start that the gas
  // step is one)
  void advance(double seconds, bool sample_contacts) override;
  // Advance `steps` DEM steps (LIGGGHTS `run`, set up every time). With `sample_contacts`, the fix records every particle's
  // contact force and N_c at the last step. With no particles and no insertion fix there is
  // nothing to advance (and LIGGGHTS 3.8.0 stops with "Atom types must start from 1"): only
  // the DEM clock moves on.
  void run(long steps, bool sample_contacts = false);
  // Write a LIGGGHTS restart file (particles, contact histories, held fluid forces) to
  // `path`, whole or not at all: written as path + ".tmp", read back (its header and every
  // rank's particle block, so a write cut short by a full disk is caught), synced to disk,
  // then renamed. Collective. Throws std::runtime_error naming the file and what is wrong. An
  // empty DEM without insertion (nothing to run, nothing to save) writes none: false.
  bool write_restart(const std::string &path) override;
  // The script's output files (rank 0; none elsewhere) and their sizes now, every C stream of
  // this process flushed first: what a checkpoint records. Collective.
  std::vector<OutputSize> output_sizes() override;
  // The script's output files whose names are patterns or variables ("file:line: name"): a
  // resumed run cannot cut them back to a checkpoint (a file per snapshot is written whole).
  const std::vector<std::string> &unresumable_outputs() const override { return unresumable_outputs_; }
  // Remove the particles with these atom IDs from the DEM (the same list on every rank;
  // collective). Their IDs are not reused; the next run sets up again.
  void remove_particles(const std::vector<int> &tags) override;
  // True when the script moves its particles (a time-integration fix: nve*, nvt*, npt*,
  // rigid*); a frozen bed has none.
  bool integrates() const;
  // True when the script has a particle insertion fix (style insert/*).
  bool inserts_particles() const;
  // Run one LIGGGHTS command (e.g. output set-up from the coupler).
  void command(const std::string &line);
  double time_step() const;
  // DEM steps done since the start of the simulation (restarts included).
  long long step() const override;
  double time() const override { return step() * time_step(); }
  // Particles on this rank and their per-atom arrays (x, v: 3 per atom; radius, mass: 1).
  std::size_t local_count() const override;
  std::size_t ghost_count() const override;
  // LIGGGHTS' processor grid (ranks along x, y, z), its even cuts of the box
  std::array<int, 3> processor_grid() const;
  const double *positions() const override;
  const double *velocities() const override;
  const double *radii() const override;
  const double *masses() const override;
  // Atom IDs and atom types (1 .. type_count()) of the local particles.
  const int *tags() const override;
  const int *types() const override;
  int type_count() const override;
  // Set the fluid force applied to each local particle every DEM step until set again
  // (3 per local particle, in local order).
  void set_fluid_force(const std::vector<double> &force) override;
  // Contact force (3 per atom, N) and N_c of the local particles at the last sample.
  void contact_sample(std::vector<double> &force, std::vector<int> &coordination) const override;
  // Sum of the gravity vectors of the script's `fix gravity` commands (m/s^2); false when it
  // has none.
  bool gravity(double g[3]) const;
  // Total particles over all ranks, as LIGGGHTS counts them (updated at its own checks).
  long global_count() const override;

  // The DEM's box; particles crossing a face of boundary f are dropped (p wraps them, s and m
  // move the face).
  Box box() const override;

  // Normal contact parameters between atom types a and b (1-based) of a linear model, as the
  // script set them with fix property/global: stiffness k_n (N/m) and either absolute
  // damping eta_n (N s/m, gamman_abs) or restitution e_n (coefficientRestitution). False when
  // k_n is absent (e.g. a Hertz model).
  struct LinearContact {
    double stiffness = 0.0;
    double damping = -1.0;      // < 0 when not given
    double restitution = -1.0;  // < 0 when not given
  };
  bool linear_contact(int a, int b, LinearContact &out) const;

  // Hertz contact parameters of atom types a and b (1-based), as the script set them with
  // fix property/global (youngsModulus and poissonsRatio per atom type). False when absent.
  struct HertzContact {
    double young_a = 0.0, poisson_a = 0.0, young_b = 0.0, poisson_b = 0.0;
  };
  bool hertz_contact(int a, int b, HertzContact &out) const;

 private:
  // The text LIGGGHTS runs: the script checked, flattened and resumed when resuming.
  std::string script_to_run(const std::string &script, const DemResume *resume);
  // Run `step` on rank 0; what it throws is thrown on every rank (collective).
  void on_rank_0(const std::function<void()> &step) const;
  // A fresh start's read_data file (atom_style sphere or granular): every atom inside the box
  // on the sides that drop atoms and finite (throws naming them; LIGGGHTS would not).
  void check_data_file(const dem_script::Script &script) const;
  // Resuming: dumps cut back to their checkpoint sizes; fix print and ave/* files set aside
  // (their fixes open them anew), to be continued by continue_outputs().
  void prepare_outputs(const DemResume &resume);
  void continue_outputs(const DemResume &resume);

  MPI_Comm comm_;
  std::string log_file_;
  std::unique_ptr<DemConsole> console_;
  LAMMPS_NS::LAMMPS *lmp_ = nullptr;
  LAMMPS_NS::FixTfdemCoupling *fix_ = nullptr;
  std::vector<dem_script::OutputFile> outputs_;
  std::vector<std::string> unresumable_outputs_;
};

}  // namespace tfdem

#endif
