// What the coupler drives: a particle engine (LIGGGHTS' soft spheres, tfdem::DemInstance, or
// the hard-sphere event-driven engine, tfdem::hard_sphere::HardSphereEngine). The gas solver
// does not know which runs: it advances the engine one coupling interval at a time with the
// fluid forces of the last coupling held, reads the particles back as flat arrays, removes
// those that left through an outlet, and checkpoints and resumes it with the gas.
#ifndef TFDEM_PARTICLE_ENGINE_H
#define TFDEM_PARTICLE_ENGINE_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tfdem {

// A file the engine writes as it runs (LIGGGHTS' fix print, fix ave/*, one-file dumps) and
// its size in bytes at a checkpoint.
using OutputSize = std::pair<std::string, std::uint64_t>;

// What a run resumed from a checkpoint starts from.
struct DemResume {
  std::string restart_file;          // the engine's restart file; "" when the bed had emptied
  long long step = 0;                // the engine's step at the checkpoint
  std::string engine;                // the engine that wrote it (its key(); "" in earlier markers)
  double time = 0;                   // and its simulated time (s)
  std::vector<OutputSize> outputs;   // the engine's output files at the checkpoint
};

struct CouplingConfig;

// The case as the solver knows it when an engine starts, for the engine's own checks.
struct CaseAtStart {
  const CouplingConfig *config = nullptr;
  double gravity[3] = {0, 0, 0};  // m/s^2 (constant/g)
  double gas_step = 0;            // s
  bool adjustable_gas_step = false;  // controlDict's adjustTimeStep
  double fastest_inflow = 0;      // m/s: the largest |U| where the gas flows in
  double fall_speed = 0;          // m/s: a free fall over the domain's extent along gravity
  double cell_size[3] = {0, 0, 0};  // the gas cells (m)
  bool resuming = false;
};

// What an engine says of itself at the start: lines for the log (each with its "TFDEM ..."
// prefix), warnings, and a refusal that stops the run, naming the cause and the fix.
struct StartReport {
  std::vector<std::string> lines, warnings;
  std::string refusal;
};

class ParticleEngine {
 public:
  virtual ~ParticleEngine() = default;

  // "LIGGGHTS" or "the hard-sphere engine", for messages
  virtual std::string name() const = 0;
  // Its name as coupling.yaml's dem.engine gives it ("liggghts", "hard_sphere"), which a
  // checkpoint's marker records
  virtual std::string key() const = 0;

  // Advance `seconds` (one coupling interval, the gas step) with the held fluid forces; with
  // `sample_contacts`, each particle's contact force and N_c at its end are recorded
  virtual void advance(double seconds, bool sample_contacts) = 0;
  // The engine's clock: its steps since the start of the simulation (restarts included) and
  // the simulated time they make (s)
  virtual long long step() const = 0;
  virtual double time() const = 0;

  // Particles on this rank (x, v: 3 per particle; radius, mass: 1) and over all ranks
  virtual std::size_t local_count() const = 0;
  virtual long global_count() const = 0;
  // Copies of other ranks' particles this rank holds for its contacts (LIGGGHTS' ghosts; 0
  // for an engine on one rank): what its neighbour exchange sends each DEM step
  virtual std::size_t ghost_count() const { return 0; }
  virtual const double *positions() const = 0;
  virtual const double *velocities() const = 0;
  virtual const double *radii() const = 0;
  virtual const double *masses() const = 0;
  // IDs and types (1 .. type_count()) of the local particles
  virtual const int *tags() const = 0;
  virtual const int *types() const = 0;
  virtual int type_count() const = 0;

  // The fluid force on each local particle (3 per particle, local order), held until set again
  virtual void set_fluid_force(const std::vector<double> &force) = 0;
  // Contact force (3 per particle, N) and N_c of the local particles at the last sample
  virtual void contact_sample(std::vector<double> &force, std::vector<int> &coordination) const = 0;
  // Remove the particles with these IDs (the same list on every rank; collective)
  virtual void remove_particles(const std::vector<int> &tags) = 0;

  // The engine's state to `path`, whole or not at all (collective); false when there was
  // nothing to write (an empty bed whose engine cannot restart from none)
  virtual bool write_restart(const std::string &path) = 0;
  // The engine's output files and their sizes now (for the checkpoint), and those it cannot
  // cut back to a checkpoint ("file:line: name")
  virtual std::vector<OutputSize> output_sizes() { return {}; }
  virtual const std::vector<std::string> &unresumable_outputs() const {
    static const std::vector<std::string> none;
    return none;
  }

  // Its checks of itself against the case (time steps, gravity, contacts), and what it reports
  // at the start and at the end of a run
  virtual StartReport check_start(const CaseAtStart & /*context*/) const { return {}; }
  virtual std::string end_report() const { return ""; }
  // The elastic energy (J) an overlap `depth` between particles of types a and b (radii ra,
  // rb) stores: negative for an engine whose contacts store none
  virtual double overlap_energy(int /*a*/, int /*b*/, double /*ra*/, double /*rb*/, double /*depth*/) const {
    return -1;
  }
  // What to look at when particles vanished from the engine between two intervals
  virtual std::string lost_particles_hint() const {
    return "Particles meant to leave through a gas outlet need it in coupling.yaml dem.outlets.";
  }
  // A warning when the start's deepest overlap (a fraction of d) is one the engine keeps as it
  // is rather than springs apart; "" for none
  virtual std::string kept_overlaps_warning(double /*deepest*/) const { return ""; }

  // The box the particles move in and, per axis and side (lower, upper), whether particles
  // crossing that face are dropped by the engine (LIGGGHTS boundary f); a face an outlet
  // opens (open_outlet) lets them through to be counted as leaving
  struct Box {
    double lower[3] = {0, 0, 0}, upper[3] = {0, 0, 0};
    bool drops[3][2] = {{false, false}, {false, false}, {false, false}};
  };
  virtual Box box() const = 0;
  virtual void open_outlet(int /*axis*/, int /*side*/) {}
};

}  // namespace tfdem

#endif
