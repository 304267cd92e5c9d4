// A third particle engine, for the test that an engine is its own file and one registration
// line (coupled.test_engine): free fall, each particle on its own under gravity and the fluid
// force the coupling holds, no contacts and no walls. One step per gas step, semi-implicit
// Euler: v += (g + F/m) dt, then x += v dt. dem.engine: free_fall, dem.particles: a LIGGGHTS
// data file.
#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "tfdem/data_file.h"
#include "tfdem/engine_registry.h"
#include "tfdem/particles.h"

namespace tfdem {
namespace {

struct FreeFallSettings : EngineSettings {
  std::string particles;
};

class FreeFall : public ParticleEngine {
 public:
  FreeFall(const std::string &file, const double gravity[3], const DemResume *resume) : g_{gravity[0], gravity[1], gravity[2]} {
    const std::string source = resume && !resume->restart_file.empty() ? resume->restart_file : file;
    std::ifstream in(source);
    if (!in) throw std::runtime_error("dem.particles: cannot read '" + source + "'");
    std::stringstream text;
    text << in.rdbuf();
    atoms_ = data_file::read_atoms(text.str(), source);
    for (std::size_t i = 0; i < atoms_.id.size(); ++i) {
      radius_.push_back(atoms_.diameter[i] / 2);
      mass_.push_back(atoms_.density[i] * sphere_volume(atoms_.diameter[i]));
    }
    force_.assign(atoms_.position.size(), 0.0);
    if (resume) step_ = resume->step, time_ = resume->time;
  }

  std::string name() const override { return "the free-fall test engine"; }
  std::string key() const override { return "free_fall"; }
  void advance(double dt, bool) override {
    for (std::size_t i = 0; i < atoms_.id.size(); ++i)
      for (int a = 0; a < 3; ++a) {
        atoms_.velocity[3 * i + a] += (g_[a] + force_[3 * i + a] / mass_[i]) * dt;
        atoms_.position[3 * i + a] += atoms_.velocity[3 * i + a] * dt;
      }
    ++step_;
    time_ += dt;
  }
  long long step() const override { return step_; }
  double time() const override { return time_; }
  std::size_t local_count() const override { return atoms_.id.size(); }
  long global_count() const override { return static_cast<long>(atoms_.id.size()); }
  const double *positions() const override { return atoms_.position.data(); }
  const double *velocities() const override { return atoms_.velocity.data(); }
  const double *radii() const override { return radius_.data(); }
  const double *masses() const override { return mass_.data(); }
  const int *tags() const override { return atoms_.id.data(); }
  const int *types() const override { return atoms_.type.data(); }
  int type_count() const override { return atoms_.type_count; }
  void set_fluid_force(const std::vector<double> &force) override { force_ = force; }
  void contact_sample(std::vector<double> &force, std::vector<int> &coordination) const override {
    force.assign(atoms_.position.size(), 0.0);
    coordination.assign(atoms_.id.size(), 0);
  }
  void remove_particles(const std::vector<int> &tags) override {
    if (!tags.empty()) throw std::runtime_error("the free-fall test engine removes no particles");
  }
  // The state as a LIGGGHTS data file (17 digits), which the engine starts from again
  bool write_restart(const std::string &path) override {
    std::ofstream out(path);
    out << std::setprecision(17) << "free fall restart\n\n" << atoms_.id.size() << " atoms\n" << atoms_.type_count
        << " atom types\n\n";
    for (int a = 0; a < 3; ++a) out << atoms_.lower[a] << " " << atoms_.upper[a] << " " << "xyz"[a] << "lo " << "xyz"[a] << "hi\n";
    out << "\nAtoms # granular\n\n";
    for (std::size_t i = 0; i < atoms_.id.size(); ++i)
      out << atoms_.id[i] << " " << atoms_.type[i] << " " << atoms_.diameter[i] << " " << atoms_.density[i] << " "
          << atoms_.position[3 * i] << " " << atoms_.position[3 * i + 1] << " " << atoms_.position[3 * i + 2] << "\n";
    out << "\nVelocities\n\n";
    for (std::size_t i = 0; i < atoms_.id.size(); ++i)
      out << atoms_.id[i] << " " << atoms_.velocity[3 * i] << " " << atoms_.velocity[3 * i + 1] << " "
          << atoms_.velocity[3 * i + 2] << " 0 0 0\n";
    return static_cast<bool>(out);
  }
  Box box() const override {
    Box b;
    for (int a = 0; a < 3; ++a) b.lower[a] = atoms_.lower[a], b.upper[a] = atoms_.upper[a];
    return b;
  }

 private:
  data_file::Atoms atoms_;
  std::vector<double> radius_, mass_, force_;
  double g_[3];
  long long step_ = 0;
  double time_ = 0;
};

std::shared_ptr<const EngineSettings> read_settings(ConfigSection &dem) {
  auto s = std::make_shared<FreeFallSettings>();
  s->particles = dem.text({"particles", "", "the particles' LIGGGHTS data file, relative to the case"}, "", true);
  return s;
}

std::unique_ptr<ParticleEngine> start(const EngineStart &start) {
  const auto &settings = static_cast<const FreeFallSettings &>(*start.config->engine_settings);
  return std::make_unique<FreeFall>(settings.particles, start.gravity, start.resume);
}

}  // namespace

TFDEM_ENGINE(free_fall, "a test engine: free fall under gravity and the fluid force, no contacts", read_settings, start);

}  // namespace tfdem
