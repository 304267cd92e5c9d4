// tfdem-scene-check: the scene check of a case as a command.
//   tfdem-scene-check <coupling.yaml> --gas-velocity U --cell-size DX --kn K (--en E | --damping ETA)
//                     [--dt DT] [--wall-kn K --wall-en E] [--json]
// Gas, particles, drag law and coupling interval come from coupling.yaml; the rest from the
// options (SI units). Exit code 1 when the scene has errors, 2 on bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "liggghts_engine.h"
#include "tfdem/config.h"
#include "tfdem/contact.h"
#include "tfdem/scene_check.h"
#include "tfdem/suggest.h"

namespace {

const std::vector<std::string> kOptions = {"--gas-velocity", "--cell-size", "--kn",      "--en",
                                           "--damping",      "--dt",        "--wall-kn", "--wall-en",
                                           "--gas-step"};
const std::vector<std::string> kFlags = {"--json"};

const char *kUsage =
    "usage: tfdem-scene-check <coupling.yaml> --gas-velocity U --cell-size DX --kn K (--en E | --damping ETA)\n"
    "                         [--dt DT] [--wall-kn K --wall-en E] [--json]\n"
    "The dimensionless numbers of a gas-particle scene (St, Re_p, Ar, U_mf, terminal velocity,\n"
    "contact time, drag response time, cell/particle ratio) and what it needs: DEM step,\n"
    "coupling interval, void-fraction method. Gas, particles (the smallest size), drag law and\n"
    "coupling interval come from coupling.yaml; the rest from the options, SI units:\n"
    "  --gas-velocity U   characteristic (superficial inflow) gas velocity, m/s\n"
    "  --cell-size DX     smallest in-plane gas cell size, m\n"
    "  --kn K             particle-particle normal stiffness k_n, N/m\n"
    "  --en E             particle-particle normal restitution e_n in [0, 1) ...\n"
    "  --damping ETA      ... or its normal damping eta_n (absolute), N s/m\n"
    "  --dt DT            DEM time step, s (default: the recommended one)\n"
    "  --gas-step DT      gas step, s: the coupling interval when coupling.yaml leaves\n"
    "                     dem.coupling_interval out (deltaT / the DEM step)\n"
    "  --wall-kn K        particle-wall normal stiffness, N/m, with --wall-en: the wall contact's\n"
    "  --wall-en E        damping, contact time and step too (a wall has infinite mass)\n"
    "  --json             the numbers and findings as one JSON object (damping of the contacts\n"
    "                     included), for scripts\n"
    "Exit code: 0 fine, 1 the scene has errors, 2 bad input.\n";

int usage_error(const std::string &message) {
  std::fprintf(stderr, "tfdem-scene-check: %s\n%s", message.c_str(), kUsage);
  return 2;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string json_string(const std::string &text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// One contact's numbers: damping for e_n (seed 001 eq. 27), t_c (seed 000 eq. 26), the step rule.
struct ContactNumbers {
  double damping, restitution, contact_time, steps_per_contact, recommended_time_step;
};

ContactNumbers contact_numbers(double stiffness, double damping, double effective_mass) {
  ContactNumbers c;
  c.damping = damping;
  c.restitution = tfdem::contact::restitution_from_damping(stiffness, damping, effective_mass);
  c.contact_time = tfdem::contact::contact_time_from_damping(stiffness, damping, effective_mass);
  c.steps_per_contact = tfdem::recommended_steps_per_contact(c.restitution);
  c.recommended_time_step = c.contact_time / c.steps_per_contact;
  return c;
}

std::string contact_json(const ContactNumbers &c) {
  return "{\"damping\": " + json_number(c.damping) + ", \"restitution\": " + json_number(c.restitution) +
         ", \"contact_time\": " + json_number(c.contact_time) +
         ", \"steps_per_contact\": " + json_number(c.steps_per_contact) +
         ", \"recommended_time_step\": " + json_number(c.recommended_time_step) + "}";
}

std::string report_json(const tfdem::SceneReport &r, const tfdem::Scene &s, const ContactNumbers &pair,
                        const ContactNumbers *wall) {
  const tfdem::SceneNumbers &n = r.numbers;
  std::ostringstream o;
  o << "{\"relaxation_time\": " << json_number(n.relaxation_time) << ", \"stokes\": " << json_number(n.stokes)
    << ", \"reynolds\": " << json_number(n.reynolds) << ", \"archimedes\": " << json_number(n.archimedes)
    << ", \"minimum_fluidization\": " << json_number(n.minimum_fluidization)
    << ", \"terminal_velocity\": " << json_number(n.terminal_velocity)
    << ", \"dense_drag_time\": " << json_number(n.dense_drag_time)
    << ", \"coupling_time\": " << json_number(n.coupling_time)
    << ", \"cell_to_particle\": " << json_number(n.cell_to_particle)
    << ", \"dem_time_step\": " << json_number(s.dem_time_step) << ", \"pair\": " << contact_json(pair);
  if (wall) o << ", \"wall\": " << contact_json(*wall);
  o << ", \"findings\": [";
  for (std::size_t i = 0; i < r.findings.size(); ++i) {
    const auto &f = r.findings[i];
    const char *level = f.level == tfdem::Finding::Level::Ok       ? "ok"
                        : f.level == tfdem::Finding::Level::Advice ? "advice"
                                                                   : "error";
    o << (i ? ", " : "") << "{\"level\": \"" << level << "\", \"topic\": " << json_string(f.topic)
      << ", \"text\": " << json_string(f.text) << "}";
  }
  o << "]}\n";
  return o.str();
}

}  // namespace

int main(int argc, char **argv) {
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::printf("%s", kUsage);
    return 0;
  }
  if (argc < 2) return usage_error("missing coupling.yaml");
  std::map<std::string, double> values;
  std::set<std::string> flags;
  for (int i = 2; i < argc; ++i) {
    const std::string option = argv[i];
    if (std::find(kFlags.begin(), kFlags.end(), option) != kFlags.end()) {
      flags.insert(option);
      continue;
    }
    std::vector<std::string> known = kOptions;
    known.insert(known.end(), kFlags.begin(), kFlags.end());
    if (std::find(kOptions.begin(), kOptions.end(), option) == kOptions.end())
      return usage_error("unknown option '" + option + "'" + tfdem::did_you_mean(option, known));
    if (i + 1 >= argc) return usage_error("option '" + option + "' needs a value");
    char *end = nullptr;
    const double v = std::strtod(argv[i + 1], &end);
    if (end == argv[i + 1] || *end != '\0')
      return usage_error("option '" + option + "' needs a number, got '" + argv[i + 1] + "'");
    values[option] = v;
    ++i;
  }
  for (const char *option : {"--gas-velocity", "--cell-size", "--kn"})
    if (!values.count(option)) return usage_error(std::string("missing option ") + option);
  if (values.count("--en") == values.count("--damping"))
    return usage_error("give the particle-particle contact's restitution --en or its damping --damping (one of them)");
  if (values.count("--wall-kn") != values.count("--wall-en"))
    return usage_error("--wall-kn and --wall-en go together (the wall contact's stiffness and restitution)");
  for (const char *option : {"--en", "--wall-en"})
    if (values.count(option) && !(values[option] >= 0.0 && values[option] < 1.0))
      return usage_error(std::string("option ") + option + " is a restitution coefficient in [0, 1), got " +
                         std::to_string(values[option]) + " (1 would be a perfectly elastic contact with no damping)");
  for (const char *option : {"--gas-velocity", "--cell-size", "--kn", "--dt", "--wall-kn", "--gas-step"})
    if (values.count(option) && !(values[option] > 0.0))
      return usage_error(std::string("option ") + option + " must be > 0, got " + std::to_string(values[option]));
  try {
    const tfdem::CouplingConfig config = tfdem::load_coupling_config(argv[1]);
    tfdem::Scene scene;
    scene.particle_diameter = config.particle_diameters.front();  // smallest: shortest contact
    scene.particle_density = config.particle_density;
    scene.gas = config.gas;
    scene.drag_law = config.transfer.law;
    const auto *liggghts = dynamic_cast<const tfdem::LiggghtsSettings *>(config.engine_settings.get());
    scene.coupling_interval = liggghts ? liggghts->coupling_interval : 0;
    scene.gas_velocity = values["--gas-velocity"];
    scene.cell_size = values["--cell-size"];
    scene.normal_stiffness = values["--kn"];
    const double mass = tfdem::contact::sphere_mass(scene.particle_diameter, scene.particle_density);
    const double pair_mass = tfdem::contact::effective_mass(mass, mass);
    scene.normal_damping = values.count("--en")
                               ? tfdem::contact::normal_damping(scene.normal_stiffness, values["--en"], pair_mass)
                               : values["--damping"];
    const ContactNumbers pair = contact_numbers(scene.normal_stiffness, scene.normal_damping, pair_mass);
    ContactNumbers wall{};
    const bool has_wall = values.count("--wall-kn") > 0;
    if (has_wall)  // a wall: m_b infinite, m_ab = m (seed 001 eq. 16)
      wall = contact_numbers(values["--wall-kn"],
                             tfdem::contact::normal_damping(values["--wall-kn"], values["--wall-en"], mass), mass);
    double recommended = pair.recommended_time_step;
    if (has_wall) recommended = std::min(recommended, wall.recommended_time_step);
    scene.dem_time_step = values.count("--dt") ? values["--dt"] : recommended;
    if (values.count("--gas-step"))
      scene.coupling_interval = std::max(1L, std::lround(values["--gas-step"] / scene.dem_time_step));
    else if (scene.coupling_interval == 0)
      return usage_error(std::string(argv[1]) + " leaves dem.coupling_interval out (deltaT / the DEM step): give "
                         "--gas-step (system/controlDict deltaT)");
    const tfdem::SceneReport report = tfdem::check_scene(scene);
    if (flags.count("--json"))
      std::printf("%s", report_json(report, scene, pair, has_wall ? &wall : nullptr).c_str());
    else {
      std::printf("%s", tfdem::format_report(report).c_str());
      if (!values.count("--dt"))
        std::printf("(checked at the recommended DEM step %.4g s%s)\n", recommended,
                    has_wall ? ", the shorter of the particle and the wall contact's" : "");
      if (has_wall)
        std::printf("Wall contact: eta_n %.4g N s/m for e_n %.4g, t_c %.4g s, DEM step t_c/%.4g = %.4g s\n",
                    wall.damping, wall.restitution, wall.contact_time, wall.steps_per_contact,
                    wall.recommended_time_step);
    }
    return report.has_errors() ? 1 : 0;
  } catch (const tfdem::ConfigError &e) {
    std::fprintf(stderr, "tfdem-scene-check: %s\n", e.what());
  } catch (const std::exception &e) {
    std::fprintf(stderr, "tfdem-scene-check: %s\n", e.what());
  }
  return 2;
}
