// Checkpoint markers: a marker read back gives what was written; a marker of the earlier
// format reads as legacy; a damaged one names its line; files that differ from their digests
// (missing, cut short, changed in place) are named, an untouched one is not.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <string>
#include <vector>
#include <sys/stat.h>

#include "tfdem/checkpoint_manifest.h"

namespace {

using tfdem::CheckpointManifest;

std::string write(const std::string &root, const std::string &name, const std::string &content) {
  ::mkdir((root + "/0.1").c_str(), 0755);
  std::ofstream(root + "/" + name, std::ios::binary) << content;
  return name;
}

CheckpointManifest example() {
  CheckpointManifest m;
  m.time = 0.1;
  m.dem_restart = true;
  m.dem_step = 16000;
  m.particles = 4000;
  m.particle_mass = 0.08266431066911364;
  m.removed_particles = 2;
  m.removed_mass = 4.1e-5;
  m.layout = "split";
  m.ranks = 2;
  m.write_format = "ascii";
  m.write_precision = 17;
  m.files = {{"processor0/0.1/U", {1234, 0x85944171f73967e8ull}}, {"0.1/dem.restart", {99, 1}}};
  m.outputs = {{"mean_height.txt", 4096}};
  return m;
}

TEST(CheckpointManifest, ReadsBackWhatWasWritten) {
  const CheckpointManifest m = example();
  const CheckpointManifest back = tfdem::parse_manifest(tfdem::format_manifest(m), "0.1/tfdem.checkpoint");
  EXPECT_EQ(back.time, 0.1);
  EXPECT_TRUE(back.dem_restart);
  EXPECT_EQ(back.dem_step, 16000);
  EXPECT_EQ(back.particles, 4000);
  EXPECT_EQ(back.particle_mass, m.particle_mass);  // 17 digits: the same double
  EXPECT_EQ(back.removed_particles, 2);
  EXPECT_EQ(back.removed_mass, 4.1e-5);
  EXPECT_EQ(back.layout, "split");
  EXPECT_EQ(back.ranks, 2);
  EXPECT_EQ(back.write_precision, 17);
  ASSERT_EQ(back.files.size(), 2u);
  EXPECT_EQ(back.files[0].path, "processor0/0.1/U");
  EXPECT_EQ(back.files[0].digest, (tfdem::FileDigest{1234, 0x85944171f73967e8ull}));
  ASSERT_EQ(back.outputs.size(), 1u);
  EXPECT_EQ(back.outputs[0].first, "mean_height.txt");
  EXPECT_EQ(back.outputs[0].second, 4096u);
  EXPECT_FALSE(back.legacy());
}

TEST(CheckpointManifest, EarlierMarkerIsLegacy) {
  // as the coupler wrote markers before they listed files
  const std::string earlier =
      "// TFDEM checkpoint, written after the fields and dem.restart: a time without it is incomplete\n"
      "time             0.10000000000000001;\ndemRestart       true;\ndemStep          16000;\n"
      "particles        4000;\nparticleMass     0.082664310669113643;\nremovedParticles 0;\nremovedMass      0;\n";
  const CheckpointManifest m = tfdem::parse_manifest(earlier, "m");
  EXPECT_TRUE(m.legacy());
  EXPECT_EQ(m.dem_step, 16000);
  EXPECT_EQ(m.time, 0.1);
}

TEST(CheckpointManifest, DamagedMarkerNamesItsLine) {
  const std::string text = tfdem::format_manifest(example());
  const auto message = [](const std::string &t) {
    try {
      tfdem::parse_manifest(t, "0.1/tfdem.checkpoint");
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("").find("not a TFDEM checkpoint marker"), std::string::npos);
  EXPECT_NE(message(text.substr(0, text.find("demStep") + 12)).find("0.1/tfdem.checkpoint:5: the entry does not end"),
            std::string::npos);
  std::string flipped = text;
  flipped[flipped.find("16000")] = 'x';
  EXPECT_NE(message(flipped).find(":5: demStep:"), std::string::npos) << message(flipped);
  EXPECT_NE(message(text + "colour blue;\n").find("colour: unknown entry"), std::string::npos);
  EXPECT_NE(message(text + "file \"p\" 12;\n").find("file: 2 values where 3 belong"), std::string::npos);
}

TEST(CheckpointManifest, ChangedFilesAreNamed) {
  const std::string root = ::testing::TempDir() + "manifest_case";
  ::mkdir(root.c_str(), 0755);
  CheckpointManifest m;
  const std::string content = "foobar";
  for (const char *name : {"0.1/p", "0.1/U", "0.1/phi"}) {
    write(root, name, content);
    m.files.push_back({name, {6, 0x85944171f73967e8ull}});  // FNV-1a 64 of "foobar" (published)
  }
  m.files.push_back({"0.1/dem.restart", {6, 0x85944171f73967e8ull}});
  write(root, "0.1/U", "fooba");    // cut short
  write(root, "0.1/phi", "foobaR");  // changed in place
  const auto changed = tfdem::changed_files(m, root);
  ASSERT_EQ(changed.size(), 3u);
  EXPECT_EQ(changed[0], "0.1/U: 5 bytes, written with 6");
  EXPECT_EQ(changed[1], "0.1/phi: its content changed since it was written (same size, another hash)");
  EXPECT_EQ(changed[2], "0.1/dem.restart: No such file or directory");
}


// Entries that cannot be so, whatever the data: each named by its entry and value; a sound
// marker (the example, and its emptied-bed form without a restart file) has none.
std::vector<std::string> problems_of(const CheckpointManifest &m) {
  return tfdem::manifest_problems(m, 0.1, "0.1/dem.restart");
}

bool names(const std::vector<std::string> &problems, const std::string &start) {
  for (const std::string &p : problems)
    if (p.compare(0, start.size(), start) == 0) return true;
  return false;
}

TEST(CheckpointManifest, SoundMarkersHaveNoProblems) {
  EXPECT_TRUE(problems_of(example()).empty());
  CheckpointManifest emptied = example();
  emptied.dem_restart = false;
  emptied.particles = 0;
  emptied.particle_mass = 0;
  emptied.files.pop_back();  // no dem.restart listed
  EXPECT_TRUE(problems_of(emptied).empty());
  CheckpointManifest later = example();
  later.engine = "hard_sphere";
  later.time = 0.10000000000000007;  // a clock summed over steps, in the folder named 0.1
  EXPECT_TRUE(problems_of(later).empty());
}

TEST(CheckpointManifest, EditedEntriesAreNamed) {
  const auto edited = [](const std::function<void(CheckpointManifest &)> &edit) {
    CheckpointManifest m = example();
    edit(m);
    return problems_of(m);
  };
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.dem_restart = false; }), "demRestart: false"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.removed_particles = -3; }), "removedParticles: -3"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.removed_mass = -1e-5; }), "removedMass: -1"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.particles = -1; }), "particles: -1"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.particle_mass = 0; }), "particleMass: 0"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.dem_step = -5; }), "demStep: -5"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.time = 0.2; }), "time: 0.20000000000000001"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.engine = "lammps"; }), "engine: lammps"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.layout = "diagonal"; }), "layout: diagonal"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.ranks = 0; }), "ranks: 0"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.layout = "serial"; }), "ranks: 2"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.write_precision = 0; }), "writePrecision: 0"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) { m.removed_particles = 0; }), "removedMass: 4.1"));
  EXPECT_TRUE(names(edited([](CheckpointManifest &m) {
                      m.dem_restart = false;
                      m.files.pop_back();
                    }),
                    "demRestart: false: a bed of 4000 particles"));
}

TEST(CheckpointManifest, EngineEntryReadsBack) {
  CheckpointManifest m = example();
  m.engine = "hard_sphere";
  EXPECT_EQ(tfdem::parse_manifest(tfdem::format_manifest(m), "m").engine, "hard_sphere");
  EXPECT_EQ(tfdem::parse_manifest(tfdem::format_manifest(example()), "m").engine, "");
}

}  // namespace
