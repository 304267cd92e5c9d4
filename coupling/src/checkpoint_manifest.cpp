#include "tfdem/checkpoint_manifest.h"

#include "tfdem/engine_registry.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace tfdem {
namespace {

std::string quoted(const std::string &text) { return "\"" + text + "\""; }

// The words of an entry's value: blank-separated, a double-quoted text one word.
std::vector<std::string> value_words(const std::string &value) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < value.size()) {
    if (value[i] == ' ' || value[i] == '\t') {
      ++i;
    } else if (value[i] == '"') {
      const std::size_t end = value.find('"', i + 1);
      if (end == std::string::npos) throw std::invalid_argument("unclosed quote");
      words.push_back(value.substr(i + 1, end - i - 1));
      i = end + 1;
    } else {
      const std::size_t end = value.find_first_of(" \t", i);
      words.push_back(value.substr(i, end == std::string::npos ? std::string::npos : end - i));
      i = end == std::string::npos ? value.size() : end;
    }
  }
  return words;
}

double real(const std::string &word) {
  std::size_t used = 0;
  const double v = std::stod(word, &used);
  if (used != word.size() || !std::isfinite(v)) throw std::invalid_argument("'" + word + "' is not a number");
  return v;
}

long long whole(const std::string &word) {
  std::size_t used = 0;
  const long long v = std::stoll(word, &used);
  if (used != word.size()) throw std::invalid_argument("'" + word + "' is not a whole number");
  return v;
}

bool yes_no(const std::string &word) {
  if (word == "true" || word == "on" || word == "yes") return true;
  if (word == "false" || word == "off" || word == "no") return false;
  throw std::invalid_argument("'" + word + "' is not true or false");
}

}  // namespace

std::string format_manifest(const CheckpointManifest &m) {
  std::ostringstream out;
  out.precision(17);
  out << "// TFDEM checkpoint: the DEM clock, the particle totals and every file of this time with\n"
      << "// its size and FNV-1a hash; written last, after the files were written and verified\n"
      << "time             " << m.time << ";\n"
      << "demRestart       " << (m.dem_restart ? "true" : "false") << ";\n"
      << "demStep          " << m.dem_step << ";\n"
      << "particles        " << m.particles << ";\n"
      << "particleMass     " << m.particle_mass << ";\n"
      << "removedParticles " << m.removed_particles << ";\n"
      << "removedMass      " << m.removed_mass << ";\n";
  if (!m.engine.empty()) out << "engine           " << m.engine << ";\n";
  out
      << "layout           " << m.layout << ";\n"
      << "ranks            " << m.ranks << ";\n"
      << "writeFormat      " << m.write_format << ";\n"
      << "writePrecision   " << m.write_precision << ";\n";
  for (const auto &f : m.files)
    out << "file             " << quoted(f.path) << " " << f.digest.size << " " << hex(f.digest.hash) << ";\n";
  for (const auto &o : m.outputs) out << "output           " << quoted(o.first) << " " << o.second << ";\n";
  return out.str();
}

CheckpointManifest parse_manifest(const std::string &text, const std::string &file) {
  CheckpointManifest m;
  std::istringstream in(text);
  int line_number = 0;
  bool has_time = false, has_step = false;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line.compare(start, 2, "//") == 0) continue;
    const std::string where = file + ":" + std::to_string(line_number) + ": ";
    const std::size_t end = line.find_last_not_of(" \t\r");
    if (line[end] != ';') throw std::invalid_argument(where + "the entry does not end with ';' (cut short?)");
    const std::string entry = line.substr(start, end - start);
    const std::size_t gap = entry.find_first_of(" \t");
    const std::string key = entry.substr(0, gap);
    try {
      const std::vector<std::string> w = value_words(gap == std::string::npos ? "" : entry.substr(gap));
      const auto need = [&w](std::size_t n) {
        if (w.size() != n) throw std::invalid_argument(std::to_string(w.size()) + " values where " + std::to_string(n) +
                                                       " belong");
      };
      if (key == "file") {
        need(3);
        m.files.push_back({w[0], {static_cast<std::uint64_t>(whole(w[1])), from_hex(w[2])}});
        continue;
      }
      if (key == "output") {
        need(2);
        m.outputs.emplace_back(w[0], static_cast<std::uint64_t>(whole(w[1])));
        continue;
      }
      need(1);
      if (key == "time") {
        m.time = real(w[0]);
        has_time = true;
      } else if (key == "demRestart") {
        m.dem_restart = yes_no(w[0]);
      } else if (key == "demStep") {
        m.dem_step = std::llround(real(w[0]));  // earlier markers wrote it as a number
        has_step = true;
      } else if (key == "particles") {
        m.particles = whole(w[0]);
      } else if (key == "particleMass") {
        m.particle_mass = real(w[0]);
      } else if (key == "removedParticles") {
        m.removed_particles = whole(w[0]);
      } else if (key == "removedMass") {
        m.removed_mass = real(w[0]);
      } else if (key == "engine") {
        m.engine = w[0];
      } else if (key == "layout") {
        m.layout = w[0];
      } else if (key == "ranks") {
        m.ranks = static_cast<int>(whole(w[0]));
      } else if (key == "writeFormat") {
        m.write_format = w[0];
      } else if (key == "writePrecision") {
        m.write_precision = static_cast<int>(whole(w[0]));
      } else {
        throw std::invalid_argument("unknown entry");
      }
    } catch (const std::invalid_argument &e) {
      throw std::invalid_argument(where + key + ": " + e.what());
    } catch (const std::out_of_range &) {
      throw std::invalid_argument(where + key + ": value out of range");
    }
  }
  if (!has_time || !has_step)
    throw std::invalid_argument(file + ": not a TFDEM checkpoint marker (no time and demStep entries; empty or " +
                                "cut short?)");
  return m;
}

std::vector<std::string> manifest_problems(const CheckpointManifest &m, double folder_time,
                                           const std::string &restart_path) {
  std::vector<std::string> problems;
  const auto refuse = [&problems](const std::string &entry, const std::string &value, const std::string &why) {
    problems.push_back(entry + ": " + value + ": " + why);
  };
  const auto text = [](double v) {
    std::ostringstream out;
    out.precision(17);
    out << v;
    return out.str();
  };
  if (std::abs(m.time - folder_time) > 1e-9 * std::max(1.0, std::abs(folder_time)))
    refuse("time", text(m.time), "not the time of its folder, " + text(folder_time) + " s");
  if (m.dem_step < 0) refuse("demStep", std::to_string(m.dem_step), "a step count cannot be negative");
  if (m.particles < 0) refuse("particles", std::to_string(m.particles), "a count cannot be negative");
  if (!(m.particle_mass >= 0)) refuse("particleMass", text(m.particle_mass), "a mass cannot be negative");
  if (m.particles == 0 && m.particle_mass != 0)
    refuse("particleMass", text(m.particle_mass), "no particles weigh nothing");
  if (m.particles > 0 && !(m.particle_mass > 0))
    refuse("particleMass", text(m.particle_mass), std::to_string(m.particles) + " particles weigh more");
  if (m.removed_particles < 0)
    refuse("removedParticles", std::to_string(m.removed_particles), "a count cannot be negative");
  if (!(m.removed_mass >= 0)) refuse("removedMass", text(m.removed_mass), "a mass cannot be negative");
  if (m.removed_particles == 0 && m.removed_mass != 0)
    refuse("removedMass", text(m.removed_mass), "no particles removed weigh nothing");
  if (!m.engine.empty() && !find_engine(m.engine)) {
    std::string names;
    for (const std::string &name : engine_names()) names += (names.empty() ? "" : " and ") + name;
    refuse("engine", m.engine, "the engines are " + names);
  }
  if (!m.legacy()) {
    bool listed = false;
    for (const auto &f : m.files) listed = listed || f.path == restart_path;
    if (m.dem_restart != listed)
      refuse("demRestart", m.dem_restart ? "true" : "false",
             std::string(listed ? "its files list" : "its files do not list") + " the DEM restart file " +
                 restart_path);
  }
  if (!m.dem_restart && m.particles > 0)
    refuse("demRestart", "false", "a bed of " + std::to_string(m.particles) +
                                      " particles resumes from its DEM restart file (none only for a bed emptied "
                                      "through its outlets)");
  if (!m.layout.empty() && m.layout != "serial" && m.layout != "whole" && m.layout != "split")
    refuse("layout", m.layout, "the gas layouts are serial, whole and split");
  if (m.ranks < 1) refuse("ranks", std::to_string(m.ranks), "a run has at least one rank");
  if (m.layout == "serial" && m.ranks != 1)
    refuse("ranks", std::to_string(m.ranks), "a serial run has one rank");
  if (!m.write_format.empty() && m.write_format != "ascii" && m.write_format != "binary")
    refuse("writeFormat", m.write_format, "OpenFOAM writes ascii or binary");
  if (!m.write_format.empty() && (m.write_precision < 1 || m.write_precision > 30))
    refuse("writePrecision", std::to_string(m.write_precision), "OpenFOAM writes 1 to 30 digits");
  return problems;
}

std::vector<std::string> changed_files(const CheckpointManifest &m, const std::string &root) {
  std::vector<std::string> changed;
  for (const auto &f : m.files) {
    const std::string path = root + "/" + f.path;
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) {
      changed.push_back(f.path + ": " + std::strerror(errno));
      continue;
    }
    if (static_cast<std::uint64_t>(st.st_size) != f.digest.size) {
      changed.push_back(f.path + ": " + std::to_string(st.st_size) + " bytes, written with " +
                        std::to_string(f.digest.size));
      continue;
    }
    try {
      if (digest_file(path).hash != f.digest.hash)
        changed.push_back(f.path + ": its content changed since it was written (same size, another hash)");
    } catch (const std::runtime_error &e) {
      changed.push_back(f.path + ": " + e.what());
    }
  }
  return changed;
}

}  // namespace tfdem
